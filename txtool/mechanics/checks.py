"""Numeric checks of a transmission's maps: invertibility, round trip, power conservation.

Joint values are sampled on a grid across each joint's limits (``JointInfo.position_range()``,
+-pi where absent); velocities and efforts across +-their URDF limits (+-1 where absent).
"""

from __future__ import annotations

import itertools
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Literal

import numpy as np

from txtool.mechanics import linear
from txtool.mechanics.maps import TransmissionMap, from_transmission
from txtool.mechanics.samples import joint_samples
from txtool.model.core import Transmission
from txtool.model.robot import JointInfo
from txtool.model.semantics import NotLoadable

ROUND_TRIP_TOL = 1e-12
POWER_TOL = 1e-12
QUANTITIES = ("position", "velocity", "effort")
Status = Literal["ok", "failed", "not loadable"]


@dataclass(frozen=True)
class Invertibility:
    determinant: float
    condition_number: float
    reason: str | None  # why A is (numerically) singular; None when it is invertible


@dataclass(frozen=True)
class RoundTrip:
    """Worst relative error of joint -> actuator -> joint per quantity."""

    errors: dict[str, float]
    samples: int
    tolerance: float = ROUND_TRIP_TOL

    @property
    def ok(self) -> bool:
        return all(error <= self.tolerance for error in self.errors.values())


@dataclass(frozen=True)
class TransmissionCheck:
    """All checks of one transmission; ``problems`` are one-line reasons (empty when ok)."""

    name: str
    status: Status
    invertibility: Invertibility | None = None
    round_trip: RoundTrip | None = None
    power_mismatch: float | None = None
    problems: tuple[str, ...] = field(default=())


def invertibility(tmap: TransmissionMap) -> Invertibility:
    a = [[float(x) for x in row] for row in tmap.A]
    return Invertibility(
        linear.determinant(a), linear.matrix_condition(a), linear.matrix_singular(a)
    )


def sample_joint_values(
    tmap: TransmissionMap,
    joints: Mapping[str, JointInfo] | None = None,
    per_axis: int = 9,
) -> dict[str, np.ndarray]:
    """Grids of joint position, velocity and effort, shape ``(m, n)`` in ``tmap.joints`` order."""
    grids = joint_samples(tmap.joints, joints, per_axis)
    return {quantity: np.array(values, dtype=float) for quantity, values in grids.items()}


def round_trip(
    tmap: TransmissionMap,
    joints: Mapping[str, JointInfo] | None = None,
    per_axis: int = 9,
    tolerance: float = ROUND_TRIP_TOL,
) -> RoundTrip:
    """joint -> actuator -> joint on the sample grid; relative to max(1, |value|, |offset|)."""
    samples = sample_joint_values(tmap, joints, per_axis)
    errors = {}
    for quantity, x in samples.items():
        back = tmap.actuator_to_joint(quantity, tmap.joint_to_actuator(quantity, x))
        scale = np.maximum(1.0, np.abs(x))
        if quantity == "position":
            scale = np.maximum(scale, np.abs(tmap.offset))
        errors[quantity] = float(np.max(np.abs(back - x) / scale))
    return RoundTrip(errors, len(samples["position"]), tolerance)


def power_residual(tmap: TransmissionMap) -> float:
    """Worst ``|tau_a . qdot_a - tau_j . qdot_j|`` relative to the size of the two powers.

    Every pair of unit and diagonal vectors in actuator effort and joint velocity is tried, so
    any effort map other than ``A^T`` shows up.
    """
    n = tmap.size
    basis = np.array(list(itertools.product((-1.0, 0.0, 1.0), repeat=n)))
    basis = basis[np.any(basis != 0.0, axis=1)]
    tau_a, qdot_j = (arr.reshape(-1, n) for arr in np.broadcast_arrays(
        basis[:, None, :], basis[None, :, :]))
    tau_j = tmap.actuator_to_joint("effort", tau_a)
    qdot_a = tmap.joint_to_actuator("velocity", qdot_j)
    p_a = np.sum(tau_a * qdot_a, axis=-1)
    p_j = np.sum(tau_j * qdot_j, axis=-1)
    scale = np.maximum(
        np.linalg.norm(tau_a, axis=-1) * np.linalg.norm(qdot_a, axis=-1),
        np.linalg.norm(tau_j, axis=-1) * np.linalg.norm(qdot_j, axis=-1),
    )
    return float(np.max(np.abs(p_a - p_j) / scale))


def check_map(
    tmap: TransmissionMap, joints: Mapping[str, JointInfo] | None = None
) -> TransmissionCheck:
    inv = invertibility(tmap)
    problems = []
    if inv.reason:
        problems.append(f"{inv.reason} (condition number {inv.condition_number:.3g})")
    trip = round_trip(tmap, joints)
    for quantity, error in trip.errors.items():
        if error > trip.tolerance:
            problems.append(f"{quantity} round trip joint -> actuator -> joint is off by "
                            f"{error:.3g} (relative)")
    power = power_residual(tmap)
    if power > POWER_TOL:
        problems.append(f"the {tmap.convention} effort map does not conserve power "
                        f"(relative mismatch {power:.3g})")
    status: Status = "failed" if problems else "ok"
    return TransmissionCheck(tmap.name, status, inv, trip, power, tuple(problems))


def check_transmission(
    t: Transmission,
    joints: Mapping[str, JointInfo] | None = None,
    convention: str = "ros2",
) -> TransmissionCheck:
    try:
        tmap = from_transmission(t, convention)
    except NotLoadable as exc:
        return TransmissionCheck(t.name, "not loadable", problems=(str(exc),))
    return check_map(tmap, joints)


def check_all(
    transmissions: Sequence[Transmission],
    joints: Mapping[str, JointInfo] | None = None,
    convention: str = "ros2",
) -> list[TransmissionCheck]:
    """One result per transmission, in the given order."""
    return [check_transmission(t, joints, convention) for t in transmissions]
