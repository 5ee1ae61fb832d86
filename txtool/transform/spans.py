"""Where each node of a parsed document is written in its bytes: the span index edits address.

lxml keeps a line per node (``sourceline``, the line where its start tag, comment or
instruction ends) but no byte offset. A small scanner reads the markup of the bytes the tree
was parsed from, one token after the other (comments, CDATA sections, instructions, the
DOCTYPE, start and end tags; text is skipped), and pairs the nodes inside the root with the
root's nodes in document order: each pair must be of the same kind and name and end on the
parser's line, or the index is refused (:class:`SpanError`). Each token is matched once from
where the last one ended, so the index costs time linear in the document.

The bytes are those edits address (:class:`txtool.transform.edits.EditedText`): the original,
or the UTF-8 form of a UTF-16 or UTF-32 document.
"""

from __future__ import annotations

import re
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


@dataclass
class Span:
    """A node as written: ``[start, end)`` all of it; for an element, ``head_end`` is after its
    start tag and ``tail_start`` where its end tag starts (both ``end`` for ``<x/>``, which
    ``empty`` says), ``close`` where the ``>`` or ``/>`` of the start tag starts (after the
    last attribute and the spaces after it: ``attributes_end``)."""

    start: int
    end: int
    head_end: int
    tail_start: int
    empty: bool = False
    attributes_end: int = 0
    close: int = 0
    attributes: dict[bytes, Attribute] | None = None


class SpanIndex:
    """The span of each node inside ``root`` (the root included) in ``data``, the bytes it was
    parsed from; the index holds the nodes it was built for (lxml keeps a node's proxy, and so
    its identity, while a reference to it lives)."""

    def __init__(self, data: bytes, root: etree._Element) -> None:
        self.data = data
        self._spans: dict[etree._Element, Span] = {}
        nodes = root.iter()
        open_spans: list[Span] = []
        line, counted = 1, 0
        at = data.find(b"<")
        started = False
        while at >= 0:
            token = _MARKUP.match(data, at)
            if token is None:
                raise SpanError(f"byte {at}: no markup the scanner reads")
            end = token.end()
            kind = data[at + 1:at + 2]
            at = data.find(b"<", end)
            if kind == b"/":
                if open_spans:
                    closed = open_spans.pop()
                    closed.tail_start, closed.end = token.start(), end
                    if not open_spans:
                        break
                continue
            if data.startswith(b"<![CDATA[", token.start()) or kind == b"!" and not data.startswith(
                    b"<!--", token.start()):
                continue  # text, or the DOCTYPE
            if not started and kind in (b"!", b"?"):
                continue  # before the root
            started = True
            node = next(nodes, None)
            if node is None:
                raise SpanError(f"byte {token.start()}: a node the tree does not have")
            line += _lines(data, counted, end)
            counted = end
            span = _span(token, node, line)
            self._spans[node] = span
            if kind not in (b"!", b"?") and not span.empty:
                open_spans.append(span)
            elif not open_spans:
                break  # the root, written <root/>
        if open_spans or next(nodes, None) is not None:
            raise SpanError("the tree has nodes the bytes do not")

    def __getitem__(self, node: etree._Element) -> Span:
        return self._spans[node]

    def __contains__(self, node: etree._Element) -> bool:
        return node in self._spans


def _lines(data: bytes, start: int, end: int) -> int:
    """Line breaks in ``data[start:end]`` as the parser counts them (a bare CR is one too)."""
    feeds = data.count(b"\n", start, end)
    returns = data.count(b"\r", start, end)
    return feeds + returns - data.count(b"\r\n", start, end) if returns else feeds


def _span(token: re.Match[bytes], node: etree._Element, line: int) -> Span:
    tag = node.tag
    start, end = token.span()
    name = token.group("name")
    if tag is etree.Comment:
        written = token.group(0).startswith(b"<!--")
    elif tag is etree.ProcessingInstruction:
        written = token.group(0).startswith(b"<?")
    else:
        written = name is not None and name.rpartition(b":")[2].decode(
            "utf-8", "replace") == tag.rpartition("}")[2]
    if not written or node.sourceline not in (None, line):
        raise SpanError(f"line {line}: the bytes do not hold the tree's {tag!r} here")
    if name is None:
        return Span(start, end, end, end)
    attributes = {}
    tag_text = token.group(0)
    for found in _ATTRIBUTE.finditer(tag_text, len(name) + 1, token.end("attributes") - start):
        quoted = 3 if found.group(3) is not None else 4
        attributes[found.group(2)] = Attribute(
            start + found.start(1), start + found.start(2), start + found.start(quoted),
            start + found.end(quoted), b'"' if quoted == 3 else b"'")
    empty = bool(token.group("empty"))
    close = token.start("empty") if empty else end - 1
    return Span(start, end, end, end, empty, token.end("attributes"), close, attributes)
