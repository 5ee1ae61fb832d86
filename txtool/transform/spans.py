"""Where each node of a parsed document is written in its bytes: the span index edits address.

lxml keeps a line per node (``sourceline``, the line where its start tag, comment or
instruction ends) but no byte offset. A small scanner reads the markup of the bytes the tree
was parsed from, one token after the other (comments, CDATA sections, instructions, the
DOCTYPE, start and end tags; text is skipped), and pairs the nodes inside the root with the
root's nodes in document order: each pair must be of the same kind and name and end on the
parser's line, or the index is refused (:class:`SpanError`). Each token is matched once from
where the last one ended, so the index costs time linear in the document; only the nodes
asked for are paired in full (their name and line checked, their attributes read).

The bytes are those edits address (:class:`txtool.transform.edits.EditedText`): the original,
or the UTF-8 form of a UTF-16 or UTF-32 document.
"""

from __future__ import annotations

import re
from collections.abc import Iterable
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


class SpanIndex:
    """The span of each node of ``within`` (elements of the tree of ``root``; by default the
    root) and of the nodes inside them, in ``data``, the bytes the tree was parsed from. The
    markup before them is only paired with the tree's nodes; the index holds the nodes it
    was built for (lxml keeps a node's proxy, and so its identity, while a reference to it
    lives)."""

    def __init__(self, data: bytes, root: etree._Element,
                 within: Iterable[etree._Element] | None = None, codec: str = "utf-8") -> None:
        self.data = data
        self.codec = codec  # how names are stored (an ASCII-compatible encoding)
        self._spans: dict[etree._Element, Span] = {}
        wanted = {root} if within is None else set(within)
        nodes = root.iter()
        open_spans: list[Span] = []  # the elements of ``wanted`` open where the scan is
        depth = 0
        line, counted = 1, 0
        started = False
        for token in _MARKUP.finditer(data):
            at = token.start()
            kind = data[at + 1]
            if kind == _SLASH:
                if open_spans:  # inside an indexed element, every element is indexed
                    closed = open_spans.pop()
                    closed.tail_start, closed.end = at, token.end()
                depth -= 1
                if not depth:
                    break  # the root's end tag
                continue
            if kind == _BANG and not data.startswith(b"<!--", at):
                continue  # text (a CDATA section), or the DOCTYPE
            if not started and kind in (_BANG, _QUESTION):
                continue  # before the root
            started = True
            node = next(nodes, None)
            if node is None:
                raise SpanError(f"byte {at}: a node the tree does not have")
            element = kind not in (_BANG, _QUESTION)
            if element is not (node.tag.__class__ is str):
                raise SpanError(f"byte {at}: the tree has a {node.tag!r} here")
            empty = element and data[token.end() - 2] == _SLASH
            if open_spans or node in wanted:
                line += _lines(data, counted, token.end())
                counted = token.end()
                span = self._spans[node] = _span(token, node, line, codec)
                if element and not empty:
                    open_spans.append(span)
            if element and not empty:
                depth += 1
            elif not depth:
                break  # the root, written <root/>
        if depth or next(nodes, None) is not None:
            raise SpanError("the tree has nodes the bytes do not")

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


def _lines(data: bytes, start: int, end: int) -> int:
    """Line breaks in ``data[start:end]`` as the parser counts them (a bare CR is one too)."""
    feeds = data.count(b"\n", start, end)
    returns = data.count(b"\r", start, end)
    return feeds + returns - data.count(b"\r\n", start, end) if returns else feeds


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
