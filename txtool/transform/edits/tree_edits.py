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

import hashlib
import re
import zlib
from collections.abc import Iterable
from dataclasses import dataclass
from itertools import pairwise
from operator import attrgetter

from lxml import etree

from txtool.io.xmlio import InputError, attributes, parse_bytes
from txtool.transform.edits.core import Edit, EditedText
from txtool.transform.edits.spans import Attribute, Span, SpanIndex

_TAIL = attrgetter("tail")


class NotEditable(ValueError):
    """A change the edits cannot say without writing more than it changed (a new attribute
    or element in a namespace the document declares elsewhere)."""


@dataclass(frozen=True, slots=True)
class _Before:
    attributes: dict[str, str]
    text: str | None
    children: list[etree._Element]
    tails: list[str | None]
    tag: str


class TreeChange:
    """The state of ``elements`` and their descendants before a change, to tell the edits
    that write it (:meth:`edits`)."""

    def __init__(self, elements: Iterable[etree._Element],
                 containers: Iterable[etree._Element] = ()) -> None:
        """``elements``: recorded with all their descendants; ``containers``: recorded
        alone (their attributes, text and children), for a change that adds, removes or
        replaces their children but changes nothing inside the children it keeps. The roots
        of the change are the containers that are no descendant of another, and the elements
        that are in none of them."""
        self._before: dict[etree._Element, _Before] = {}
        for element in containers:
            self._record(element)
        outer = set(self._before)
        self.roots = [e for e in outer if not any(a in outer for a in e.iterancestors())]
        for root in elements:
            for element in root.iter("*"):
                self._record(element)
            if root not in outer and not any(a in outer for a in root.iterancestors()):
                self.roots.append(root)
        # Nodes written as given bytes rather than as lxml writes them (by :meth:`substitute`).
        self._substitutes: dict[etree._Element, bytes] = {}
        self._redeclare = False

    def _record(self, element: etree._Element) -> None:
        children = element[:]
        self._before[element] = _Before(attributes(element), element.text, children,
                                        list(map(_TAIL, children)), element.tag)

    def substitute(self, node: etree._Element, markup: bytes) -> None:
        """Write ``node`` (a node the change puts in) as ``markup``, bytes of the document,
        instead of as lxml writes it; its tail is written as usual."""
        self._substitutes[node] = markup

    def edits(self, text: EditedText, index: SpanIndex, *, redeclare: bool = False
              ) -> list[Edit]:
        """The edits of ``text.data`` (which ``index`` reads) that write the change.
        ``redeclare``: a new node may declare a namespace its place declares already (a
        redundant declaration, which no reader sees) rather than be refused
        (:class:`NotEditable`)."""
        self._redeclare = redeclare
        edits: list[Edit] = []
        for root in self.roots:
            self._element(root, text, index, edits)
        return edits

    def written(self, text: EditedText, index: SpanIndex) -> list[Edit]:
        """:meth:`edits`, where a new node may declare a namespace only if it must
        (:class:`NotEditable` where even that cannot say the change)."""
        try:
            return self.edits(text, index)
        except NotEditable:
            return self.edits(text, index, redeclare=True)

    def _element(self, element: etree._Element, text: EditedText, index: SpanIndex,
                 edits: list[Edit]) -> None:
        before, span = self._before[element], index[element]
        if element.tag != before.tag:
            raise NotEditable(f"<{etree.QName(element).localname}> changed its name")
        edits.extend(_attribute_edits(element, index, before.attributes, text, self._redeclare))
        children = element[:]
        tails = list(map(_TAIL, children))
        if (children, tails, element.text) == (before.children, before.tails, before.text):
            for child in filter(self._before.__contains__, children):
                self._element(child, text, index, edits)
            return
        if span.empty:
            name = index.data[span.start + 1:span.name_end]
            edits.append(Edit(span.attributes_end, span.end, text.encode(
                ">" + _escaped(element.text)) + self._nodes(children, text) + b"</" + name
                + b">"))
            return
        if not children and not element.text:
            # Emptied by the change: written as lxml writes an empty element, <x/>.
            edits.append(Edit(span.close, span.end, b"/>"))
            return
        was_at = {child: place for place, child in enumerate(before.children)}
        # Each kept child: where it stands, and where it stood before.
        kept = [(place, was_at[child]) for place, child in enumerate(children)
                if child in was_at]
        if any(old >= later for (_, old), (_, later) in pairwise(kept)):
            kept = []  # reordered: all of the content is written anew
        self._regions(element, span, children, tails, kept, text, index, edits)
        for child in filter(self._before.__contains__, (children[place] for place, _ in kept)):
            self._element(child, text, index, edits)

    def _regions(self, element: etree._Element, span: Span, children: list[etree._Element],
                 tails: list[str | None], kept: list[tuple[int, int]],
                 text: EditedText, index: SpanIndex, edits: list[Edit]) -> None:
        """An edit for each run of content between two kept children (or the start or end
        of the element) that the change made differ: a node put in or taken out there, or
        the text before the run's first node (``kept``: where each kept child stands among
        ``children`` and stood before)."""
        before = self._before[element]
        for place, next_place in _changed_runs(
                kept, tails, before.tails, element.text != before.text,
                len(children), len(before.children)):
            lead = element.text if place < 0 else tails[place]
            # Only the bounds of a run that changed are read (the index may hold no more).
            start = index[children[place]].end if place >= 0 else span.head_end
            end = index[children[next_place]].start if next_place < len(children) else (
                span.tail_start)
            written = text.encode(_escaped(lead)) + self._nodes(
                children[place + 1:next_place], text)
            edit = _trimmed(index.data, start, end, written)
            if edit.start < edit.end or edit.content:
                edits.append(edit)

    def _nodes(self, nodes: list[etree._Element], text: EditedText) -> bytes:
        """``nodes`` and their tails as bytes of the document."""
        written = []
        for node in nodes:
            markup = self._substitutes.get(node)
            if markup is None:
                written.append(text.encode(_written(node, self._redeclare)))
            else:
                written.append(markup + text.encode(_escaped(node.tail)))
        return b"".join(written)


def _changed_runs(kept: list[tuple[int, int]], tails: list[str | None],
                  tails_before: list[str | None], text_changed: bool, size: int,
                  size_before: int) -> list[tuple[int, int]]:
    """The runs of content between two kept children that differ, as the places of their
    bounds among the children (-1: the element's start; ``size``, ``size_before``: its end,
    now and before): a node put in or taken out between them, or the text before the run
    (the tail of the kept child it starts at, or the element's text) changed."""
    bounds = [(-1, -1), *kept, (size, size_before)]
    runs = []
    for (start, was), (end, was_end) in pairwise(bounds):
        retold = text_changed if start < 0 else tails[start] != tails_before[was]
        if end - start != 1 or was_end - was != 1 or retold:
            runs.append((start, end))
    return runs


def _prefixed_name(element: etree._Element, key: str) -> str | None:
    """``{namespace}name`` as ``prefix:name`` with a prefix in scope at ``element``."""
    namespace, _, name = key[1:].partition("}")
    prefix = next((p for p, uri in element.nsmap.items() if uri == namespace and p), None)
    return None if prefix is None else f"{prefix}:{name}"


def _attribute_edits(element: etree._Element, index: SpanIndex, before: dict[str, str],
                     text: EditedText, redeclare: bool = False) -> list[Edit]:
    after = attributes(element)
    if after == before:
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
    # A new attribute goes after the one the tree puts before it, or last where none of the
    # attributes written comes after it in the tree.
    keys = list(after)
    last_kept = max((i for i, key in enumerate(keys) if key in before), default=-1)
    at = span.name_end
    for position, key in enumerate(keys):
        value = after[key]
        if key in before:
            at = written[_written_name(element, key, written)].end
            continue
        if position > last_kept:
            at = span.attributes_end
        name = key
        if key.startswith("{"):  # its prefix may be declared nowhere in the document
            name = _prefixed_name(element, key) if redeclare else None
            if name is None:
                raise NotEditable(f"a new attribute {key} in a namespace")
        edits.append(Edit.insertion(at, text.encode(
            f' {name}="{_attribute_value(value, chr(34))}"')))
    return edits


def _written_name(element: etree._Element, key: str, written: dict[bytes, Attribute]) -> bytes:
    """The name of attribute ``key`` of ``element`` as the document writes it."""
    if not key.startswith("{"):
        return key.encode("utf-8")
    namespace, _, name = key[1:].partition("}")
    return next(spelled for prefix, uri in element.nsmap.items() if uri == namespace and (
        spelled := f"{prefix}:{name}".encode()) in written)


def _trimmed(data: bytes, start: int, end: int, written: bytes) -> Edit:
    """The edit of ``[start, end)`` to ``written`` without the bytes both begin or end with."""
    old = memoryview(data)[start:end]  # (no copy: a run may hold thousands of elements)
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
    if bool(edit.content) == (edit.start != edit.end):  # a replacement, or no change
        return edit
    moved = edit.content or memoryview(data)[edit.start:edit.end]
    at, size = edit.start, len(moved)
    while at > bound and data[at - 1:at] not in (b"\n", b"\r"):
        if data[at - 1] != moved[size - 1 - (edit.start - at) % size]:
            return edit
        at -= 1
    shift = edit.start - at
    if not shift or data[at - 1:at] not in (b"\n", b"\r"):
        return edit
    if not edit.content:
        return Edit(at, at + (edit.end - edit.start), b"")
    rotated = moved[size - shift % size:] + moved[:size - shift % size]
    return Edit(at, at + (edit.end - edit.start), rotated)


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


def _written(node: etree._Element, redeclare: bool = False) -> str:
    """A node the change put here, and its tail, as lxml writes it: without the namespace
    declarations lxml repeats from its new parent's scope (a copied node takes them along),
    as the document declares them there already; ``redeclare``: with them, where one cannot
    go (a declaration no reader sees)."""
    markup = etree.tostring(node, encoding=str, with_tail=False)
    if "xmlns" in markup:
        parent = node.getparent()
        scope = parent.nsmap if parent is not None else {}
        head_end = markup.index(">")

        def redundant(found: re.Match[str]) -> bool:
            uri = found.group(2) if found.group(2) is not None else found.group(3)
            return scope.get(found.group(1)) == uri

        kept = [found for found in _DECLARATION.finditer(markup, 0, head_end)
                if not redundant(found)]
        if (kept or "xmlns" in markup[head_end:]) and not redeclare:
            raise NotEditable(f"<{etree.QName(node).localname}> would declare a namespace")
        markup = _DECLARATION.sub(lambda found: "" if redundant(found) else found.group(0),
                                  markup[:head_end]) + markup[head_end:]
    return markup + _escaped(node.tail)


def canonical(tree: etree._ElementTree) -> bytes:
    """The form two documents are compared in to tell whether bytes read as a tree: its
    exclusive canonical XML, comments kept (about twice as fast as the inclusive form on a
    large robot). Element and attribute names are compared with their namespaces, texts,
    comments and instructions as they are; a namespace declaration that no name uses is not
    compared: no loader reads one (tinyxml2 and urdfdom read no namespaces, xacro reads
    prefixes)."""
    return etree.tostring(tree, method="c14n", exclusive=True)


def reads_as_serialized(read: etree._ElementTree, written: Serialized, path: str) -> bool:
    """Whether ``read``, parsed from bytes written for a tree kept only as its
    :func:`serialization` ``written`` (whose memory the parse of ``read`` could then reuse),
    holds the document that tree holds. lxml writes a tree, parsed or changed, as the
    document it holds, so the same serialization is the same document: that is compared
    first, by digest, in a third of the time of a canonical form. Where the two differ (a
    namespace declared on another element than where it is used, an empty text written as
    ``<a></a>`` where a parse reads ``<a/>``; quotes and spaces in tags never differ, lxml
    writes both), the canonical form (:func:`canonical`) of the serialization parsed decides
    (parsed again, it has the tree's canonical form)."""
    if _Sink(pack=False).of(read).digest == written.digest:
        return True
    try:
        tree = parse_bytes(zlib.decompress(written.packed), path, limit=None)
    except InputError:
        return False
    return canonical(read) == canonical(tree)


@dataclass(frozen=True, slots=True)
class Serialized:
    """A document as lxml writes it (UTF-8, no XML declaration), held small: the digest of
    its bytes, and the bytes compressed for the comparison that parses them
    (:func:`reads_as_serialized`)."""

    digest: bytes
    packed: bytes


def serialization(tree: etree._ElementTree) -> Serialized:
    """A document as lxml writes it: what :func:`reads_as_serialized` compares first. Made as
    lxml writes it out, piece by piece: the text of a large document is never held whole
    (twice, as bytes and as a string), while the changed tree and its written bytes are."""
    return _Sink(pack=True).of(tree)


class _Sink:
    """Where lxml writes a document (a file object: its ``write``), taken as a digest and,
    with ``pack``, compressed."""

    def __init__(self, pack: bool) -> None:
        self.hash = hashlib.sha256()
        self.packer = zlib.compressobj(1) if pack else None
        self.parts: list[bytes] = []

    def write(self, piece: bytes) -> None:
        self.hash.update(piece)
        if self.packer is not None:
            self.parts.append(self.packer.compress(piece))

    def of(self, tree: etree._ElementTree) -> Serialized:
        tree.write(self, encoding="utf-8")
        if self.packer is not None:
            self.parts.append(self.packer.flush())
        return Serialized(self.hash.digest(), b"".join(self.parts))
