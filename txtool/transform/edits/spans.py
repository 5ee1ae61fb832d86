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
from bisect import bisect_right
from collections.abc import Iterable, Iterator
from dataclasses import dataclass
from itertools import accumulate

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


class NotIndexed(KeyError):
    """A node asked for that the index was not built for."""


@dataclass(frozen=True)
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
_FEED = ord("\n")
_NONE, _CHILDREN, _DEEP = 0, 1, 2  # how far below an open element nodes are indexed


class SpanIndex:
    """The span of each node of ``within`` (elements of the tree of ``root``; by default the
    root) and of the nodes inside them, in ``data``, the bytes the tree was parsed from. The
    markup before them is only paired with the tree's nodes; the index holds the nodes it
    was built for (lxml keeps a node's proxy, and so its identity, while a reference to it
    lives)."""

    def __init__(self, data: bytes, root: etree._Element,
                 within: Iterable[etree._Element] | None = None, codec: str = "utf-8",
                 shallow: Iterable[etree._Element] = (),
                 near: set[etree._Element] | None = None) -> None:
        """``within``: the elements indexed with every node inside them; ``shallow``: elements
        indexed with their children alone (the places a change may add or remove children);
        ``near``: of the root's children, the only ones whose bounds a change may need (the
        rest are passed over: a robot's links and joints); None: all."""
        self.data = data
        self.codec = codec  # how names are stored (an ASCII-compatible encoding)
        self._spans: dict[etree._Element, Span] = {}
        wanted = {root} if within is None else set(within)
        scan = _Scan(self._spans, data, root, wanted, set(shallow), near, codec)
        scan.run()
        if scan.open or not self._spans and root in wanted | scan.outline:
            raise SpanError("the bytes end before the tree does")

    def __getitem__(self, node: etree._Element) -> Span:
        try:
            return self._spans[node]
        except KeyError:
            raise NotIndexed(f"<{etree.QName(node).localname}> was not indexed") from None

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
    turn, paired with the next node of the tree (see :class:`SpanIndex` for ``wanted``,
    ``outline`` and ``near``)."""

    def __init__(self, spans: dict[etree._Element, Span], data: bytes, root: etree._Element,
                 wanted: set[etree._Element], outline: set[etree._Element],
                 near: set[etree._Element] | None, codec: str) -> None:
        self.spans, self.data, self.root, self.codec = spans, data, root, codec
        self.wanted, self.outline, self.near = wanted, outline, near
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
        self.cdata = b"<![CDATA[" in data
        self.jumps = None if near is None else _Jumps(
            data, root, near | self.way | wanted | outline, codec)

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
                if self.jumps is not None and len(self.open) == 1:
                    landed = self._jump(node, token)
                    if landed is None:
                        return  # at the root's end tag
                    node, token = landed
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

    def _jump(self, node: etree._Element, token: re.Match[bytes]
              ) -> tuple[etree._Element, re.Match[bytes]] | None:
        """At ``node``, a child of the root whose start tag is ``token``: the child to read
        and its start tag, past those nothing asks about (:class:`_Jumps`); None where the
        scan went on to the root's end tag and closed the root."""
        landing = self.jumps.past(node)  # type: ignore[union-attr]
        if landing is None:
            return node, token
        landed, token, self.line, self.counted = landing
        if landed is None:  # no child after it is asked about: at the root's end tag
            closed, _ = self.open.pop()
            if closed is not None:
                closed.tail_start, closed.end = token.span()
            return None
        self.children[0] = landed.itersiblings()
        self.tokens = _MARKUP.finditer(self.data, token.end())
        return landed, token

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
        elif reach and (self.near is None or len(self.open) > 1 or node in self.near):
            # A child a change may keep, not look into: its bounds are all that is read.
            span = self.spans[node] = _bounds(token, node, self.codec)
        if not element or empty:
            return not self.open
        below = _DEEP if deep else _CHILDREN if node in self.outline else _NONE
        if below == _NONE and self.open and node not in self.way:
            # Nothing inside is indexed: passed over to its end tag.
            closing, self.tokens = _pass_over(token, self.tokens, data, self.cdata)
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


def _outside_instructions(data: bytes, at: int) -> bool:
    """Whether ``at`` stands in no processing instruction: none closes after it, or the last
    to open before it closes before it. (A comment cannot hold the root's last ``</``: what
    follows it in the comment would end in a ``-->`` that nothing after the root can open.)"""
    if data.find(b"?>", at) < 0:
        return True  # none ends after it: it is in none
    start = data.rfind(b"<?", 0, at)
    return start < 0 or data.find(b"?>", start + 2, at) >= 0


class _Jumps:
    """Where the scan can go straight from a child of the root that nothing asks about to
    the next one something does (``wanted``), by the line the parser gives it: a robot's
    thousands of links and joints are then not read at all. A landing is taken only where it
    cannot be wrong: the node before it in the document ends on an earlier line, and on its
    own line only spaces and end tags come before its start tag, which ends on that line."""

    def __init__(self, data: bytes, root: etree._Element, wanted: set[etree._Element],
                 codec: str = "utf-8") -> None:
        self.data = data
        self.codec = codec
        self.root_name = root.tag.rpartition("}")[2]
        # The children asked about, and their lines in order: a child after another starts
        # on the same line or a later one (no step over the root's children to tell where
        # each stands among them: lxml walks them one by one).
        self.asked = {node for node in wanted if node.getparent() is root}
        self.on_line: dict[int, list[etree._Element]] = {}
        for node in self.asked:
            self.on_line.setdefault(node.sourceline or 0, []).append(node)
        self.lines = sorted(self.on_line)
        self.lines_known = 0 not in self.on_line  # else no child is jumped to
        self._refused = -1  # the line a landing was refused at (not tried again)
        self._starts: list[int] | None = None
        self._last_line = (0, 1)  # the start of the line last landed on, and its line
        self._end: re.Match[bytes] | None | bool = False  # the root's end tag; False: not sought

    def past(self, node: etree._Element
             ) -> tuple[etree._Element | None, re.Match[bytes], int, int] | None:
        """For ``node``, the child of the root the scan has just taken: None to read it, or
        the next child asked about, its start tag, its line and where that line starts (the
        scan goes on with the children after it); where none is, None for the child, and the
        root's end tag (the scan ends there; the lines are not counted). A child asked about
        on the line of ``node`` is read to; where the line of one is not known, every child
        is."""
        line = node.sourceline
        if node in self.asked or not line or not self.lines_known:
            return None
        following = bisect_right(self.lines, line)
        if following and self.lines[following - 1] == line:
            return None
        if following == len(self.lines):
            end = self._root_end()
            return None if end is None else (None, end, 0, 0)
        target = self.lines[following]
        if target == self._refused:
            return None
        for candidate in self.on_line[target]:  # the first on its line lands, if one does
            landing = self._landing(candidate, candidate.getprevious())
            if landing is not None:
                return candidate, *landing
        self._refused = target
        return None

    def _root_end(self) -> re.Match[bytes] | None:
        """The root's end tag: the document's last ``</``, where it is an end tag of the
        root's name that only comments, instructions and spaces follow, and no instruction
        before it could hold it (else None, and the scan reads on)."""
        if self._end is False:
            self._end = None
            data = self.data
            at = data.rfind(b"</")
            token = _MARKUP.match(data, at) if at >= 0 else None
            if token is not None and _MISC.fullmatch(data, token.end()) is not None and (
                    _outside_instructions(data, at)
                    and token.group(0)[2:-1].strip().rpartition(b":")[2].decode(
                        self.codec, "replace") == self.root_name):
                self._end = token
        return self._end

    def _line_start(self, line: int) -> int | None:
        """Where line ``line`` starts (None: the document has fewer lines)."""
        data = self.data
        if b"\r" in data:  # a bare CR ends a line too: every line's start is listed
            if self._starts is None:
                self._starts = [0, *accumulate(map(len, data.splitlines(keepends=True)))]
            return self._starts[line - 1] if line <= len(self._starts) else None
        # Line feeds alone: halving the range after the line before's start, each byte is
        # counted about once.
        at, counted = self._last_line
        if line < counted:
            at, counted = 0, 1
        need, low, high = line - counted, at, len(data)
        while need and low < high:  # the line starts after the need-th line feed from low
            middle = (low + high) // 2
            feeds = data.count(b"\n", low, middle)
            if feeds >= need:
                high = middle
            else:
                need -= feeds
                low = middle
            if high - low == 1:
                low, need = high, 0
        if need or low and data[low - 1] != _FEED:
            return None  # fewer lines than that
        self._last_line = low, line
        return low

    def _landing(self, node: etree._Element, previous: etree._Element
                 ) -> tuple[re.Match[bytes], int, int] | None:
        line = node.sourceline
        last = previous
        while last.tag.__class__ is str and len(last):
            last = last[-1]
        if line is None or last.sourceline is None or last.sourceline >= line:
            return None
        start = self._line_start(line)
        if start is None:
            return None
        gap = _GAP.match(self.data, start)
        token = _MARKUP.match(self.data, gap.end()) if gap is not None else None
        if token is None or self.data[token.start() + 1] == _SLASH:
            return None
        name = token.group("name")
        if node.tag.__class__ is str:
            if name is None or name.rpartition(b":")[2].decode("utf-8", "replace") != (
                    node.tag.rpartition("}")[2]):
                return None
        elif name is not None:
            return None
        if _lines(self.data, start, token.end()):
            return None  # it ends on a later line: not the node's start tag
        return token, line, start


_GAP = re.compile(rb"(?:[ \t\r\n]+|</[^>]*>)*")
_MISC = re.compile(rb"(?:[ \t\r\n]+|<!--.*?-->|<\?.*?\?>)*", re.S)  # what may follow the root
_END_TAGS: dict[bytes, re.Pattern[bytes]] = {}


def _pass_over(token: re.Match[bytes], tokens: Iterator[re.Match[bytes]], data: bytes,
               cdata: bool) -> tuple[tuple[int, int], Iterator[re.Match[bytes]]]:
    """Read past the element whose start tag is ``token`` (just read) in ``tokens``: where
    its end tag starts and ends, and the tokens after it. The first end tag of its name ends
    it where nothing between can hide or nest one (no start tag of the same name, comment or
    instruction between, and ``cdata`` false: no CDATA section in the document); else every
    token is read. The nodes inside are not paired: one out of step with the tree shows at
    the next node indexed, or at the end."""
    if not cdata:
        name = token.group("name")
        end_tag = _END_TAGS.get(name)
        if end_tag is None:
            end_tag = _END_TAGS[name] = re.compile(b"</" + re.escape(name) + rb"\s*>")
        end = end_tag.search(data, token.end())
        if end is not None:
            inside = token.end(), end.start()
            if data.find(b"<!--", *inside) < 0 and data.find(b"<?", *inside) < 0 and (
                    _nests(data, name, *inside) is False):
                return end.span(), _MARKUP.finditer(data, end.end())
    depth = 1
    for token in tokens:
        at = token.start()
        kind = data[at + 1]
        if kind == _SLASH:
            depth -= 1
            if not depth:
                return (at, token.end()), tokens
        elif kind not in (_BANG, _QUESTION) and data[token.end() - 2] != _SLASH:
            depth += 1
    raise SpanError("an element the bytes do not end")


def _nests(data: bytes, name: bytes, start: int, end: int) -> bool:
    """Whether a start tag of ``name`` may stand in ``data[start:end]``."""
    at = data.find(b"<" + name, start, end)
    while at >= 0:
        if data[at + 1 + len(name):at + 2 + len(name)] in (b" ", b"\t", b"\r", b"\n", b"/",
                                                           b">"):
            return True
        at = data.find(b"<" + name, at + 1, end)
    return False


def _bounds(token: re.Match[bytes], node: etree._Element, codec: str) -> Span:
    """Where ``node`` starts, and where its start tag ends (its end, until its end tag is
    read); its name checked, not its line."""
    name = token.group("name")
    if name is not None and name.rpartition(b":")[2].decode(
            codec, "replace") != node.tag.rpartition("}")[2]:
        raise SpanError(f"byte {token.start()}: the bytes do not hold the tree's {node.tag!r}")
    return Span(token.start(), token.end())


def _span(token: re.Match[bytes], node: etree._Element, line: int, codec: str) -> Span:
    start, end = token.span()
    name = token.group("name")
    if name is not None and name.rpartition(b":")[2].decode(
            codec, "replace") != node.tag.rpartition("}")[2] or node.sourceline not in (
            None, line):
        raise SpanError(f"line {line}: the bytes do not hold the tree's {node.tag!r} here")
    if name is None:
        return Span(start, end)
    empty = token.start("empty") != token.end("empty")
    return Span(start, end, empty, token.end("name"), token.end("attributes"),
                token.start("empty") if empty else end - 1)
