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
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, Protocol

from lxml import etree

from txtool import dialects
from txtool.io.xmlio import safe_parser
from txtool.model.core import Dialect, Transmission

if TYPE_CHECKING:
    from txtool.transform.memo import Follower, Renaming
    from txtool.transform.templates import Templates

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


class Move(Protocol):
    """What :func:`write` reads of a placed conversion (see :mod:`.placement`)."""

    old: etree._Element
    follower: Follower | None
    carried: object

    @property
    def renaming(self) -> Renaming | None: ...

    @property
    def dialect(self) -> Dialect: ...

    @property
    def new(self) -> Transmission: ...

    def joints(self) -> list[tuple[str, tuple[str, ...], tuple[str, ...]]]: ...


def write(name: str, plugin: str, moves: Sequence[Move], tails: list[str], indent: str,
          step: str, templates: Templates
          ) -> tuple[etree._Element, list[Written], list[Written],
                     tuple[etree._Comment, bytes]] | None:
    """The block generated for ``moves`` (each followed by its ``tails``) at ``indent``: its
    element with the marker, each transmission as :class:`Written`, those whose joints none
    before declared, and the marker with the text that goes in its place (the declarations,
    then the transmissions by one ``%`` of the forms of their templates); None when a piece
    has no plain text."""
    newline = ("\n" + indent + step).encode()
    part = Block(name)
    declarations = part.declarations  # the first of each joint, in order
    forms: dict[tuple, tuple[bytes, bytes]] = {}
    by_record: dict[int, tuple[str, Callable] | None] = {}  # a follower's form
    heads: list[bytes] = []
    bodies: list[str] = []
    values: list[str] = []
    written: list[Written] = []
    alone: list[Written] = []  # those whose joints none before declared
    for move, tail in zip(moves, tails, strict=True):
        follower = move.follower
        if move.carried:
            return None
        if follower is not None:  # the same key and dialect as its record's
            known = by_record.get(id(follower.record), False)
            if known is False:
                known = by_record[id(follower.record)] = templates.form(
                    follower.renaming(), move.dialect, indent + step, step, move, True)
            if known is None:
                return None
            form, args = known[0], known[1](follower.names)
            joints = follower.record.joints_for(follower.names)
            one = Written(part, form, args, follower)
        else:
            text = None if move.renaming is None else templates.text(
                move.renaming, move.dialect, indent + step, step, move, True)
            if text is None:
                return None
            form, args = text.decode().replace("%", "%%"), ()
            joints = move.joints()
            one = Written(part, form, args, [joint for joint, _, _ in joints])
        own = True
        for joint, commands, states in joints:
            interfaces = (commands, states)
            if joint in declarations:
                own = False
                continue
            form_ = forms.get(interfaces)
            if form_ is None:
                form_ = forms[interfaces] = templates.declaration(
                    interfaces, indent + step, step)
                if not plain(form_[0] + form_[1]):
                    return None
            declarations[joint] = declared = form_[0] + joint.encode() + form_[1]
            heads += (declared, newline)
        bodies += (form, tail)
        values += args
        written.append(one)
        if own:
            alone.append(one)
    if not plain_names("".join(declarations)):
        return None
    block = etree.Element("ros2_control", name=name, type="system")
    hardware = etree.SubElement(block, "hardware")
    etree.SubElement(hardware, "plugin").text = plugin
    dialects.pretty(hardware, indent + step, step)
    hardware.tail = block.text = newline.decode()
    comment = marker()
    block.append(comment)
    heads.append(("".join(bodies) % tuple(values)).encode())
    return block, written, alone, (comment, b"".join(heads))


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
