"""Where each node of a parsed document is written in its bytes: the span index edits address.

lxml keeps a line per node (``sourceline``, the line where its start tag, comment or
instruction ends) but no byte offset. A small scanner reads the markup of the bytes the tree
was parsed from, one token after the other (comments, CDATA sections, instructions, the
DOCTYPE, start and end tags; text is skipped), and pairs the nodes inside the root with the
root's nodes in document order: each pair must be of the same kind and name and end on the
parser's line, or the index is refused (:class:`SpanError`). Each token is matched once from
where the last one ended, so the index costs time linear in the document; only the nodes
asked for are paired in full (their name and line checked, their attributes read).

The bytes are those edits address (:class:`txtool.transform.edits.core.EditedText`): the original,
or the UTF-8 form of a UTF-16 or UTF-32 document.
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Iterator
from dataclasses import dataclass

from lxml import etree

_MARKUP = re.compile(
    rb"""<!--.*?-->
    |<!\[CDATA\[.*?\]\]>
    |<\?.*?\?>
    |<!DOCTYPE(?:[^\[>"']|"[^"]*"|'[^']*')*(?:\[(?:<!--.*?-->|"[^"]*"|'[^']*'|[^\]"'])*\]\s*)?>
    |</[^>]*>
    |<(?P<name>[^\s/>]+)(?P<attributes>(?:\s+[^\s=/>]+\s*=\s*(?:"[^"]*"|'[^']*'))*)\s*(?P<empty>/?)>
    """, re.S | re.X)
_ATTRIBUTE = re.compile(rb"""(\s+)([^\s=/>]+)\s*=\s*(?:"([^"]*)"|'([^']*)')""")


class SpanError(ValueError):
    """The bytes do not read as the tree says (they are not what it was parsed from)."""


@dataclass(frozen=True, slots=True)
class Attribute:
    """An attribute as written: ``lead`` is where the whitespace before its name starts,
    ``[value_start, value_end)`` its value between the quotes ``quote``."""

    lead: int
    name_start: int
    value_start: int
    value_end: int
    quote: bytes

    @property
    def end(self) -> int:
        """After the closing quote."""
        return self.value_end + 1


class Span:
    """A node as written: ``[start, end)`` all of it; for an element, ``head_end`` is after its
    start tag and ``tail_start`` where its end tag starts (both ``end`` for ``<x/>``, which
    ``empty`` says), ``close`` where the ``>`` or ``/>`` of the start tag starts, after the
    attributes (``[name_end, attributes_end)``) and the spaces after them."""

    __slots__ = ("start", "end", "head_end", "tail_start", "empty", "name_end", "attributes_end",
                 "close")

    def __init__(self, start: int, end: int, empty: bool = False, name_end: int = 0,
                 attributes_end: int = 0, close: int = 0) -> None:
        self.start, self.end, self.head_end, self.tail_start = start, end, end, end
        self.empty, self.name_end, self.attributes_end, self.close = (
            empty, name_end, attributes_end, close)


_SLASH, _BANG, _QUESTION = b"/!?"
_NONE, _CHILDREN, _DEEP = 0, 1, 2  # how far below an open element nodes are indexed


class SpanIndex:
    """The span of each node of ``within`` (elements of the tree of ``root``; by default the
    root) and of the nodes inside them, in ``data``, the bytes the tree was parsed from. The
    markup before them is only paired with the tree's nodes; the index holds the nodes it
    was built for (lxml keeps a node's proxy, and so its identity, while a reference to it
    lives)."""

    def __init__(self, data: bytes, root: etree._Element,
                 within: Iterable[etree._Element] | None = None, codec: str = "utf-8",
                 shallow: Iterable[etree._Element] = ()) -> None:
        """``within``: the elements indexed with every node inside them; ``shallow``: elements
        indexed with their children alone (the places a change may add or remove children)."""
        self.data = data
        self.codec = codec  # how names are stored (an ASCII-compatible encoding)
        self._spans: dict[etree._Element, Span] = {}
        wanted = {root} if within is None else set(within)
        scan = _Scan(self._spans, data, root, wanted, set(shallow), codec)
        scan.run()
        if scan.open or not self._spans and root in wanted | scan.outline:
            raise SpanError("the bytes end before the tree does")

    def __getitem__(self, node: etree._Element) -> Span:
        return self._spans[node]

    def __contains__(self, node: etree._Element) -> bool:
        return node in self._spans

    def attributes(self, node: etree._Element) -> dict[bytes, Attribute]:
        """The attributes of element ``node`` as written, by their written names."""
        span = self._spans[node]
        attributes = {}
        for found in _ATTRIBUTE.finditer(self.data, span.name_end, span.attributes_end):
            quoted = 3 if found.group(3) is not None else 4
            attributes[found.group(2)] = Attribute(
                found.start(1), found.start(2), found.start(quoted), found.end(quoted),
                b'"' if quoted == 3 else b"'")
        return attributes


class _Scan:
    """The scan that builds a :class:`SpanIndex` into ``spans``: each token of the markup, in
    turn, paired with the next node of the tree (see :class:`SpanIndex` for ``wanted`` and
    ``outline``)."""

    def __init__(self, spans: dict[etree._Element, Span], data: bytes, root: etree._Element,
                 wanted: set[etree._Element], outline: set[etree._Element], codec: str
                 ) -> None:
        self.spans, self.data, self.root, self.codec = spans, data, root, codec
        self.wanted, self.outline = wanted, outline
        self.way: set[etree._Element] = set()  # the ancestors of what is indexed
        for node in wanted | outline:
            for ancestor in node.iterancestors():
                if ancestor in self.way:
                    break
                self.way.add(ancestor)
        # For each element open where the scan is: its span where it is indexed (else None),
        # how far down its descendants are (_DEEP: all; _CHILDREN: its children alone), and
        # its children still to be read.
        self.open: list[tuple[Span | None, int]] = []
        self.children: list[Iterator[etree._Element]] = []
        self.line, self.counted = 1, 0  # the line at byte ``counted``
        self.tokens = _MARKUP.finditer(data)

    def run(self) -> None:
        """Read the tokens up to the root's end tag (or the end of the bytes)."""
        data = self.data
        while (token := next(self.tokens, None)) is not None:
            at = token.start()
            kind = data[at + 1]
            if kind == _SLASH:
                if self._close(token):
                    return  # the root's end tag
                continue
            if kind == _BANG and not data.startswith(b"<!--", at):
                continue  # text (a CDATA section), or the DOCTYPE
            if not self.open:
                if kind in (_BANG, _QUESTION):
                    continue  # before the root
                node = self.root
            else:
                node = next(self.children[-1], None)
                if node is None:
                    raise SpanError(f"byte {at}: a node the tree does not have")
            if self._enter(node, token):
                return  # the root, written <root/>

    def _close(self, token: re.Match[bytes]) -> bool:
        """The end tag ``token`` closes the element open last; whether it is the root's."""
        closed, _ = self.open.pop()
        if next(self.children.pop(), None) is not None:
            raise SpanError(f"byte {token.start()}: the tree has nodes the bytes do not")
        if closed is not None:
            closed.tail_start, closed.end = token.start(), token.end()
        return not self.open

    def _enter(self, node: etree._Element, token: re.Match[bytes]) -> bool:
        """Pair ``node`` with ``token``, its start tag (or comment, or instruction): index it
        as far as asked, then go into it or past it; whether it was the root, written
        ``<root/>``."""
        data, at = self.data, token.start()
        kind = data[at + 1]
        element = kind not in (_BANG, _QUESTION)
        if element is not (node.tag.__class__ is str):
            raise SpanError(f"byte {at}: the tree has a {node.tag!r} here")
        empty = element and data[token.end() - 2] == _SLASH
        reach = self.open[-1][1] if self.open else _NONE
        span = None
        deep = reach == _DEEP or node in self.wanted
        if deep or node in self.outline:
            self.line += _lines(data, self.counted, token.end())
            self.counted = token.end()
            span = self.spans[node] = _span(token, node, self.line, self.codec)
        elif reach:
            # A child a change may keep, not look into: its bounds are all that is read.
            span = self.spans[node] = _bounds(token, node, self.codec)
        if not element or empty:
            return not self.open
        below = _DEEP if deep else _CHILDREN if node in self.outline else _NONE
        if below == _NONE and self.open and node not in self.way:
            # Nothing inside is indexed: passed over to its end tag.
            closing = _pass_over(self.tokens, data)
            if span is not None:
                span.tail_start, span.end = closing
            return False
        self.open.append((span, below))
        self.children.append(iter(node))
        return False


def _lines(data: bytes, start: int, end: int) -> int:
    """Line breaks in ``data[start:end]`` as the parser counts them (a bare CR is one too)."""
    feeds = data.count(b"\n", start, end)
    returns = data.count(b"\r", start, end)
    return feeds + returns - data.count(b"\r\n", start, end) if returns else feeds


def _pass_over(tokens: Iterator[re.Match[bytes]], data: bytes) -> tuple[int, int]:
    """Read past the element whose start tag was just read from ``tokens``: where its end tag
    starts and ends. The nodes inside are not paired: one out of step with the tree shows at
    the next node indexed, or at the end."""
    depth = 1
    for token in tokens:
        at = token.start()
        kind = data[at + 1]
        if kind == _SLASH:
            depth -= 1
            if not depth:
                return at, token.end()
        elif kind not in (_BANG, _QUESTION) and data[token.end() - 2] != _SLASH:
            depth += 1
    raise SpanError("an element the bytes do not end")


def _bounds(token: re.Match[bytes], node: etree._Element, codec: str) -> Span:
    """Where ``node`` starts, and where its start tag ends (its end, until its end tag is
    read); its name checked, not its line."""
    if not _named(token, node, codec):
        raise SpanError(f"byte {token.start()}: the bytes do not hold the tree's {node.tag!r}")
    return Span(token.start(), token.end())


def _named(token: re.Match[bytes], node: etree._Element, codec: str) -> bool:
    """Whether ``token`` (a start tag, or a comment or instruction) names ``node``'s tag."""
    name = token.group("name")
    return name is None or name.rpartition(b":")[2].decode(
        codec, "replace") == node.tag.rpartition("}")[2]


# libxml2 keeps a node's line exactly below 65,535; past it, the line it reports may be one
# off (2.14: the line after a start tag), so there the kind and name alone are paired.
_EXACT_LINES = 65_535


def _span(token: re.Match[bytes], node: etree._Element, line: int, codec: str) -> Span:
    start, end = token.span()
    if not _named(token, node, codec) or node.sourceline not in (None, line) and (
            line < _EXACT_LINES):
        raise SpanError(f"line {line}: the bytes do not hold the tree's {node.tag!r} here")
    if token.group("name") is None:
        return Span(start, end)
    empty = token.start("empty") != token.end("empty")
    return Span(start, end, empty, token.end("name"), token.end("attributes"),
                token.start("empty") if empty else end - 1)
