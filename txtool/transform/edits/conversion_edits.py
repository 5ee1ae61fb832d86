"""A conversion said as edits of the bytes it read.

A conversion changes the parsed tree: the placer (:mod:`txtool.transform.placement.placer`) replaces
transmissions, cuts them out, wraps them in a ``<ros2_control>`` of their own, moves them into or
out of a block, and restyles a Proposal 1 transmission's roles in place. :class:`ConversionEdits`
records, before any of that, the elements whose children a conversion may change (each
transmission's ancestors, and each ``<ros2_control>`` of the document with its parent) and the
transmissions themselves in full; afterwards :meth:`ConversionEdits.edits` says the change as edits
of their spans (:mod:`.tree_edits`, :mod:`.spans`), the one applier
(:func:`txtool.transform.edits.core.apply_edits`) makes the bytes, and :func:`check_written`
parses them and holds them to the converted tree: the whole document, or, for a robot whose
transmissions come after its links and joints, what follows the first child of the root the
change recorded, the bytes before it held to the input's (:class:`Window`).

Two kinds of node are written as bytes rather than as lxml writes them: the block generated
for a whole robot, whose transmissions are text already
(:mod:`txtool.transform.repeated.block_text`: its marker is filled in inside the edit that
writes the block), and a transmission going back to ROS 1 whose original ``--reversible``
carried (:mod:`txtool.transform.reversible`): written as its original bytes.
"""

from __future__ import annotations

import hashlib
import itertools
import re
from dataclasses import dataclass

from lxml import etree

from txtool.dialects.read import detect_dialect
from txtool.io.encodings import SCANNABLE, utf8_form
from txtool.io.xmlio import InputError, local, parse_bytes
from txtool.model.core import kind_of
from txtool.transform.edits.core import Edit, EditedText
from txtool.transform.edits.declaration import late_declaration
from txtool.transform.edits.spans import SpanError, SpanIndex
from txtool.transform.edits.tree_edits import (
    NotEditable,
    TreeChange,
    canonical,
    reads_as_serialized,
    serialization,
)
from txtool.transform.repeated.block_text import fill


class ConversionEdits:
    """The document ``data`` whose tree (root ``root``) a conversion is about to change."""

    def __init__(self, path: str, data: bytes, root: etree._Element,
                 transmissions: list[etree._Element], at_root: list[etree._Element],
                 target: str, *, near: bool = True) -> None:
        """``at_root``: those of ``transmissions`` that are children of ``root``
        (:func:`txtool.dialects.read.transmissions_with_those_at_root`). ``near``: of the root's
        children, index the bounds of those next to a transmission or a ``<ros2_control>``
        alone (the places the placer changes the root's children); false: all of them
        (:class:`.spans.NotIndexed` said one was missing)."""
        self.path = path
        self.text = EditedText(data)
        containers: set[etree._Element] = {root}
        if len(at_root) < len(transmissions):
            for element in transmissions:
                if element.getparent() in containers:
                    continue  # (the common case, without an iterator)
                for ancestor in element.iterancestors():
                    if ancestor in containers:
                        break
                    containers.add(ancestor)
        ros1_alone = _ros1_alone(self.text)
        if not ros1_alone:
            for component in root.iter("{*}ros2_control"):
                containers.add(component)
                containers.update(component.iterancestors())
        inside = _changed_inside(transmissions, target, ros1_alone)
        first = _first_recorded(root, at_root, containers) if near else None
        # First: the index reuses its proxies.
        self.change = TreeChange(inside, containers, None if first is None else {root: first})
        bounded = _near(root, self.change.children_before(root), at_root, containers,
                        _replaced(root, transmissions, target, inside, ros1_alone,
                                  self.text.data)
                        ) if near else None
        self.first = first  # where the check may start reading (see :meth:`expect`)
        try:
            self.index = SpanIndex(self.text.data, root, inside, self.text.codec,
                                   shallow=containers, near=bounded)
        except SpanError as exc:
            raise InputError(f"{path}: cannot convert: the bytes do not read as parsed "
                             f"({exc})") from None
        self.marked: tuple[int, Edit, bytes] | None = None  # see :class:`Expected`

    def substitute(self, node: etree._Element, block: bytes) -> None:
        """Write ``node`` as ``block``, the whole lines a transmission stood on (the
        indentation of its first line and its last line ending left to the tree's layout)."""
        markup = block.lstrip(b" \t")
        self.change.substitute(node, markup[:len(markup.rstrip(b"\r\n"))])

    def edits(self, marker: etree._Comment | None = None,
              pieces: list[bytes] | None = None) -> list[Edit] | None:
        """The edits that write the converted tree, with the text ``pieces`` in place of the
        comment ``marker`` where one was placed; None where the marker cannot be filled in
        (the caller parses the text into the tree and asks again)."""
        try:
            edits = self.change.written(self.text, self.index)
        except NotEditable as exc:
            raise InputError(f"{self.path}: cannot convert: {exc}") from None
        self.marked = None
        if marker is not None:
            assert pieces is not None
            newline = self.text.newline.encode("ascii")
            if newline != b"\n":  # the pieces are ASCII, laid out with line feeds
                pieces = [piece.replace(b"\n", newline) for piece in pieces]
            filled = _filled(edits, marker, pieces)
            if filled is None:
                return None
            edits, (place, unfilled) = filled
            self.marked = place, unfilled, f"<!--{marker.text}-->".encode("ascii")
        late = late_declaration(self.text.data) if edits else None
        if late is not None:
            edits.append(late)
        return edits

    def applied(self, edits: list[Edit]) -> bytes:
        """The document with ``edits`` made, stored as the original was."""
        return self.text.applied(edits)

    def expect(self, tree: etree._ElementTree, edits: list[Edit]) -> Expected:
        """What :func:`check_written` holds the bytes that ``edits`` (the last :meth:`edits`)
        write to: ``tree``, the converted document. Where no edit reaches the root's first
        child recorded (:class:`.tree_edits.TreeChange` passed over those before it, a
        robot's links and joints), the bytes are read from that child on, after the root's
        start tag (:class:`Window`); else the whole document is, held to ``tree``'s
        serialization (the tree can go before the bytes are parsed, and the parse reuse its
        memory). A block written as text stands in ``tree`` as its marker comment, and in
        what is parsed too: each of its transmissions is read back on its own by the
        conversion's check (:mod:`txtool.transform.repeated.block_text`)."""
        root = tree.getroot()
        first = self._first_indexed(root)
        if first is not None:
            start = self.index[first].start
            if all(edit.start >= start for edit in edits):
                return Expected("", self.marked, Window(self.index[root].head_end, start,
                                                        root, first, self.text.data))
        return Expected(serialization(tree), self.marked)

    def _first_indexed(self, root: etree._Element) -> etree._Element | None:
        """Of the root's children from the first recorded on, the first the index holds the
        bounds of, where it is still a child of the root (the index passes over those it
        cannot tell the bounds of from their lines, a link and a joint on one line)."""
        first = self.first
        if first is None or first.getparent() is not root:
            return None
        siblings = itertools.chain([first], first.itersiblings())
        return next((node for node in itertools.islice(siblings, 2 * _AROUND + 2)
                     if node in self.index), None)


@dataclass(frozen=True)
class Window:
    """Where the check of a conversion reads the written bytes: those up to ``head_end``
    (the end of the root's start tag) and from ``start`` (where the root's first child
    recorded, ``first``, starts) on. The bytes before ``start`` must be those of the input,
    ``original`` (a robot's links and joints, which no edit reached), compared as bytes: they
    parsed, and the conversion changes nothing there. ``root``: the converted document's
    root, whose children from ``first`` on, and the nodes after it, what is read must
    match."""

    head_end: int
    start: int
    root: etree._Element
    first: etree._Element
    original: bytes


@dataclass(frozen=True)
class Expected:
    """A converted document as lxml writes it (:func:`.tree_edits.serialization`), or the
    part of it a :class:`Window` reads; and where a block was written as text, the place of
    the edit that holds it among the edits, that edit with the block's marker in place of
    its text, and the marker as written."""

    text: str
    marked: tuple[int, Edit, bytes] | None = None
    window: Window | None = None


def check_written(data: bytes, edits: list[Edit], path: str, expected: Expected) -> None:
    """Refuse (:class:`InputError`) the bytes ``data`` that ``edits`` wrote where they do not
    parse to the converted document (:meth:`ConversionEdits.expect`). Where a block was
    written as text, what is parsed is ``data`` with the block's marker back in place of
    the block's text (the tree holds the marker; the block's transmissions are read back on
    their own)."""
    data = utf8_form(data)  # what the edits addressed (UTF-16 and UTF-32 stored back)
    if expected.marked is not None:
        data = _marked(data, edits, *expected.marked)
    if expected.window is not None:
        if _reads_as_window(data, path, expected.window):
            return
        # Not as the window tells: the whole document decides.
        expected = Expected(serialization(expected.window.root.getroottree()))
    try:
        written = parse_bytes(data, path, limit=None)
    except InputError as exc:
        raise InputError(f"{path}: cannot convert: what the edits write does not read "
                         f"back ({exc})") from None
    if not reads_as_serialized(written, expected.text, path):
        got = _digest(canonical(written))
        raise InputError(f"{path}: cannot convert: what the edits write does not read as the "
                         f"converted document (read back {got[:6].hex()}); please report "
                         "this file")


def _reads_as_window(data: bytes, path: str, window: Window) -> bool:
    """Whether ``data``, read as its :class:`Window` tells, is the input up to the window
    and then holds the converted root's start tag, its children from the first recorded on
    and the nodes after it, each as lxml writes it (a namespace a child uses declared on it
    alike on both sides: the same root declares them)."""
    start = window.start
    if memoryview(data)[:start] != memoryview(window.original)[:start]:
        return False
    try:
        read = parse_bytes(data[:window.head_end] + data[start:], path, limit=None).getroot()
    except InputError:
        return False
    root = window.root
    return (len(read) > 0 and read.tag == root.tag and read.nsmap == root.nsmap
            and read.attrib.items() == root.attrib.items()
            and _pieces(read[0], read) == _pieces(window.first, root))


def _pieces(first: etree._Element, root: etree._Element) -> list[str]:
    """``first`` and the nodes after it, then those after ``root``, each as lxml writes it
    with its tail."""
    nodes = [first, *first.itersiblings(), None, *root.itersiblings()]
    return [etree.tostring(node, encoding="unicode") if node is not None else ""
            for node in nodes]


def _marked(data: bytes, edits: list[Edit], place: int, unfilled: Edit, token: bytes) -> bytes:
    """``data``, written by ``edits``, with the text filled in for a block's marker (the
    comment ``token``) replaced by the marker: edit ``place`` was ``unfilled`` before."""
    filled = edits[place]
    key = (filled.start, filled.end)
    # Where the filled edit's content starts in ``data``: after what the edits applied
    # before it (in the applier's order) added or took away.
    shift = sum(len(edit.content) - (edit.end - edit.start) for i, edit in enumerate(edits)
                if (edit.start, edit.end) < key or (edit.start, edit.end) == key and i < place)
    at = filled.start + shift + unfilled.content.index(token)
    size = len(filled.content) - len(unfilled.content) + len(token)
    return b"".join((data[:at], token, data[at + size:]))


def _digest(data: bytes) -> bytes:
    return hashlib.sha256(data).digest()


_AROUND = 2  # siblings on either side of a changed child whose bounds are indexed


def _first_recorded(root: etree._Element, at_root: list[etree._Element],
                    containers: set[etree._Element]) -> etree._Element | None:
    """Of the root's children, the first a conversion needs recorded (it leaves those
    before it as they are): before the first child it may replace, cut or put something
    beside (the first transmission at the root), as many as are indexed around such a child
    (:data:`_AROUND`), and as many again; None where a container of the change is a child of
    the root, or fewer children come first."""
    if not at_root or any(child.getparent() is root for child in containers):
        return None
    first: etree._Element | None = at_root[0]
    for _ in range(2 * _AROUND + 1):
        first = first.getprevious() if first is not None else None
    return first


def _near(root: etree._Element, kids: list[etree._Element], at_root: list[etree._Element],
          containers: set[etree._Element], replaced: set[etree._Element]
          ) -> set[etree._Element]:
    """Of the root's children ``kids``, those next to one a conversion may replace, cut or
    put something beside (a transmission, ``at_root``, or a ``<ros2_control>``), two on
    either side: a cut changes the tail of the node before, and taking a carried original's
    comment out changes the one before that. Not those ``replaced``: the edits write over
    them, from a kept node to the next."""
    changing = set(at_root)
    changing.update(child for child in containers if child.getparent() is root
                    and child.tag.rpartition("}")[2] == "ros2_control")
    near = set(changing)
    flags = list(map(changing.__contains__, kids))
    end = 0
    while True:  # over each run of changing children: those around it
        try:
            start = flags.index(True, end)
        except ValueError:
            break
        try:
            end = flags.index(False, start)
        except ValueError:
            end = len(kids)
        near.update(kids[max(0, start - _AROUND):start])
        near.update(kids[end:end + _AROUND])
    return near.difference(replaced)


def _replaced(root: etree._Element, transmissions: list[etree._Element], target: str,
              inside: list[etree._Element], ros1_alone: bool, data: bytes
              ) -> set[etree._Element]:
    """Transmissions a conversion to ``target`` replaces whole, as far as a glance tells: of
    another dialect, not changed inside (:func:`_changed_inside`), of a standard type by
    their first ``<type>`` (ROS 1) or ``<plugin>`` (ROS 2) child (a custom type is left as
    written: :func:`txtool.transform.convert._convert_one`). One the glance takes for replaced
    that is not is asked for after the change, and the index is made again in full
    (:class:`.spans.NotIndexed`)."""
    if target == "ros1" and local(root) == "ros2_control":
        return set()  # a bare fragment's transmissions are left as they are
    if target != "ros1" and ros1_alone:
        if _types_standard(data):  # (the glance of every one, without a step for each)
            return set(transmissions)
        other = transmissions
    else:
        other = [element for element in transmissions if detect_dialect(element) != target]
    kept = set(inside)
    return {element for element in other if element not in kept and _standard(element)}


_TYPE_TEXT = re.compile(rb"<type>([^<]*)</type>")


def _types_standard(data: bytes) -> bool:
    """Whether the bytes hold a ``<type>`` written as text alone, and each such names a
    standard type (a glance for a document all ROS 1: each transmission then takes it as
    replaced; one without such a ``<type>`` that is not is asked for after the change)."""
    texts = set(_TYPE_TEXT.findall(data))
    return bool(texts) and all(kind_of(text.decode("latin-1")) != "other" for text in texts)


def _standard(element: etree._Element) -> bool:
    """Whether the first ``<type>`` child, or else the first ``<plugin>``, is text alone
    that names a standard type."""
    plugin = None
    child = element[0] if len(element) else None  # (faster than an iterator, for one child)
    while child is not None:
        tag = child.tag
        if tag == "type":
            return _names_standard(child)
        if plugin is None and tag == "plugin":
            plugin = child
        child = child.getnext()
    return plugin is not None and _names_standard(plugin)


def _names_standard(element: etree._Element) -> bool:
    return not len(element) and kind_of(element.text or "") != "other"


def _ros1_alone(text: EditedText) -> bool:
    """Whether the bytes hold no ROS 2 spelling (``role``, ``plugin``, ``ros2_control``):
    every transmission is ROS 1, and no ``<ros2_control>`` stands in the document."""
    return text.stored.codec in SCANNABLE and not any(
        word in text.data for word in (b"role", b"plugin", b"ros2_control"))


def _changed_inside(transmissions: list[etree._Element], target: str, ros1_alone: bool
                    ) -> list[etree._Element]:
    """The transmissions a conversion to ``target`` may change inside rather than replace
    whole: those of the other ROS 2 proposal, whose roles are restyled in place
    (:func:`txtool.transform.placement.layout.restyle_roles`). A ROS 1 transmission, or any
    going to ROS 1, is replaced; a document whose bytes hold no ROS 2 spelling has none."""
    if target == "ros1" or not transmissions or ros1_alone:
        return []
    return [element for element in transmissions if detect_dialect(element) != "ros1"]


def _filled(edits: list[Edit], marker: etree._Comment, pieces: list[bytes]
            ) -> tuple[list[Edit], tuple[int, Edit]] | None:
    """``edits`` with the marker filled in inside the one edit that holds it, and the place
    of that edit with the edit as it was."""
    token = f"<!--{marker.text}-->".encode("ascii")
    holding = [i for i, edit in enumerate(edits) if token in edit.content]
    if len(holding) != 1:
        return None
    edit = edits[holding[0]]
    content = fill(edit.content, marker, pieces)
    if content is None:
        return None
    edits[holding[0]] = Edit(edit.start, edit.end, content)
    return edits, (holding[0], edit)
