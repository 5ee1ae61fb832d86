"""A change of a parsed document said as edits of the bytes it read, and read back.

A fix changes transmissions in place; a conversion replaces transmissions, cuts them out,
wraps them in a ``<ros2_control>`` of their own, moves them into or out of a block, and
restyles a Proposal 1 transmission's roles in place (the placer:
:mod:`txtool.transform.placement.placer`). :class:`DocumentEdits` records, before the change,
what it may touch (:func:`conversion_edits`: each transmission's ancestors and each
``<ros2_control>`` with its own, the elements whose children a conversion may change, and the
transmissions it changes inside); afterwards :meth:`DocumentEdits.written` says the change as
edits of their spans (:mod:`.tree_edits`, :mod:`.spans`), the one applier
(:func:`txtool.transform.edits.core.apply_edits`) makes the bytes, and :func:`read_back`
parses them and holds them to the changed tree.

A transmission going back to ROS 1 whose original ``--reversible`` carried
(:mod:`txtool.transform.reversible`) is written as its original bytes (:meth:`substitute`).
"""

from __future__ import annotations

import hashlib

from lxml import etree

from txtool.dialects.read import detect_dialect
from txtool.io.encodings import utf8_form
from txtool.io.xmlio import InputError, XMLSyntax, parse_bytes
from txtool.transform.edits.core import Edit, EditedText
from txtool.transform.edits.declaration import late_declaration
from txtool.transform.edits.spans import SpanError, SpanIndex
from txtool.transform.edits.tree_edits import (
    NotEditable,
    Serialized,
    TreeChange,
    canonical,
    reads_as_serialized,
)


class DocumentEdits:
    """The document ``data`` whose tree (root ``root``) a change is about to change:
    ``elements`` recorded with all their descendants, ``containers`` alone (see
    :class:`.tree_edits.TreeChange`); ``verb`` names the change in a refusal (``fix``,
    ``convert``)."""

    def __init__(self, path: str, data: bytes, root: etree._Element,
                 elements: list[etree._Element], containers: set[etree._Element] | None = None,
                 verb: str = "fix") -> None:
        self.path, self.verb = path, verb
        self.text = EditedText(data)
        self.change = TreeChange(elements, containers or ())
        try:
            self.index = SpanIndex(self.text.data, root, elements, self.text.codec,
                                   shallow=containers or ())
        except SpanError as exc:
            raise InputError(f"{path}: cannot {verb}: the bytes do not read as parsed "
                             f"({exc})") from None

    def substitute(self, node: etree._Element, block: bytes) -> None:
        """Write ``node`` as ``block``, the whole lines a transmission stood on (the
        indentation of its first line and its last line ending left to the tree's layout)."""
        markup = block.lstrip(b" \t")
        self.change.substitute(node, markup[:len(markup.rstrip(b"\r\n"))])

    def said(self) -> list[Edit]:
        """The edits that write the changed tree. The change is said once: what was recorded
        to say it (the state before, the spans, and with them the tree) is let go."""
        try:
            edits = self.change.written(self.text, self.index)
        except NotEditable as exc:
            raise InputError(f"{self.path}: cannot {self.verb}: {exc}") from None
        finally:
            del self.change, self.index
        late = late_declaration(self.text.data) if edits else None
        if late is not None:
            edits.append(late)
        return edits

    def written(self) -> tuple[list[Edit], bytes]:
        """:meth:`said`, and the document the edits make, stored as the original was."""
        edits = self.said()
        return edits, self.text.applied(edits)


def conversion_edits(path: str, data: bytes, root: etree._Element,
                     transmissions: list[etree._Element], target: str) -> DocumentEdits:
    """:class:`DocumentEdits` for a conversion to ``target`` of the transmissions
    ``transmissions``: the elements whose children it may change are each transmission's
    ancestors and each ``<ros2_control>`` with its ancestors; those of the other ROS 2
    proposal are changed inside (their roles restyled in place:
    :func:`txtool.transform.placement.layout.restyle_roles`), the others replaced."""
    containers: set[etree._Element] = {root}
    for element in transmissions:
        for ancestor in element.iterancestors():
            if ancestor in containers:
                break
            containers.add(ancestor)
    for component in root.iter("{*}ros2_control"):
        containers.add(component)
        containers.update(component.iterancestors())
    inside = [] if target == "ros1" else [
        element for element in transmissions if detect_dialect(element) != "ros1"]
    return DocumentEdits(path, data, root, inside, containers, "convert")


def read_back(data: bytes, path: str, expected: Serialized | None, verb: str = "convert"
              ) -> etree._ElementTree:
    """The parse of ``data``, the bytes a change wrote, refused (:class:`InputError`) where
    it fails (a change may nest elements deeper than a parse reads) or, given ``expected``
    (the changed document as lxml writes it: :func:`.tree_edits.serialization`), where it
    does not read as that."""
    try:
        written = parse_bytes(utf8_form(data), path, limit=None)
    except XMLSyntax as exc:
        raise InputError(f"{path}: cannot {verb}: the result could not be read back; its line "
                         f"{exc.line}: {exc.reason}") from None
    if expected is not None and not reads_as_serialized(written, expected, path):
        got = hashlib.sha256(canonical(written)).digest()
        raise InputError(f"{path}: cannot {verb}: what the edits write does not read as the "
                         f"{verb}ed document (read back {got[:6].hex()}); please report "
                         "this file")
    return written
