"""Static gravity loads the URDF's effort limits cannot carry: an undescribed counterbalance.

Some robots hold part of their weight with springs that the URDF leaves out: PR2's shoulder
counterbalance, TIAGo's base suspension. Their actuators' effort limits then sit below the
gravity torque at rest, and a self-check would fail on the URDF, not on the transmissions.

A joint whose *static* load, the gravity torque ``g(q_ref)`` at the reference pose, exceeds
the joint torque its actuators can give (their effort limits through the robot's effort map)
is taken to have such a counterbalance. The counterbalance carries what exceeds ``KEEP`` of
that capacity, as a torque on the joint, applied to the plant directly and known to the
controller, which subtracts it from its command. The actuator keeps the rest of the gravity and
the whole dynamic part (``M qdd + C qd``, damping, friction), and it is checked on that.

The carried torque is a function of the reference alone, the same for every config, so it
cannot hide a fault of the transmissions: their sign, reduction or offset still reach the
actuator's share and the position estimate.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

KEEP = 0.5  # share of a joint's torque capacity its actuator keeps for the static load
# A static load beyond this many times the capacity is taken as a wrong effort limit, not as an
# undescribed spring: real counterbalances leave the motor a sizeable share (PR2's shoulder
# needs 1.5x its limit, TIAGo's suspension 1.16x); a limit written 50 times too small is not one.
MAX_LOAD = 4.0

Parts = tuple[np.ndarray, np.ndarray, np.ndarray]
Dynamics = Callable[[np.ndarray, np.ndarray, np.ndarray], Parts]


@dataclass(frozen=True)
class Counterbalance:
    """Per DoF: the static torque the actuator keeps (inf where nothing is carried)."""

    joints: tuple[str, ...]
    units: tuple[str, ...]  # rad or m per DoF
    keep: np.ndarray
    capacity: np.ndarray  # the joint torque the actuators can give (inf: no limit)
    load: np.ndarray  # peak static load where it was found (the planned or given motion)

    @property
    def active(self) -> bool:
        return bool(np.isfinite(self.keep).any())

    def carried(self, gravity: np.ndarray) -> np.ndarray:
        """Rows of joint torques: the part of ``gravity`` beyond what each actuator keeps."""
        return gravity - np.clip(gravity, -self.keep, self.keep)

    def relieve(self, dynamics: Dynamics) -> Dynamics:
        """``dynamics`` whose static part leaves out the carried torque."""

        def parts(x: np.ndarray, xd: np.ndarray, xdd: np.ndarray) -> Parts:
            quadratic, linear, static = dynamics(x, xd, xdd)
            gravity = dynamics(x, np.zeros_like(xd), np.zeros_like(xdd))[2]
            return quadratic, linear, static - self.carried(gravity)

        return parts

    @property
    def refused(self) -> list[str]:
        """Notes on the joints whose load is too far beyond their limit to assume a spring."""
        notes = []
        for v in np.nonzero(self.load > MAX_LOAD * self.capacity)[0]:
            unit = "N" if self.units[v] == "m" else "N·m"
            notes.append(
                f"joint '{self.joints[v]}': gravity needs up to {self.load[v]:.4g} {unit}, "
                f"{self.load[v] / self.capacity[v]:.3g} times its effort limit "
                f"{self.capacity[v]:.4g} {unit}: no counterbalance is assumed beyond "
                f"{MAX_LOAD:g} times the limit (the limit is more likely wrong than a spring "
                "that large left out)")
        return notes

    def notes(self, gravity: np.ndarray) -> list[str]:
        """One note per joint the counterbalance carries a part of along the run's reference
        (``gravity``: its rows). The joints were found on the planned motion; the one that runs
        may have been cut since, and load them less than their limit, or no more than half."""
        load = np.abs(gravity).max(axis=0, initial=0.0)
        carried = np.abs(self.carried(gravity)).max(axis=0, initial=0.0)
        notes = []
        for v in self._carrying(carried):
            unit = "N" if self.units[v] == "m" else "N·m"
            limit = f"{self.capacity[v]:.4g} {unit}"
            how = (f"beyond its effort limit {limit}" if load[v] > self.capacity[v] else
                   f"{100 * load[v] / self.capacity[v]:.0f}% of its effort limit {limit} "
                   "(beyond the limit on the motion before it was cut)")
            notes.append(
                f"joint '{self.joints[v]}': gravity needs up to {load[v]:.4g} {unit} to hold it, "
                f"{how}: a counterbalance or spring the URDF does not describe is assumed to "
                f"carry up to {carried[v]:.4g} {unit} (what exceeds {100 * KEEP:.0f}% of the "
                "limit), applied to the joint directly; the actuator is checked on the rest "
                "(--no-counterbalance: off)")
        return notes

    def table(self, gravity: np.ndarray) -> dict[str, dict[str, float | str]]:
        """Per counterbalanced joint: static load, limit, carried (peaks), units (for JSON)."""
        load = np.abs(gravity).max(axis=0, initial=0.0)
        carried = np.abs(self.carried(gravity)).max(axis=0, initial=0.0)
        return {self.joints[v]: {"static_load": float(load[v]),
                                 "limit": float(self.capacity[v]),
                                 "carried": float(carried[v]),
                                 "units": "N" if self.units[v] == "m" else "N·m"}
                for v in self._carrying(carried)}

    def _carrying(self, carried: np.ndarray) -> list[int]:
        """The DoFs with a counterbalance that carries something of ``carried`` (peaks)."""
        return [int(v) for v in np.nonzero(np.isfinite(self.keep) & (carried > 0))[0]]


def capacity(eff_j2a: np.ndarray, actuator_effort: np.ndarray) -> np.ndarray:
    """Per DoF, the largest static joint torque its actuators give alone: min of L_a / |E_aj|."""
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.where(eff_j2a != 0, actuator_effort[:, None] / np.abs(eff_j2a), np.inf)
    return ratio.min(axis=0, initial=np.inf)


def find(joints: tuple[str, ...], units: tuple[str, ...], gravity: np.ndarray,
         eff_j2a: np.ndarray, actuator_effort: np.ndarray) -> Counterbalance:
    """The joints whose static load (rows of ``gravity``) exceeds their torque capacity."""
    limit = capacity(eff_j2a, actuator_effort)
    load = np.abs(gravity).max(axis=0, initial=0.0)
    keep = np.where((load > limit) & (load <= MAX_LOAD * limit), KEEP * limit, np.inf)
    return Counterbalance(joints, units, keep, limit, load)
