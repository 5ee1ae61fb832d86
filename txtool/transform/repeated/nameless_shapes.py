"""Transmissions compared without their names, so that a check is not repeated for each of
thousands of transmissions that differ only in what their members are called.

The conversion check (:func:`txtool.transform.convert._check`) reads names only to tell
members apart: it keys values by member name and compares those keys, so what it finds
depends on which names are equal, not on what they spell, except for the names its code
writes itself (``actuator1``, which converting back to ROS 1 adds to a transmission without
an actuator, and ``*``, a simple transmission's reduction). :func:`shape` keeps exactly that:
every other name becomes the index of its first appearance.
"""

from __future__ import annotations

from collections.abc import Callable, Hashable

from txtool.model.core import Member, Number, Transmission

# Names the check's own code writes or keys by; a member so named keeps its name in a shape.
LITERAL_NAMES = frozenset({"actuator1", "*"})


def shape(*transmissions: Transmission) -> Hashable:
    """``transmissions`` with every name replaced by the index of its first appearance among
    them (names in :data:`LITERAL_NAMES` kept as written); equal shapes mean the same
    transmissions up to a renaming that keeps which names are equal."""
    names: dict[str, int] = {}

    def name(text: str) -> object:
        if text in LITERAL_NAMES:
            return text
        return names.setdefault(text, len(names))

    return _shape(transmissions, name)


def ordered_shape(*transmissions: Transmission) -> Hashable:
    """:func:`shape` for what also reads the order of the names (ros2_control orders handles
    by name): every name becomes its rank among all their names and :data:`LITERAL_NAMES`,
    so equal shapes mean a renaming that keeps every comparison between names."""
    every = {n for t in transmissions for n in (t.name, *(m.name for m in t.joints),
                                                  *(m.name for m in t.actuators))}
    rank = {text: index for index, text in enumerate(sorted(every | LITERAL_NAMES))}
    return _shape(transmissions, lambda text: text if text in LITERAL_NAMES else rank[text])


def _shape(transmissions: tuple[Transmission, ...], name: Callable[[str], object]) -> Hashable:
    def number(n: Number | None) -> object:
        return None if n is None else (repr(n.value), n.text)

    def member(m: Member) -> tuple:
        return (name(m.name), m.role, number(m.mechanical_reduction), number(m.offset),
                m.interfaces, m.state_interfaces, m.read_only, m.location)

    return tuple(
        (name(t.name), t.type, t.kind, t.dialect, t.parameters, t.ros2_control, t.xml,
         t.location, tuple(member(j) for j in t.joints), tuple(member(a) for a in t.actuators))
        for t in transmissions
    )
