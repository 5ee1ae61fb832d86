"""BB actuators: what one ROS simple transmission becomes, and its DSL text.

An :class:`Attachment` is an ``actuator`` with its ``transmission`` inside the ``joint``
(beam-bots/bb ``lib/bb/dsl.ex:209-247``); :func:`actuator_lines` writes one, as
:func:`render_joints` (joint blocks to merge) and :mod:`txtool.transform.bb.topology` (a whole
topology) place it. Numbers are written as BB reads them: ``reduction`` a float literal, an
``offset`` in plain decimal form inside ``~u(...)``.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from decimal import Decimal
from typing import Literal

from txtool.model.numbers import format_float
from txtool.transform.bb.names import elixir_atom

Direction = Literal["reversed", "negative-reduction"]
DIRECTIONS: tuple[Direction, ...] = ("reversed", "negative-reduction")
DRIVER = "Driver"


@dataclass(frozen=True)
class Attachment:
    """One BB actuator and its transmission, made from one ROS simple transmission."""

    transmission: str
    joint: str
    actuator: str
    joint_atom: str
    actuator_atom: str
    reduction: float  # signed: negative where the joint runs reversed
    offset: float
    linear: bool  # the offset is a length (prismatic joint)

    @property
    def identity(self) -> bool:
        return self.reduction == 1.0 and self.offset == 0.0


def render_joints(attachments: Sequence[Attachment], direction: Direction) -> str:
    """One ``joint`` block per joint holding its actuators, to merge into a BB topology."""
    if not attachments:
        return ""
    by_joint: dict[str, list[Attachment]] = {}
    for a in attachments:
        by_joint.setdefault(a.joint_atom, []).append(a)
    blocks = []
    for joint_atom, group in by_joint.items():
        lines = [f"joint {elixir_atom(joint_atom)} do"]
        for a in group:
            lines.extend("  " + line for line in actuator_lines(a, direction))
        lines.append("end")
        blocks.append("\n".join(lines))
    header = ("# Merge each actuator into the joint of that name in your BB robot's topology.\n")
    return header + "\n\n".join(blocks) + "\n"


def actuator_lines(a: Attachment, direction: Direction) -> list[str]:
    """The ``actuator`` entity with its ``transmission`` (none for an identity transmission)."""
    renamed = [f"{what} '{name}'" for what, name, atom in (
        ("joint", a.joint, a.joint_atom), ("actuator", a.actuator, a.actuator_atom))
        if name and name != atom]
    source = f"# transmission '{a.transmission}'" + (f" ({', '.join(renamed)})" if renamed else "")
    head = f"actuator {elixir_atom(a.actuator_atom)}, {DRIVER}"
    if a.identity:
        return [source + ": reduction 1, no offset, nothing to declare", head]
    reversed_ = direction == "reversed" and a.reduction < 0
    reduction = abs(a.reduction) if direction == "reversed" else a.reduction
    body = [f"reduction {elixir_float(reduction)}"]
    if a.offset != 0.0:
        unit = "meter" if a.linear else "radian"
        body.append(f"offset ~u({decimal_text(a.offset)} {unit})")
    if reversed_:
        body.append("reversed? true")
    return [source, head + " do", "  transmission do", *("    " + b for b in body),
            "  end", "end"]


def elixir_float(value: float) -> str:
    """:func:`format_float` as an Elixir float literal (``50`` -> ``50.0``, ``1e+20`` ->
    ``1.0e20``): BB's ``reduction`` option is typed float and rejects integers."""
    text = format_float(value)
    mantissa, e, exponent = text.partition("e")
    if "." not in mantissa and mantissa.lstrip("-").isdigit():
        mantissa += ".0"
    return mantissa + e + exponent.lstrip("+")


def decimal_text(value: float) -> str:
    """The shortest round-trip digits in plain decimal form (``1e-05`` -> ``0.00001``), as
    BB's importer writes the numbers inside ``~u(...)``."""
    if not math.isfinite(value):
        raise ValueError(f"{value!r} has no decimal form")
    text = format(Decimal(repr(value)), "f")
    return text[:-2] if text.endswith(".0") else text
