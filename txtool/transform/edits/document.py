"""A conversion said as edits of the bytes it read.

A conversion changes the parsed tree: the placer (:mod:`txtool.transform.placement.placer`) replaces
transmissions, cuts them out, wraps them in a ``<ros2_control>`` of their own, moves them into or
out of a block, and restyles a Proposal 1 transmission's roles in place. :class:`ConversionEdits`
records, before any of that, the elements whose children a conversion may change (each
transmission's ancestors, and each ``<ros2_control>`` of the document with its parent) and the
transmissions it changes inside; afterwards :meth:`ConversionEdits.edits` says the change as edits
of their spans (:mod:`.tree_edits`, :mod:`.spans`), the one applier
(:func:`txtool.transform.edits.core.apply_edits`) makes the bytes, and :func:`check_written`
parses them and holds them to the converted tree.

A transmission going back to ROS 1 whose original ``--reversible`` carried
(:mod:`txtool.transform.reversible`) is written as its original bytes (:meth:`substitute`).
"""

from __future__ import annotations

import hashlib

from lxml import etree

from txtool.dialects.read import detect_dialect
from txtool.io.encodings import utf8_form
from txtool.io.xmlio import InputError, parse_bytes
from txtool.transform.edits.core import Edit, EditedText
from txtool.transform.edits.declaration import late_declaration
from txtool.transform.edits.spans import SpanError, SpanIndex
from txtool.transform.edits.tree_edits import (
    NotEditable,
    TreeChange,
    canonical,
    reads_as_serialized,
)


class ConversionEdits:
    """The document ``data`` whose tree (root ``root``) a conversion to ``target`` is about
    to change; ``transmissions``: its transmission elements."""

    def __init__(self, path: str, data: bytes, root: etree._Element,
                 transmissions: list[etree._Element], target: str) -> None:
        self.path = path
        self.text = EditedText(data)
        containers: set[etree._Element] = {root}
        for element in transmissions:
            for ancestor in element.iterancestors():
                if ancestor in containers:
                    break
                containers.add(ancestor)
        for component in root.iter("{*}ros2_control"):
            containers.add(component)
            containers.update(component.iterancestors())
        # Those of the other ROS 2 proposal have their roles restyled in place
        # (:func:`txtool.transform.placement.layout.restyle_roles`); the others are replaced.
        inside = [] if target == "ros1" else [
            element for element in transmissions if detect_dialect(element) != "ros1"]
        self.change = TreeChange(inside, containers)
        try:
            self.index = SpanIndex(self.text.data, root, inside, self.text.codec,
                                   shallow=containers)
        except SpanError as exc:
            raise InputError(f"{path}: cannot convert: the bytes do not read as parsed "
                             f"({exc})") from None

    def substitute(self, node: etree._Element, block: bytes) -> None:
        """Write ``node`` as ``block``, the whole lines a transmission stood on (the
        indentation of its first line and its last line ending left to the tree's layout)."""
        markup = block.lstrip(b" \t")
        self.change.substitute(node, markup[:len(markup.rstrip(b"\r\n"))])

    def edits(self) -> list[Edit]:
        """The edits that write the converted tree."""
        try:
            edits = self.change.written(self.text, self.index)
        except NotEditable as exc:
            raise InputError(f"{self.path}: cannot convert: {exc}") from None
        late = late_declaration(self.text.data) if edits else None
        if late is not None:
            edits.append(late)
        return edits

    def applied(self, edits: list[Edit]) -> bytes:
        """The document with ``edits`` made, stored as the original was."""
        return self.text.applied(edits)


def check_written(data: bytes, path: str, expected: str) -> None:
    """Refuse (:class:`InputError`) the bytes ``data`` that a conversion's edits wrote where
    they do not parse to the converted document, ``expected`` as lxml writes it
    (:func:`.tree_edits.serialization`)."""
    data = utf8_form(data)  # what the edits addressed (UTF-16 and UTF-32 stored back)
    try:
        written = parse_bytes(data, path, limit=None)
    except InputError as exc:
        raise InputError(f"{path}: cannot convert: what the edits write does not read "
                         f"back ({exc})") from None
    if not reads_as_serialized(written, expected, path):
        got = hashlib.sha256(canonical(written)).digest()
        raise InputError(f"{path}: cannot convert: what the edits write does not read as the "
                         f"converted document (read back {got[:6].hex()}); please report "
                         "this file")
