"""Export simple transmissions as Beam Bots (BB) DSL blocks.

BB's URDF importer does not import transmissions; it asks the user to declare
``transmission do ... end`` inside the actuator by hand. This writes those blocks. BB computes
``motor = sign * reduction * (joint - offset)`` with ``sign = -1`` when ``reversed?``, which is
ros2_control's SimpleTransmission with reduction ``sign * reduction``; so a negative effective
reduction is written as its magnitude plus ``reversed? true``. BB has no coupled transmissions.
Units are CLDR unit names as BB's ``~u`` sigil takes them (``radian``, ``meter``).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field

from txtool.model.core import Transmission
from txtool.model.numbers import format_float
from txtool.model.robot import JointInfo
from txtool.model.semantics import NotLoadable, effective


@dataclass(frozen=True)
class BBExport:
    """The DSL text (blocks separated by blank lines) and what could not be written."""

    text: str
    not_representable: list[str] = field(default_factory=list)

    @property
    def lossless(self) -> bool:
        return not self.not_representable


def export_bb(
    transmissions: Sequence[Transmission], joints: Mapping[str, JointInfo]
) -> BBExport:
    if not transmissions:
        return BBExport("# no transmission to export\n")
    blocks: list[str] = []
    lost: list[str] = []
    for t in transmissions:
        if t.kind != "simple":
            what = "custom type" if t.kind == "other" else f"{t.kind.replace('_', '-')} type"
            lost.append(f"transmission '{t.name}': {what} '{t.type}' is not representable in BB "
                        f"(BB has simple transmissions only)")
            continue
        try:
            eff = effective(t)
        except NotLoadable as exc:
            lost.append(f"transmission '{t.name}': not loadable: {exc}")
            continue
        info = joints.get(eff.joints[0])
        blocks.append(_block(eff.joints[0], eff.actuators[0], t.name,
                             eff.actuator_reduction[0] * eff.joint_reduction[0],
                             eff.joint_offset[0], info))
    text = "\n\n".join(blocks)
    return BBExport(text + "\n" if text else "", lost)


def _block(
    joint: str,
    actuator: str,
    name: str,
    reduction: float,
    offset: float,
    info: JointInfo | None,
) -> str:
    lines = [f"# joint '{joint}', actuator '{actuator}' (transmission '{name}')",
             "transmission do",
             f"  reduction {elixir_float(abs(reduction))}"]
    if offset != 0.0:
        unit = "meter" if info is not None and info.is_linear else "radian"
        lines.append(f"  offset ~u({elixir_float(offset)} {unit})")
    if reduction < 0:
        lines.append("  reversed? true")
    lines.append("end")
    return "\n".join(lines)


def elixir_float(value: float) -> str:
    """:func:`format_float` as an Elixir float literal (``50`` -> ``50.0``, ``1e+20`` ->
    ``1.0e20``): BB's ``reduction`` option is typed float and rejects integers."""
    text = format_float(value)
    mantissa, e, exponent = text.partition("e")
    if "." not in mantissa and mantissa.lstrip("-").isdigit():
        mantissa += ".0"
    return mantissa + e + exponent.lstrip("+")
