"""The block generated for a whole document, written as text and never parsed.

Thousands of keyed transmissions (:mod:`.memo`) converted into the ``<ros2_control>`` that
txtool generates for the document are already text (:mod:`.templates`): the block goes into
the tree as its start tag and hardware, with a marker comment where the rest goes; the
serialized document gets the text in place of the marker (:func:`fill`). That is the very
serialization the block would have with those elements parsed into it, when every piece is
plain (:func:`plain`): ASCII whose only references are the predefined entities, which every
encoding writes alike, and layout that is whitespace only.

A transmission of the block is a :class:`Written`: its text, and the declarations of its
joints as the block declares them. Reading it back (the conversion's check) reads it in a
``<ros2_control>`` of the block's name holding those declarations and it alone, which gives
what reading it in the whole block gives: the reader reads of the block its name and the
first declaration of each joint, nothing else (:class:`txtool.dialects.read.Declarations`).
"""

from __future__ import annotations

import os
import re
from typing import TYPE_CHECKING

from lxml import etree

from txtool.io.xmlio import safe_parser

if TYPE_CHECKING:
    from txtool.transform.memo import Follower

_UNSAFE = re.compile(rb"[^\x20-\x7e\n\t]|&#")  # a reference, or what another encoding writes
_UNSAFE_NAME = re.compile(r'[^\x20-\x7e]|[&<>"]')


def plain(text: bytes) -> bool:
    """Whether ``text`` (a serialization) reads the same written in any ASCII encoding."""
    return _UNSAFE.search(text) is None


def plain_names(names: str) -> bool:
    """Whether names (joined) are written as they are in an attribute value."""
    return _UNSAFE_NAME.search(names) is None


def blank(layout: str) -> bool:
    """Whether ``layout`` (a tail or an indentation) is spaces, tabs and line feeds."""
    return not layout.strip(" \t\n")


class Block:
    """The shared part of the transmissions of one written block: its name and the text of
    the first declaration of each joint."""

    __slots__ = ("name", "declarations")

    def __init__(self, name: str) -> None:
        self.name = name
        self.declarations: dict[str, bytes] = {}


class Written:
    """A transmission of a written block, not parsed (see the module): its text is ``form %
    values``."""

    __slots__ = ("block", "form", "values", "joints")

    def __init__(self, block: Block, form: str, values: tuple[str, ...],
                 joints: list[str] | Follower) -> None:
        self.block = block
        self.form = form
        self.values = values
        self.joints = joints

    def source(self) -> bytes:
        """It in a ``<ros2_control>`` (without its name) declaring its joints."""
        declarations = self.block.declarations
        joints = self.joints if isinstance(self.joints, list) else [
            name for name, _, _ in self.joints.record.joints_for(self.joints.names)]
        return b"".join([b"<ros2_control>",
                         *[declarations[name] for name in dict.fromkeys(joints)],
                         (self.form % self.values).encode(), b"</ros2_control>"])


def read_back(written: list[Written]) -> list[etree._Element]:
    """The element of each of ``written``, each in a ``<ros2_control>`` of its own, parsed in
    one go."""
    if not written:
        return []
    root = etree.fromstring(b"".join([b"<x>", *[w.source() for w in written], b"</x>"]),
                            safe_parser())
    elements = []
    for w, component in zip(written, root, strict=True):
        component.set("name", w.block.name)
        elements.append(component[len(component) - 1])
    return elements


def marker() -> etree._Comment:
    """A comment no document holds (checked when it is filled)."""
    return etree.Comment(f"txtool-block-{os.urandom(16).hex()}")


def fill(data: bytes, comment: etree._Comment, text: bytes) -> bytes | None:
    """``data`` (a serialization holding ``comment`` once) with ``text`` in its place, or None
    when the comment is not there exactly once."""
    token = f"<!--{comment.text}-->".encode("ascii")
    if data.count(token) != 1:
        return None
    return data.replace(token, text)
