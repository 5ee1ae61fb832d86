"""What one simulated run is made of: the controller's gains, the loop's matrices and the
history rows the loop fills (:class:`Plan`), and the layout of a row.

:mod:`txtool.simulation.setup` builds a plan, :mod:`txtool.simulation.loop` (and the delayed
loop of :mod:`txtool.simulation.ring`) advance it.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import pinocchio as pin

from txtool.simulation.model import RobotModel
from txtool.simulation.plant import Dynamics
from txtool.simulation.sensing import Encoder


@dataclass
class Controller:
    """Gains and what the controller knows (per DoF) besides the candidate's maps."""

    kp: np.ndarray
    kd: np.ndarray
    ki: np.ndarray
    i_limit: np.ndarray  # bound of |integral(e)| (i_clamp / ki), inf when unbounded
    damping: np.ndarray  # compensated viscous damping
    friction: np.ndarray  # compensated Coulomb friction, on the sign of the reference velocity


@dataclass
class Plan:
    robot: RobotModel
    dt: float
    steps: int
    rows: np.ndarray  # (steps + 1, W)
    slots: dict[str, slice]
    H: np.ndarray
    C: np.ndarray
    PD: np.ndarray
    Phi: np.ndarray
    limit: np.ndarray
    plant: tuple[pin.Model, pin.Data]
    ctrl: tuple[pin.Model, pin.Data]
    plant_block: np.ndarray | None  # off-diagonal rotor inertia (or mimic): crba + solve
    ctrl_block: np.ndarray | None
    dynamics: Dynamics
    bias: bool
    q_ref: np.ndarray
    ki: np.ndarray | None = None
    i_limit: np.ndarray | None = None
    delay: bool = False  # the effort computed at step k acts from step k + 1 (sensing.py)
    encoder: Encoder | None = None  # quantised readings in the "enc"/"encv" slots
    diverged_at: int | None = None
    done: int = 0
    extras: dict[str, object] = field(default_factory=dict)

    def column(self, name: str) -> np.ndarray:
        return self.rows[:, self.slots[name]]


def layout(nv: int, na: int, *, unobserved: bool, friction_ff: bool,
           encoder: bool = False, carried: bool = False) -> dict[str, slice]:
    """Columns of a history row: what each step writes first (up to ``ta``), then the columns
    precomputed for every step (from ``one`` on)."""
    sizes = [("sat", na), ("est", 3 * nv + na), ("tj", nv), ("ta", na), ("x", nv), ("v", nv),
             ("a", nv), ("one", 1), ("ff", nv)]
    if carried:
        sizes.append(("cb", nv))  # joint torque of an undescribed counterbalance
    if unobserved:
        sizes += [("qref", nv), ("vref", nv)]
    if friction_ff:
        sizes.append(("fric", nv))
    if encoder:
        sizes += [("enc", na), ("encv", na)]  # actuator readings: counts, finite differences
    slots, start = {}, 0
    for name, size in sizes:
        slots[name] = slice(start, start + size)
        start += size
    return slots
