"""What a change made to parsed elements is, as edits of the bytes they were parsed from.

A fix (``txtool migrate``) changes the tree in place: it renames or drops an attribute,
changes a text, inserts, moves or removes an element. :class:`TreeChange` records what the
elements it may touch held before (their attributes, text, children and each child's tail);
afterwards it compares and says each difference as an edit of the span it stood in
(:mod:`.spans`): an attribute's value or the attribute with the space before it, or the run of
content between two children the change kept, written anew from the tree. A node the change
did not touch is never written: it keeps its bytes because no edit covers them.
"""

from __future__ import annotations

import re
from collections.abc import Iterable
from dataclasses import dataclass

from lxml import etree

from txtool.io.xmlio import InputError, parse_bytes
from txtool.transform.edits import Edit, EditedText
from txtool.transform.spans import Attribute, Span, SpanIndex


class NotEditable(ValueError):
    """A change the edits cannot say without writing more than it changed (a new attribute
    or element in a namespace the document declares elsewhere)."""


@dataclass(frozen=True)
class _Before:
    attributes: dict[str, str]
    text: str | None
    children: list[etree._Element]
    tails: list[str | None]


class TreeChange:
    """The state of ``elements`` and their descendants before a change, to tell the edits
    that write it (:meth:`edits`)."""

    def __init__(self, elements: Iterable[etree._Element]) -> None:
        self.roots = list(elements)
        self._before: dict[etree._Element, _Before] = {}
        for root in self.roots:
            for element in root.iter("*"):
                children = list(element)
                self._before[element] = _Before(dict(element.attrib), element.text, children,
                                                [child.tail for child in children])

    def edits(self, text: EditedText, index: SpanIndex) -> list[Edit]:
        """The edits of ``text.data`` (which ``index`` reads) that write the change."""
        edits: list[Edit] = []
        for root in self.roots:
            self._element(root, text, index, edits)
        return edits

    def _element(self, element: etree._Element, text: EditedText, index: SpanIndex,
                 edits: list[Edit]) -> None:
        before, span = self._before[element], index[element]
        edits.extend(_attribute_edits(element, index, before.attributes, text))
        children = list(element)
        tails = [child.tail for child in children]
        if (children, tails, element.text) == (before.children, before.tails, before.text):
            for child in children:
                if child in self._before:
                    self._element(child, text, index, edits)
            return
        if span.empty:
            name = index.data[span.start + 1:span.start + 1 + _name_length(index.data, span)]
            content = _escaped(element.text) + "".join(map(_written, children))
            edits.append(Edit(span.attributes_end, span.end, text.encode(
                ">" + content) + b"</" + name + b">"))
            return
        kept = [child for child in children if child in before.children]
        order = [before.children.index(child) for child in kept]
        if order != sorted(order):
            kept = []  # reordered: all of the content is written anew
        self._regions(element, span, kept, text, index, edits)
        for child in kept:
            if child.tag.__class__ is str:
                self._element(child, text, index, edits)

    def _regions(self, element: etree._Element, span: Span, kept: list[etree._Element],
                 text: EditedText, index: SpanIndex, edits: list[Edit]) -> None:
        """An edit for each run of content between two kept children (or the start or end
        of the element) that the change made differ."""
        before = self._before[element]
        children = list(element)
        bounds = [span.head_end, *(x for child in kept for x in (index[child].start,
                                                                   index[child].end)),
                  span.tail_start]
        leads = [(element.text, before.text), *((child.tail, before.tails[
            before.children.index(child)]) for child in kept)]
        places = [children.index(child) for child in kept]
        old_places = [before.children.index(child) for child in kept]
        firsts = [0, *(place + 1 for place in places)]
        lasts = [*places, len(children)]
        old_firsts = [0, *(place + 1 for place in old_places)]
        old_lasts = [*old_places, len(before.children)]
        for region, (lead, old_lead) in enumerate(leads):
            new_nodes = children[firsts[region]:lasts[region]]
            old_nodes = before.children[old_firsts[region]:old_lasts[region]]
            if lead == old_lead and not new_nodes and not old_nodes:
                continue
            start, end = bounds[2 * region], bounds[2 * region + 1]
            written = text.encode(_escaped(lead) + "".join(map(_written, new_nodes)))
            edit = _trimmed(index.data, start, end, written)
            if edit.start < edit.end or edit.content:
                edits.append(edit)


def _attribute_edits(element: etree._Element, index: SpanIndex, before: dict[str, str],
                     text: EditedText) -> list[Edit]:
    after = element.attrib
    if len(after) == len(before) and all(before.get(k) == v for k, v in after.items()):
        return []
    written = index.attributes(element)
    span = index[element]
    edits = []
    for key, value in before.items():
        place = written[_written_name(element, key, written)]
        if key not in after:
            edits.append(Edit.deletion(place.lead, place.end))
        elif after[key] != value:
            edits.append(Edit.replacement(place.value_start, place.value_end, text.encode(
                _attribute_value(after[key], place.quote.decode()))))
    for key, value in after.items():
        if key not in before:
            if key.startswith("{"):  # its prefix may be declared nowhere in the document
                raise NotEditable(f"a new attribute {key} in a namespace")
            edits.append(Edit.insertion(span.attributes_end, text.encode(
                f' {key}="{_attribute_value(value, chr(34))}"')))
    return edits


def _written_name(element: etree._Element, key: str, written: dict[bytes, Attribute]) -> bytes:
    """The name of attribute ``key`` of ``element`` as the document writes it."""
    if not key.startswith("{"):
        return key.encode("utf-8")
    namespace, _, name = key[1:].partition("}")
    return next(spelled for prefix, uri in element.nsmap.items() if uri == namespace and (
        spelled := f"{prefix}:{name}".encode()) in written)


def _name_length(data: bytes, span: Span) -> int:
    end = span.start + 1
    while data[end:end + 1] not in (b"", b" ", b"\t", b"\r", b"\n", b"/", b">"):
        end += 1
    return end - span.start - 1


def _trimmed(data: bytes, start: int, end: int, written: bytes) -> Edit:
    """The edit of ``[start, end)`` to ``written`` without the bytes both begin or end with."""
    old = data[start:end]
    head = 0
    most = min(len(old), len(written))
    while head < most and old[head] == written[head]:
        head += 1
    tail = 0
    while tail < most - head and old[-1 - tail] == written[-1 - tail]:
        tail += 1
    return _at_line_start(data, start, Edit(start + head, end - tail,
                                            written[head:len(written) - tail]))


def _at_line_start(data: bytes, bound: int, edit: Edit) -> Edit:
    """An insertion or a deletion moved back to the start of its line where the bytes it
    passes over repeat its own (the same result, said as whole lines: ``  <x/>\n`` rather
    than ``<x/>\n  ``), not before ``bound``."""
    moved = edit.content or data[edit.start:edit.end]
    if not moved or edit.content and edit.start != edit.end:
        return edit
    at, size = edit.start, len(moved)
    while at > bound and data[at - 1:at] not in (b"\n", b"\r"):
        if data[at - 1] != moved[size - 1 - (edit.start - at) % size]:
            return edit
        at -= 1
    shift = edit.start - at
    if not shift or data[at - 1:at] not in (b"\n", b"\r"):
        return edit
    rotated = moved[size - shift % size:] + moved[:size - shift % size]
    return Edit(at, at + (edit.end - edit.start), rotated if edit.content else b"")


def _escaped(value: str | None) -> str:
    """A text or tail as lxml writes it."""
    if not value:
        return ""
    return (value.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")
            .replace("\r", "&#13;"))


def _attribute_value(value: str, quote: str) -> str:
    value = _escaped(value).replace("\n", "&#10;").replace("\t", "&#9;")
    return value.replace(quote, "&quot;" if quote == '"' else "&apos;")


_DECLARATION = re.compile(r"""\sxmlns(?::([^\s=]+))?\s*=\s*(?:"([^"]*)"|'([^']*)')""")


def _written(node: etree._Element) -> str:
    """A node the change put here, and its tail, as lxml writes it: without the namespace
    declarations lxml repeats from its new parent's scope (a copied node takes them along),
    as the document declares them there already."""
    markup = etree.tostring(node, encoding=str, with_tail=False)
    if "xmlns" in markup:
        parent = node.getparent()
        scope = parent.nsmap if parent is not None else {}
        head_end = markup.index(">")
        kept = [found for found in _DECLARATION.finditer(markup, 0, head_end)
                if scope.get(found.group(1)) != (found.group(2) if found.group(2) is not None
                                                 else found.group(3))]
        if kept or "xmlns" in markup[head_end:]:
            raise NotEditable(f"<{etree.QName(node).localname}> would declare a namespace")
        markup = _DECLARATION.sub("", markup[:head_end]) + markup[head_end:]
    return markup + _escaped(node.tail)


def reads_as(data: bytes, tree: etree._ElementTree, path: str) -> bool:
    """Whether ``data`` parses to the document ``tree`` holds (canonical forms compared): the
    check of bytes written by edits."""
    try:
        written = parse_bytes(data, path, limit=None)
    except InputError:
        return False
    return etree.tostring(written, method="c14n") == etree.tostring(tree, method="c14n")
