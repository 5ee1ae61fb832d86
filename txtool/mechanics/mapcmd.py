"""``txtool map``: map values of one transmission between joint and actuator space.

Values are given and printed in ROLE order (``joint1, joint2`` / ``actuator1, actuator2``),
the order people write them in. The maths runs in the loader's index order: ros_control takes
the parameters by role but fills its data vectors in XML order (:mod:`txtool.views.effective`);
ros2_control binds parameters in XML order but orders the handles by NAME. A value given for
role ``joint1`` goes to the handle of the member that has that role, and the loader then
applies whatever parameters sit at that handle's index, as
:func:`txtool.model.semantics.effective` binds them. Where roles are missing or not
``joint1``/``joint2`` (ros2_control does not check them), XML order stands in for role order.

Efforts go through the four-bar map of the file's own loader (ros_control's for a ROS 1
transmission, ros2_control's for a ROS 2 one) unless ``convention`` names one.
"""

from __future__ import annotations

import io
import json
import math
from dataclasses import dataclass, field

from txtool.io.load import load
from txtool.io.xmlio import InputError, XacroOptions
from txtool.mechanics.convention import effort_convention, source_of
from txtool.mechanics.points import PointMap, from_effective
from txtool.model.core import Member, Transmission
from txtool.model.numbers import format_float, parse_strict
from txtool.model.semantics import ROLES_ACTUATOR, ROLES_JOINT, NotLoadable, effective

QUANTITIES = ("position", "velocity", "effort")
_LOADERS = {"ros1": "ros_control's", "ros2": "ros2_control's"}


@dataclass(frozen=True)
class MapOutcome:
    """What ``txtool map`` prints; ``error`` is a one-line message when ``exit_code`` != 0."""

    exit_code: int
    error: str | None = None
    transmission: str = ""
    to: str = ""
    inputs: tuple[str, ...] = ()  # input member names, role order
    outputs: tuple[str, ...] = ()  # output member names, role order
    values: dict[str, list[float]] = field(default_factory=dict)
    convention: str = "ros2"
    convention_source: str = ""

    def to_json(self) -> str:
        return json.dumps(self.values)


class _Failure(Exception):
    pass


def run_map(
    path: str,
    transmission: str,
    to: str,
    *,
    position: str | None = None,
    velocity: str | None = None,
    effort: str | None = None,
    convention: str | None = None,
    xacro: XacroOptions | None = None,
) -> MapOutcome:
    """Load ``path``, find ``transmission`` and map the given comma-separated values.

    ``convention`` (``ros1``/``ros2``) overrides the effort convention of the file's loader.
    """
    try:
        return _run(path, transmission, to, {"position": position, "velocity": velocity,
                                             "effort": effort}, convention, xacro)
    except InputError as exc:
        return MapOutcome(2, str(exc))
    except _Failure as exc:
        return MapOutcome(2, f"{path}: {exc}")


def _run(
    path: str,
    name: str,
    to: str,
    raw: dict[str, str | None],
    convention: str | None,
    xacro: XacroOptions | None,
) -> MapOutcome:
    if to not in ("actuator", "joint"):
        raise _Failure(f"--to must be 'actuator' or 'joint', not {to!r}")
    requested = {q: text for q, text in raw.items() if text is not None}
    if not requested:
        raise _Failure("nothing to map: give --position, --velocity or --effort")
    t = _find(path, name, xacro)
    chosen = effort_convention(t, convention)
    try:
        eff = effective(t)
        tmap = from_effective(eff, chosen)
    except NotLoadable as exc:
        raise _Failure(f"transmission '{t.name}' cannot be loaded: {exc}") from None
    joints = _role_order(t.joints, ROLES_JOINT, tmap.joints)
    actuators = _role_order(t.actuators, ROLES_ACTUATOR, tmap.actuators)
    source, target = (joints, actuators) if to == "actuator" else (actuators, joints)
    values = {}
    for quantity in QUANTITIES:
        if quantity in requested:
            given = _parse(quantity, requested[quantity] or "", len(source), t.name)
            values[quantity] = _map(tmap, to, quantity, given, source, target)
            if not all(math.isfinite(v) for v in values[quantity]):
                raise _Failure(f"--{quantity}: the result through transmission '{t.name}' is "
                               "not a finite number (values or reductions too large or too "
                               "small)")
    return MapOutcome(0, None, t.name, to, tuple(_names(tmap, to, source, True)),
                      tuple(_names(tmap, to, target, False)), values, chosen,
                      source_of(convention))


def _find(path: str, name: str, xacro: XacroOptions | None) -> Transmission:
    from txtool.dialects.read import read_source

    found = [f.transmission for f in read_source(load(path, xacro=xacro or XacroOptions()))]
    for t in found:
        if t.name == name:
            return t
    names = ", ".join(sorted({f"'{t.name}'" for t in found})) or "none"
    raise _Failure(f"no transmission named '{name}' (transmissions: {names})")


def _role_order(members: tuple[Member, ...], roles: tuple[str, ...], loaded: tuple[str, ...]
                ) -> list[int]:
    """For each role position, the index of that member in the maths' order ``loaded``."""
    if len(loaded) == 1:
        return [0]
    by_role = {m.role: m.name for m in members if m.role in roles}
    if len(by_role) == len(roles) and len({m.role for m in members}) == len(members):
        ordered = [by_role[role] for role in roles]
    else:
        ordered = [m.name for m in members[: len(loaded)]]
    return [loaded.index(n) for n in ordered]


def _names(tmap: PointMap, to: str, order: list[int], is_input: bool) -> list[str]:
    joint_side = (to == "actuator") == is_input
    names = tmap.joints if joint_side else tmap.actuators
    return [names[i] for i in order]


def _parse(quantity: str, text: str, count: int, name: str) -> list[float]:
    parts = [p.strip() for p in text.split(",")]
    values = []
    for part in parts:
        value = parse_strict(part)
        if value is None:
            raise _Failure(f"--{quantity}: {part!r} is not a number")
        values.append(value)
    if len(values) != count:
        raise _Failure(f"--{quantity} needs {count} value(s) for transmission '{name}', "
                       f"got {len(values)}")
    return values


def _map(tmap: PointMap, to: str, quantity: str, given: list[float],
         source: list[int], target: list[int]) -> list[float]:
    x = [0.0] * len(given)
    for k, index in enumerate(source):
        x[index] = given[k]
    if to == "actuator":
        y = tmap.joint_to_actuator(quantity, x)
    else:
        y = tmap.actuator_to_joint(quantity, x)
    return [float(y[index]) for index in target]


def _show(value: float) -> str:
    # Twelve significant digits hide the last-bit noise of the maths (2.9999999999999996).
    return format_float(float(f"{value:.12g}"))


def render_text(outcome: MapOutcome) -> str:
    """A small table: one row per quantity, one column per output member (role order)."""
    from rich.console import Console
    from rich.markup import escape
    from rich.table import Table

    from txtool.io.printable import printable

    def text(name: str) -> str:  # a name from the file: shown as written, never as markup
        return escape(printable(name))

    src, dst = ("joint", "actuator") if outcome.to == "actuator" else ("actuator", "joint")
    table = Table(title=f"transmission '{text(outcome.transmission)}': {src} -> {dst}")
    table.add_column("quantity")
    for name in outcome.outputs:
        table.add_column(f"{dst} '{text(name)}'", justify="right")
    for quantity, values in outcome.values.items():
        table.add_row(quantity, *(_show(v) for v in values))
    buffer = io.StringIO()
    console = Console(file=buffer, width=100, color_system=None, highlight=False,
                      emoji=False)
    console.print(table)
    if "effort" in outcome.values:
        console.print(f"effort convention: {outcome.convention} ({_LOADERS[outcome.convention]} "
                      f"map, from {outcome.convention_source})", markup=False)
    return buffer.getvalue()
