"""Do two configs of one robot drive the actuators the same way?

Transmissions are paired by the set of their joint names. For each pair the same joint
positions, velocities and efforts are mapped to actuator space through each config's loaded
maps (:mod:`txtool.model.semantics`), and the results are compared per joint and actuator NAME:
ros2_control orders handles by name, so a conversion that keeps the numbers but lists the
members in another order can bind a parameter to a different joint.

Each side maps efforts with its own loader's four-bar map (:mod:`txtool.mechanics.convention`)
unless one convention is imposed on both. By default, therefore, a ROS 1 four-bar and its ROS 2
conversion differ in effort, as ros_control and ros2_control do.

The handful of sampled values is mapped in plain Python floats (the same IEEE operations as
:mod:`txtool.mechanics.maps`, so the same bits, with :mod:`txtool.mechanics.points` where a
division by zero needs IEEE's infinities), so ``roundtrip`` needs no numpy. Two sides that
read the same parameters (bit for bit) through the same formulas are equivalent without
sampling: every sample would map to the same bits.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Literal, NamedTuple

from txtool.mechanics.convention import effort_convention
from txtool.mechanics.formulas import FORMULAS, formula_key, read_parameters
from txtool.mechanics.samples import Sample, joint_samples
from txtool.model.core import Transmission
from txtool.model.robot import JointInfo
from txtool.model.semantics import Effective, NotLoadable, effective

Status = Literal["equivalent", "differs", "missing", "not loadable"]
QUANTITIES = ("position", "velocity", "effort")
RTOL = 1e-9


@dataclass(frozen=True)
class EquivalenceRow:
    """One transmission pair. ``a``/``b`` are the transmission names (None when missing)."""

    joints: tuple[str, ...]
    a: str | None
    b: str | None
    status: Status
    # Max abs diff per quantity; None where it is not a finite number (values that overflow).
    differences: dict[str, float | None] = field(default_factory=dict)
    reason: str = ""


@dataclass(frozen=True)
class EquivalenceReport:
    rows: tuple[EquivalenceRow, ...]

    @property
    def equivalent(self) -> bool:
        return all(row.status == "equivalent" for row in self.rows)

    def row_for(self, name: str) -> EquivalenceRow | None:
        """The row of transmission ``name`` of the first config."""
        return next((row for row in self.rows if row.a == name), None)


def compare(
    a: Sequence[Transmission],
    b: Sequence[Transmission],
    joints: Mapping[str, JointInfo] | None = None,
    *,
    convention: str | None = None,
) -> EquivalenceReport:
    """Compare two configs; ``joints`` gives the sampling ranges (URDF limits).

    ``convention`` (``ros2`` or ``ros1``) imposes one effort convention on both sides; by
    default each side uses its own loader's.
    """
    unused = list(b)
    rows = []
    for ta in a:
        key = _joint_set(ta)
        tb = next((t for t in unused if _joint_set(t) == key), None)
        if tb is None:
            rows.append(EquivalenceRow(key, ta.name, None, "missing",
                                       reason="no transmission of these joints in the second"))
            continue
        unused.remove(tb)
        rows.append(compare_pair(ta, tb, joints, convention=convention))
    for tb in unused:
        rows.append(EquivalenceRow(_joint_set(tb), None, tb.name, "missing",
                                   reason="no transmission of these joints in the first"))
    return EquivalenceReport(tuple(rows))


def _joint_set(t: Transmission) -> tuple[str, ...]:
    return tuple(sorted({j.name for j in t.joints}))


class _Loaded(NamedTuple):
    """A loaded transmission's parameters and the effort convention it runs."""

    eff: Effective
    convention: str

    @property
    def joints(self) -> tuple[str, ...]:
        return self.eff.joints

    @property
    def actuators(self) -> tuple[str, ...]:
        return self.eff.actuators

    def reads(self) -> tuple:
        """What its joint-to-actuator maps read: members in order, formulas, parameters."""
        eff = self.eff
        formulas = tuple(FORMULAS[formula_key(eff.kind, quantity, self.convention)][1]
                         for quantity in QUANTITIES)
        return (eff.joints, eff.actuators, formulas, read_parameters(
            eff.kind, eff.actuator_reduction, eff.joint_reduction, eff.joint_offset))

    def joint_to_actuator(self, quantity: str, rows: list[Sample]) -> list[Sample]:
        eff = self.eff
        formula = FORMULAS[formula_key(eff.kind, quantity, self.convention)][1]
        ar, jr, off = eff.actuator_reduction, eff.joint_reduction, eff.joint_offset
        try:
            return [formula(row, ar, jr, off) for row in rows]
        except ZeroDivisionError:  # reductions whose product underflows to 0
            return self._ieee(quantity, rows)

    def _ieee(self, quantity: str, rows: list[Sample]) -> list[Sample]:
        """IEEE's infinities and NaN (as numpy and the loaders' C++ give them) where Python
        refuses to divide by zero."""
        from txtool.mechanics.points import from_effective

        maps = from_effective(self.eff, self.convention)
        return [maps.joint_to_actuator(quantity, row) for row in rows]


def _load(t: Transmission, convention: str | None) -> _Loaded:
    return _Loaded(effective(t), effort_convention(t, convention))


def compare_pair(
    ta: Transmission,
    tb: Transmission,
    joints: Mapping[str, JointInfo] | None = None,
    *,
    convention: str | None = None,
) -> EquivalenceRow:
    key = _joint_set(ta)
    maps = []
    for side, t in (("first", ta), ("second", tb)):
        try:
            maps.append(_load(t, convention))
        except NotLoadable as exc:
            return EquivalenceRow(key, ta.name, tb.name, "not loadable",
                                  reason=f"{side}: transmission '{t.name}': {exc}")
    ma, mb = maps
    mismatch = _name_mismatch(ma, mb)
    if mismatch:
        return EquivalenceRow(key, ta.name, tb.name, "differs", reason=mismatch)
    if ma.reads() == mb.reads():
        # The same formulas on the same bits map every sample to the same bits: sampling
        # would find a difference of 0 everywhere (a conversion most often gives this).
        return EquivalenceRow(key, ta.name, tb.name, "equivalent",
                              dict.fromkeys(QUANTITIES, 0.0))
    differences, reason = _compare_maps(ma, mb, joints)
    status: Status = "differs" if reason else "equivalent"
    return EquivalenceRow(key, ta.name, tb.name, status, differences, reason)


def _name_mismatch(ma: _Loaded, mb: _Loaded) -> str:
    for noun, x, y in (("joints", ma.joints, mb.joints), ("actuators", ma.actuators, mb.actuators)):
        if sorted(x) != sorted(y):
            return f"loaded {noun} differ: {_names(x)} vs {_names(y)}"
    return ""


def _names(names: Sequence[str]) -> str:
    return ", ".join(f"'{n}'" for n in names)


def _compare_maps(
    ma: _Loaded, mb: _Loaded, joints: Mapping[str, JointInfo] | None
) -> tuple[dict[str, float | None], str]:
    joint_names = sorted(ma.joints)
    actuator_names = sorted(ma.actuators)
    samples = joint_samples(ma.joints, joints, per_axis=5)
    # Samples come in ma.joints order; re-key them to sorted names for both maps.
    to_sorted = [ma.joints.index(n) for n in joint_names]
    differences: dict[str, float | None] = {}
    reason = ""
    for quantity in QUANTITIES:
        x = [tuple(row[i] for i in to_sorted) for row in samples[quantity]]
        ya = _by_name(ma, quantity, x, joint_names, actuator_names)
        yb = _by_name(mb, quantity, x, joint_names, actuator_names)
        diff = [[_difference(a, b) for a, b in zip(ra, rb, strict=True)]
                for ra, rb in zip(ya, yb, strict=True)]
        worst = max(max(row) for row in diff)
        differences[quantity] = worst if math.isfinite(worst) else None
        if not reason:
            reason = _excess(quantity, x, ya, yb, diff, joint_names, actuator_names)
    return differences, reason


def _excess(quantity: str, x: list[Sample], ya: list[Sample], yb: list[Sample],
            diff: list[list[float]], joint_names: list[str], actuator_names: list[str]) -> str:
    """Why the worst difference beyond RTOL of each actuator's largest value over the samples
    (scale-free) is too large, or "" when none is. A value that is nan in both maps makes its
    actuator's scale nan, and the quantity then passes (as the numpy reduction it mirrors)."""
    scale = [_column_max([_fmax(abs(ra[c]), abs(rb[c])) for ra, rb in zip(ya, yb, strict=True)])
             for c in range(len(actuator_names))]
    excess = [[math.inf if d == math.inf else d - RTOL * scale[c] for c, d in enumerate(row)]
              for row in diff]
    if any(e != e for row in excess for e in row):
        return ""
    top = max(max(row) for row in excess)
    if not top > 0:
        return ""
    row, col = next((r, c) for r, values in enumerate(excess) for c, e in enumerate(values)
                    if e == top)
    at = ", ".join(f"{n}={x[row][i]:.6g}" for i, n in enumerate(joint_names))
    return (f"actuator '{actuator_names[col]}' {quantity} differs by "
            f"{diff[row][col]:.6g} at joint values ({at})")


def _fmax(a: float, b: float) -> float:
    """The larger of two values, ignoring a nan (``numpy.fmax``)."""
    if a != a:
        return b
    if b != b:
        return a
    return max(a, b)


def _column_max(values: list[float]) -> float:
    """The largest value; nan if any is nan (``numpy.max``)."""
    return math.nan if any(v != v for v in values) else max(values)


def _difference(a: float, b: float) -> float:
    """``|a - b|``; 0 where both hold the same value (inf or nan included), inf where the two
    differ and one is not finite (huge reductions overflow)."""
    if a == b or (a != a and b != b):
        return 0.0
    diff = abs(a - b)
    return math.inf if diff != diff else diff


def _by_name(
    loaded: _Loaded,
    quantity: str,
    x: list[Sample],
    joint_names: list[str],
    actuator_names: list[str],
) -> list[Sample]:
    """Map joint values given in ``joint_names`` order; actuator values in ``actuator_names``."""
    take = [joint_names.index(n) for n in loaded.joints]
    out = loaded.joint_to_actuator(quantity, [tuple(row[i] for i in take) for row in x])
    give = [loaded.actuators.index(n) for n in actuator_names]
    return [tuple(row[i] for i in give) for row in out]
