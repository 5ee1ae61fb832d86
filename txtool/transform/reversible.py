"""``convert --reversible``: converting back gives the original transmission bytes.

ROS 2 cannot hold everything a ROS 1 transmission's text holds (its layout, comments, an
actuator ``<hardwareInterface>`` that no loader reads, member order), so a plain round trip
brings each block back as txtool writes it. With ``--reversible`` each converted transmission
is preceded by one comment that carries the original block, compressed::

    <!-- txtool-original eNqzKS... -->

Both loaders skip comments. Converting back, a transmission whose comment is still there and
which is still exactly what txtool would generate from the original (nothing edited since) is
replaced by the original bytes; an edited one is written as txtool writes it, and said so.
Either way the comment goes.
"""

from __future__ import annotations

import base64
import binascii
import re
import zlib
from collections import deque

from lxml import etree

from txtool.dialects.read import Found, read_source
from txtool.dialects.translate import translate
from txtool.io.encodings import utf8_form
from txtool.io.xmlio import InputError, Source, local, parse_bytes
from txtool.model.core import Member, Transmission

MARK = "txtool-original"
# Before the payload: the transmission stood after the <ros2_control> it went into (base64
# has no spaces, so the word cannot be part of a payload).
AFTER = "after"
MAX_ORIGINAL = 1 << 20  # a transmission block is a few hundred bytes
_END = re.compile(rb"</([\w.-]+:)?transmission\s*>")
_START = re.compile(rb"<([\w.-]+:)?transmission[\s/>]")
_END_LINE = re.compile(rb"</([\w.-]+:)?transmission\s*>$")
_EMPTY_LINE = re.compile(rb"\s*<([\w.-]+:)?transmission\b[^>]*/>\s*")


def block_of(lines: list[bytes], element: etree._Element) -> bytes | None:
    """The whole lines ``element`` stands on (``lines``: those of the document, with their
    endings), or None when they hold more: its start tag must open its first line and its
    end tag close its last."""
    start = (element.sourceline or 0) - 1
    if not 0 <= start < len(lines) or not _START.match(lines[start].lstrip()):
        return None
    end = start
    if not _EMPTY_LINE.fullmatch(lines[start].rstrip(b"\r\n")):
        while end < len(lines) and not _END.search(lines[end]):
            end += 1
        if end >= len(lines) or not _END_LINE.search(lines[end].rstrip()):
            return None
    text = b"".join(lines[start:end + 1])
    return text if len(_START.findall(text)) == 1 else None


def comment_for(block: bytes, after: bool = False) -> etree._Comment:
    """The comment carrying ``block``; ``after``: the transmission stood after the
    ``<ros2_control>`` it went into, and goes back there (:data:`AFTER`)."""
    payload = base64.b64encode(zlib.compress(block, 9)).decode("ascii")
    return etree.Comment(f" {MARK} {AFTER + ' ' if after else ''}{payload} ")


def annotate(element: etree._Element, block: bytes, after: bool = False) -> None:
    """Put the comment carrying ``block`` on its own line before ``element``."""
    comment = comment_for(block, after)
    previous = element.getprevious()
    before = (previous.tail if previous is not None else element.getparent().text) or ""
    indent = before.rpartition("\n")[2] if "\n" in before else ""
    newline = "\r\n" if "\r\n" in before else "\n"
    element.addprevious(comment)
    comment.tail = newline + indent


def carries_originals(root: etree._Element) -> bool:
    """Whether a comment under ``root`` carries an original (converting the document to ROS 1
    may write it back as its bytes)."""
    return any((c.text or "").strip().startswith(MARK) for c in root.iter(etree.Comment))


def original_of(element: etree._Element) -> bytes | None:
    """The block carried by the comment right before ``element``; b"" for a damaged one."""
    comment = _marker(element)
    if comment is None:
        return None
    payload = _payload(comment)
    try:
        inflater = zlib.decompressobj()
        data = inflater.decompress(base64.b64decode(payload, validate=True), MAX_ORIGINAL)
    except (binascii.Error, ValueError, zlib.error):
        return b""
    return b"" if inflater.unconsumed_tail else data


def _payload(comment: etree._Comment) -> str:
    payload = (comment.text or "").strip()[len(MARK):].strip()
    return payload[len(AFTER):].strip() if payload.startswith(AFTER + " ") else payload


def goes_after(element: etree._Element) -> bool:
    """Whether the comment before ``element`` says it goes back after its block."""
    comment = _marker(element)
    return comment is not None and (comment.text or "").strip()[len(MARK):].strip().startswith(
        AFTER + " ")


def drop_marker(element: etree._Element) -> None:
    from txtool.transform.placement.layout import cut

    comment = _marker(element)
    if comment is not None:
        cut(comment)


def _marker(element: etree._Element) -> etree._Comment | None:
    previous = element.getprevious()
    if isinstance(previous, etree._Comment) and (previous.text or "").strip().startswith(MARK):
        return previous
    return None


def restorable(found: Found, original: bytes) -> bool:
    """Is ``found`` exactly what converting ``original`` gives (nothing edited since)?"""
    try:
        wrapped = b"<robot>" + original + b"</robot>"
        tree = parse_bytes(wrapped, "original")
        (source,) = read_source(Source("original", wrapped, tree), locate=False)
    except (InputError, ValueError):
        return False
    present = found.transmission
    generated = translate(source.transmission, present.dialect).transmission
    return _essence(generated) == _essence(present)


def _essence(t: Transmission) -> tuple:
    def member(m: Member) -> tuple:
        return (m.name, m.role, _value(m.mechanical_reduction), _value(m.offset))

    return (t.name, t.kind, t.type.strip(), tuple(member(j) for j in t.joints),
            tuple(member(a) for a in t.actuators))


def _value(number) -> object:
    return None if number is None else (number.value, number.text)


class Carrier:
    """What one conversion carries to ROS 2 (``reversible``) and puts back on the way to
    ROS 1 (whenever a carried original is found)."""

    def __init__(self, source: Source, target: str, reversible: bool) -> None:
        self.source = source
        self.target = target
        self.reversible = reversible and target != "ros1" and not source.expanded
        self.notes: list[str] = []
        if reversible and source.expanded:
            self.notes.append("--reversible: a xacro expansion has no original lines to carry "
                              "(use migrate, or --no-xacro, to convert the source itself)")
        self._carried: list[tuple[str, bytes, etree._Element]] = []
        # Elements going back to ROS 1 after their <ros2_control> (the placer's ``after``).
        self.after_block: set[etree._Element] = set()
        self._pending: list[tuple[etree._Element, bytes]] = []
        # The document's lines, once (each transmission's block is found among them).
        self._lines = utf8_form(source.data).splitlines(keepends=True) if (
            self.reversible) else []

    def before(self, found: Found) -> None:
        """Called for each transmission about to be converted, before it is placed."""
        t = found.transmission
        if self.target == "ros1":
            self._take_back(found)
        elif self.reversible and t.dialect == "ros1":
            block = block_of(self._lines, found.element)
            if block is None:
                self.notes.append(f"transmission '{t.name}': shares its lines with other "
                                  "elements; its original is not carried (--reversible)")
            else:
                self._carried.append((t.name, block, found.element))

    def after(self, tree: etree._ElementTree, built: dict[etree._Element, etree._Element]
              ) -> list[tuple[etree._Element, bytes]]:
        """Put each carried original before its converted transmission; the elements built
        back in ROS 1 that are to be written as their carried originals, with those
        (``built``: old element -> what the placer built)."""
        restored = [(built[old], original) for old, original in self._pending
                    if old in built]  # (not when it could not be moved: see Placer.losses)
        if restored:
            count = len(restored)
            self.notes.append(f"{count} transmission{'s' if count > 1 else ''}: the original "
                              "bytes carried by --reversible are put back")
        if self._carried:
            placed: dict[str | None, deque[etree._Element]] = {}  # by name, in order
            for e in tree.getroot().iter():
                if isinstance(e.tag, str) and local(e) == "transmission" and _in_component(e):
                    placed.setdefault(e.get("name"), deque()).append(e)
            for name, block, old in self._carried:
                same = placed.get(name)
                if same:
                    element = same.popleft()
                    annotate(element, block, _stood_after(old, element.getparent()))
        return restored

    def _take_back(self, found: Found) -> None:
        name = found.transmission.name
        original = original_of(found.element)
        if original is None:
            return
        if goes_after(found.element):
            self.after_block.add(found.element)
        drop_marker(found.element)
        if original and restorable(found, original):
            self._pending.append((found.element, original))
        else:
            self.notes.append(f"transmission '{name}': changed since it was converted with "
                              "--reversible; written as txtool writes it")


def _stood_after(old: etree._Element, component: etree._Element) -> bool:
    """Whether ``old`` stood after ``component``, a block of the document (one txtool
    generates has no source line)."""
    return (component.sourceline is not None and old.sourceline is not None
            and old.sourceline > component.sourceline)


def _in_component(element: etree._Element) -> bool:
    parent = element.getparent()
    return parent is not None and isinstance(parent.tag, str) and local(parent) == "ros2_control"
