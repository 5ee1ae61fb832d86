"""Do two configs of one robot drive the actuators the same way?

Transmissions are paired by the set of their joint names. For each pair the same joint
positions, velocities and efforts are mapped to actuator space through each config's loaded
maps (:mod:`txtool.model.semantics`), and the results are compared per joint and actuator NAME:
ros2_control orders handles by name, so a conversion that keeps the numbers but lists the
members in another order can bind a parameter to a different joint.

Each side maps efforts with its own loader's four-bar map (:mod:`txtool.mechanics.convention`)
unless one convention is imposed on both. By default, therefore, a ROS 1 four-bar and its ROS 2
conversion differ in effort, as ros_control and ros2_control do.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Literal

import numpy as np

from txtool.mechanics.checks import sample_joint_values
from txtool.mechanics.convention import effort_convention
from txtool.mechanics.maps import TransmissionMap, from_effective
from txtool.model.core import Transmission
from txtool.model.robot import JointInfo
from txtool.model.semantics import NotLoadable, effective

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


def _load(t: Transmission, convention: str | None) -> TransmissionMap:
    return from_effective(effective(t), effort_convention(t, convention))


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
    differences, reason = _compare_maps(ma, mb, joints)
    status: Status = "differs" if reason else "equivalent"
    return EquivalenceRow(key, ta.name, tb.name, status, differences, reason)


def _name_mismatch(ma: TransmissionMap, mb: TransmissionMap) -> str:
    for noun, x, y in (("joints", ma.joints, mb.joints), ("actuators", ma.actuators, mb.actuators)):
        if sorted(x) != sorted(y):
            return f"loaded {noun} differ: {_names(x)} vs {_names(y)}"
    return ""


def _names(names: Sequence[str]) -> str:
    return ", ".join(f"'{n}'" for n in names)


def _compare_maps(
    ma: TransmissionMap, mb: TransmissionMap, joints: Mapping[str, JointInfo] | None
) -> tuple[dict[str, float], str]:
    joint_names = sorted(ma.joints)
    actuator_names = sorted(ma.actuators)
    samples = sample_joint_values(ma, joints, per_axis=5)
    # Samples come in ma.joints order; re-key them to sorted names for both maps.
    to_sorted = [ma.joints.index(n) for n in joint_names]
    differences: dict[str, float | None] = {}
    reason = ""
    for quantity in QUANTITIES:
        x = samples[quantity][:, to_sorted]
        ya = _by_name(ma, quantity, x, joint_names, actuator_names)
        yb = _by_name(mb, quantity, x, joint_names, actuator_names)
        diff = _difference(ya, yb)
        worst = float(np.max(diff))
        differences[quantity] = worst if np.isfinite(worst) else None
        # Relative to each actuator's largest value over the samples: scale-free.
        scale = np.fmax(np.abs(ya), np.abs(yb)).max(axis=0)
        with np.errstate(invalid="ignore"):
            excess = np.where(np.isinf(diff), np.inf, diff - RTOL * scale)
        if not reason and np.max(excess) > 0:
            row, col = np.unravel_index(int(np.argmax(excess)), excess.shape)
            at = ", ".join(f"{n}={x[row, i]:.6g}" for i, n in enumerate(joint_names))
            reason = (f"actuator '{actuator_names[col]}' {quantity} differs by "
                      f"{diff[row, col]:.6g} at joint values ({at})")
    return differences, reason


def _difference(ya: np.ndarray, yb: np.ndarray) -> np.ndarray:
    """``|ya - yb|``; 0 where both hold the same value (inf or nan included), inf where the
    two differ and one is not finite (huge reductions overflow)."""
    with np.errstate(all="ignore"):
        diff = np.abs(ya - yb)
    same = (ya == yb) | (np.isnan(ya) & np.isnan(yb))
    return np.where(same, 0.0, np.where(np.isnan(diff), np.inf, diff))


def _by_name(
    tmap: TransmissionMap,
    quantity: str,
    x: np.ndarray,
    joint_names: list[str],
    actuator_names: list[str],
) -> np.ndarray:
    """Map joint values given in ``joint_names`` order; actuator values in ``actuator_names``."""
    inputs = x[:, [joint_names.index(n) for n in tmap.joints]]
    out = tmap.joint_to_actuator(quantity, inputs)
    return out[:, [tmap.actuators.index(n) for n in actuator_names]]
