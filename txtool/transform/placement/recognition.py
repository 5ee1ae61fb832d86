"""ROS 2 -> ROS 1: whether a ``<ros2_control>`` block is exactly what txtool generates for its
transmissions, so that converting back replaces it by them at its place (any other block is
kept, and they move out to stand beside it).

A block is recognized by building it again, without recording anything, through the placer's
own builder (:class:`Builder`) and comparing the two element by element (:func:`same`: tags,
attributes, stripped texts and children, without the layout), holding nothing of either.
"""

from __future__ import annotations

import re
from typing import Protocol

from lxml import etree

from txtool.dialects.read import detect_dialect
from txtool.dialects.translate import translate
from txtool.io.xmlio import local
from txtool.model.core import Dialect, Transmission, replace
from txtool.model.robot import children
from txtool.transform.placement.layout import namespace_of
from txtool.transform.placement.moves import Move


class Builder(Protocol):
    """What recognition builds with (:class:`txtool.transform.placement.placer.Placer`)."""

    def block(self, name: str, plugin: str, moves: list[Move], like: etree._Element,
              indent: str, step: str, *, record: bool = True,
              transmissions: bool = True) -> etree._Element: ...

    def build(self, move: Move, indent: str, step: str, like: etree._Element, *,
              record: bool = True) -> etree._Element: ...


def generated_from(component: etree._Element, moves: list[Move], document: str,
                   builder: Builder) -> list[Transmission] | None:
    """The ROS 1 transmissions from which txtool generates exactly ``component`` (holding
    the transmissions of ``moves``, converted to ROS 1), or None when it generates no such
    block. ``document``: the name of the document's ``<robot>``, which a block generated
    for the document is named after."""
    inside = [e for e in component.iter("{*}transmission") if e is not component]
    bases = [document]  # a block for the document
    if moves:  # a block wrapped in place around those of a xacro macro, after the first
        bases.append(moves[0].new.name)
    if [m.old for m in moves] != inside or not named_after(component.get("name"), bases):
        return None
    plugins = [p for h in children(component, "hardware") for p in children(h, "plugin")]
    if len(plugins) != 1 or not plugins[0].text:
        return None
    dialect = detect_dialect(moves[0].old)
    found = [g for g in (_generating(move, dialect, builder) for move in moves) if g]
    if len(found) < len(moves):
        return None
    forward = [Move(m.old, f, m.carried) for m, (_, f) in zip(moves, found, strict=True)]
    namespace = namespace_of(component)
    if any(namespace_of(m.old) != namespace for m in moves):
        return None  # txtool builds a block's transmissions in the block's namespace
    # Each transmission is known to be as generated: compare the rest of the block, which
    # ends with them, without building them again.
    built = builder.block(component.get("name"), plugins[0].text, forward, component, "", "",
                          record=False, transmissions=False)
    if not same(built, component, tail=[m.old for m in moves]):
        return None
    return [source for source, _ in found]


def _generating(move: Move, dialect: Dialect, builder: Builder
                ) -> tuple[Transmission, Transmission] | None:
    """The ROS 1 transmission from which txtool generates exactly ``move.old``, and what it
    generates: the conversion itself, or the same without the reduction it had to write
    (ROS 1 requires one; ros2_control reads a missing one as 1.0)."""
    t = move.new
    candidates = [t]
    if t.kind == "simple" and t.actuators and t.actuators[0].mechanical_reduction:
        bare = replace(t.actuators[0], mechanical_reduction=None)
        candidates.append(replace(t, actuators=(bare, *t.actuators[1:])))
    for candidate in candidates:
        forward = translate(candidate, dialect).transmission
        built = builder.build(Move(move.old, forward, move.carried), "", "", move.old,
                              record=False)
        if same(built, move.old):
            return candidate, forward
    return None


def named_after(name: str | None, bases: list[str]) -> bool:
    """Whether ``name`` is one txtool gives a block generated under one of ``bases``
    (``Placer._fresh_name``: the base, or the base with ``_2``, ``_3``...)."""
    return name is not None and any(
        name == base or re.fullmatch(re.escape(base) + r"_([2-9]|[1-9][0-9]+)", name)
        for base in bases)


def same(built: etree._Element, written: etree._Element,
         tail: list[etree._Element] | None = None) -> bool:
    """Whether ``written`` is ``built`` but for the layout: the same tags, attributes,
    stripped texts and children, comments included but for those inside transmissions
    (carried, not generated); ``tail``: children of ``written`` after those ``built`` has,
    known to be as generated."""
    return _same(built, written, _in_transmission(built), _in_transmission(written), tail)


def _same(a: etree._Element, b: etree._Element, a_inside: bool, b_inside: bool,
          tail: list[etree._Element] | None = None) -> bool:
    if a.tag != b.tag or (a.text or "").strip() != (b.text or "").strip():
        return False
    attributes_a, attributes_b = a.items(), b.items()
    if attributes_a != attributes_b and sorted(attributes_a) != sorted(attributes_b):
        return False  # (their order aside)
    if tail is None and not len(a) and not len(b):
        return True  # two leaves (most elements of a block)
    kids_a, kids_b = _kids(a, a_inside), _kids(b, b_inside)
    if tail is not None:
        if kids_b[len(kids_b) - len(tail):] != tail:
            return False
        kids_b = kids_b[:len(kids_b) - len(tail)]
    if len(kids_a) != len(kids_b):
        return False
    for x, y in zip(kids_a, kids_b, strict=True):
        if x.__class__ is str or y.__class__ is str:
            if x != y:
                return False
            continue
        tag = x.tag
        here = tag == "transmission" or tag.endswith("}transmission")
        if not _same(x, y, a_inside or here, b_inside or here):
            return False
    return True


def _kids(element: etree._Element, inside: bool) -> list[etree._Element | str]:
    """The child elements, and the texts of the comments (outside transmissions)."""
    kids: list[etree._Element | str] = []
    for child in element:
        if child.tag.__class__ is str:
            kids.append(child)
        elif not inside and isinstance(child, etree._Comment):
            kids.append(child.text or "")
    return kids


def _in_transmission(element: etree._Element) -> bool:
    """Whether ``element`` is or stands in a transmission."""
    return local(element) == "transmission" or any(
        local(a) == "transmission" for a in element.iterancestors())
