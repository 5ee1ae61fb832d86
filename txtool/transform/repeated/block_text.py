"""The block generated for a whole document, written as text instead of built as elements.

Thousands of keyed transmissions (:mod:`.renamings`) converted into the ``<ros2_control>`` that
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
So the block is parsed only for that check (:func:`read_back`), or into the tree after all
where its text cannot be filled in (:meth:`txtool.transform.placement.placer.Placer.unwrite`).
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
from txtool.transform.repeated.templates import Templates, plain

if TYPE_CHECKING:
    from txtool.transform.repeated.renamings import Follower, Record, Renaming

_UNSAFE_NAME = re.compile(r'[^\x20-\x7e]|[&<>"]')


def plain_names(names: str) -> bool:
    """Whether names (joined) are written as they are in an attribute value."""
    return _UNSAFE_NAME.search(names) is None


def blank(layout: str) -> bool:
    """Whether ``layout`` (a tail or an indentation) is spaces, tabs and line feeds."""
    return not layout.strip(" \t\n")


class Block:
    """The shared part of the transmissions of one written block: its name and the text of
    the first declaration of each joint (before and after the joint's name)."""

    __slots__ = ("name", "declarations")

    def __init__(self, name: str) -> None:
        self.name = name
        self.declarations: dict[str, tuple[bytes, bytes]] = {}


class Written:
    """A transmission of a written block, not parsed (see the module): its text is ``form %
    pick(names)``, a follower's (:mod:`.renamings`) the form of its record's with its own names;
    one converted in full has no ``pick`` and its form is its text."""

    __slots__ = ("block", "form", "pick", "record", "names")

    def __init__(self, block: Block, form: str, pick: Callable | None, record: Record | None,
                 names: tuple[str, ...] | list[str]) -> None:
        """``record`` and ``names``: a follower's (not the follower, which refers to this:
        no reference cycle to wait for the collector); without a record, ``names`` are those
        of its joints."""
        self.block = block
        self.form = form
        self.pick = pick
        self.record = record
        self.names = names

    def source(self) -> bytes:
        """It in a ``<ros2_control>`` (without its name) declaring its joints."""
        declarations = self.block.declarations
        joints = self.names if self.record is None else [
            name for name, _, _ in self.record.joints_for(self.names)]  # type: ignore[arg-type]
        text = self.form if self.pick is None else self.form % self.pick(self.names)
        return b"".join([b"<ros2_control>",
                         *[b"%s%s%s" % (declarations[name][0], name.encode(),
                                        declarations[name][1])
                           for name in dict.fromkeys(joints)],
                         text.encode(), b"</ros2_control>"])


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
    """What :func:`write` reads of a placed conversion (see
    :mod:`txtool.transform.placement.placer`)."""

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
                     tuple[etree._Comment, list[bytes]]] | None:
    """The block generated for ``moves`` (each followed by its ``tails``) at ``indent``: its
    element with the marker, each transmission as :class:`Written`, those whose joints none
    before declared, and the marker with the pieces of the text that goes in its place (the
    declarations, then the transmissions by one ``%`` of the forms of their templates); None
    when a piece has no plain text."""
    writer = _Writer(Block(name), indent, step, templates)
    if not writer.add(moves, tails):
        return None
    declarations = writer.part.declarations
    if not plain_names("".join(declarations)):
        return None
    newline = writer.newline
    block = etree.Element("ros2_control", name=name, type="system")
    hardware = etree.SubElement(block, "hardware")
    etree.SubElement(hardware, "plugin").text = plugin
    dialects.pretty(hardware, indent + step, step)
    hardware.tail = block.text = newline
    comment = marker()
    block.append(comment)
    writer.flush()
    return block, writer.written, writer.alone, (comment, [*writer.heads(), *writer.texts])


_PER_TEXT = 2 * 64  # forms and tails in one of :attr:`_Writer.texts`


class _Writer:
    """The pieces of a written block, one transmission at a time."""

    def __init__(self, part: Block, indent: str, step: str, templates: Templates) -> None:
        self.part = part
        self.indent, self.step = indent, step
        self.templates = templates
        self.newline = "\n" + indent + step
        # The declarations' forms, each followed by a newline, and the joint names they take.
        self.head_forms: list[str] = []
        self.head_values: list[str] = []
        self.bodies: list[str] = []  # the forms of the transmissions, each with its tail
        self.values: list[str] = []  # what goes into the forms
        self.texts: list[bytes] = []  # the transmissions filled in, a few at a time
        self.written: list[Written] = []
        self.alone: list[Written] = []  # those whose joints none before declared
        # A declaration's text around its joint's name, and its form, by interfaces.
        self._forms: dict[tuple, tuple[tuple[bytes, bytes], str]] = {}
        # A follower's form, what picks its names, and per joint of its record's the text of
        # its declaration once made, by record.
        self._by_record: dict[Record, tuple[str, Callable, list] | None] = {}

    def add(self, moves: Sequence[Move], tails: list[str]) -> bool:
        """Add each of ``moves`` followed by its tail; False when one has no plain text.

        A follower (the same key and dialect as its record's) takes its record's form with its
        own names, and declares those of its joints that none before declared; its steps are
        written out here, with the lists they add to at hand, as thousands of them pass."""
        declarations = self.part.declarations
        head_forms, head_values = self.head_forms, self.head_values
        bodies, values = self.bodies, self.values
        written, alone = self.written, self.alone
        by_record = self._by_record
        part = self.part
        for move, tail in zip(moves, tails, strict=True):
            follower = move.follower
            if move.carried:
                return False
            if follower is None:
                if not self.other(move, tail):
                    return False
                continue
            record = follower.record
            known = by_record.get(record, False)
            if known is False:
                known = self._form_of(move, follower)
            if known is None:
                return False
            form, pick, made = known
            names = follower.names
            args = pick(names)
            own = True
            for k, (i, joint, interfaces) in enumerate(record.joint_plan):
                if i is not None:
                    joint = names[i]
                if joint in declarations:
                    own = False
                    continue
                declaration = made[k]
                if declaration is None:
                    declaration = made[k] = self._declaration(interfaces)
                    if declaration is None:
                        return False
                declarations[joint] = declaration[0]
                head_forms.append(declaration[1])
                head_values.append(joint)
            one = Written(part, form, pick, record, names)
            bodies += (form, tail)
            values += args
            written.append(one)
            if own:
                alone.append(one)
            if len(bodies) >= _PER_TEXT:
                self.flush()
        return True

    def _form_of(self, move: Move, follower: Follower) -> tuple[str, Callable, list] | None:
        """A follower's form, what picks its names, and per joint of its record's the text of
        its declaration once made (made once per record)."""
        record = follower.record
        form_of = self.templates.form(follower.renaming(), move.dialect,
                                      self.indent + self.step, self.step, move, True)
        known = self._by_record[record] = None if form_of is None else (
            form_of[0], form_of[1], [None] * len(record.joint_plan))
        return known

    def other(self, move: Move, tail: str) -> bool:
        """Add a transmission converted in full; False when it has no plain text."""
        text = None if move.renaming is None else self.templates.text(
            move.renaming, move.dialect, self.indent + self.step, self.step, move, True)
        if text is None:
            return False
        form = text.decode().replace("%", "%%")
        joints = move.joints()
        own = True
        for joint, commands, states in joints:
            if joint in self.part.declarations:
                own = False
                continue
            declaration = self._declaration((commands, states))
            if declaration is None:
                return False
            self._declare(joint, declaration)
        self._add(Written(self.part, text.decode(), None, None,
                          [joint for joint, _, _ in joints]), form, (), tail, own)
        return True

    def _declaration(self, interfaces: tuple) -> tuple[tuple[bytes, bytes], str] | None:
        """A joint declaration's text before and after its name, and the ``%`` form of it
        followed by a newline (made once per interfaces), or None when it is not plain."""
        known = self._forms.get(interfaces)
        if known is None:
            around = self.templates.declaration(interfaces, self.indent + self.step, self.step)
            if not plain(around[0] + around[1]):
                return None  # and the block is not written
            head, tail = (part.decode("ascii").replace("%", "%%") for part in around)
            known = self._forms[interfaces] = (around, head + "%s" + tail + self.newline)
        return known

    def _declare(self, joint: str, declaration: tuple[tuple[bytes, bytes], str]) -> None:
        self.part.declarations[joint] = declaration[0]
        self.head_forms.append(declaration[1])
        self.head_values.append(joint)

    def heads(self) -> list[bytes]:
        """The declarations' texts, a few at a time (see :meth:`flush`)."""
        forms, values = self.head_forms, self.head_values
        return [("".join(forms[at:at + _PER_TEXT]) % tuple(values[at:at + _PER_TEXT])).encode()
                for at in range(0, len(forms), _PER_TEXT)]

    def _add(self, one: Written, form: str, args: tuple[str, ...], tail: str,
             own: bool) -> None:
        self.bodies += (form, tail)
        self.values += args
        self.written.append(one)
        if own:
            self.alone.append(one)
        if len(self.bodies) >= _PER_TEXT:
            self.flush()

    def flush(self) -> None:
        """Fill in the transmissions added since the last time: texts of a few tens of
        kilobytes, which the document's text is joined from (one large string filled in at
        once, then encoded, would be two copies of the block more)."""
        if self.bodies:
            self.texts.append(("".join(self.bodies) % tuple(self.values)).encode())
            self.bodies.clear()
            self.values.clear()


def marker() -> etree._Comment:
    """A comment no document holds (checked when it is filled)."""
    return etree.Comment(f"txtool-block-{os.urandom(16).hex()}")


def fill(data: bytes, comment: etree._Comment, pieces: list[bytes]) -> bytes | None:
    """``data`` (a serialization holding ``comment`` once) with the text ``pieces`` join to
    in its place (one copy of each), or None when the comment is not there exactly once."""
    token = f"<!--{comment.text}-->".encode("ascii")
    at = data.find(token)
    if at < 0 or data.find(token, at + 1) >= 0:
        return None
    view = memoryview(data)
    return b"".join([view[:at], *pieces, view[at + len(token):]])
