"""What one simulated run is made of (:class:`Plan`), what changes as it runs
(:class:`RunState`), and the layout of a history row.

As Pinocchio separates a ``Model`` from its ``Data``, a plan holds what is fixed for a run: the
controller's gains, the loop's matrices, the models, the first row's state and every row's
precomputed columns. A run state holds what the steps change: the history rows, how far the
run got, the integral term, the Pinocchio ``Data`` and the delayed loop's working rows. One
plan can be run any number of times, each run from a fresh state.

:mod:`txtool.simulation.setup` builds a plan, :mod:`txtool.simulation.loop` (and the delayed
loop of :mod:`txtool.simulation.ring`) runs it.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

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


@dataclass(frozen=True)
class Plan:
    """What is fixed for a run (the arrays are not written to by the loop)."""

    robot: RobotModel
    dt: float
    steps: int
    start_rows: np.ndarray  # (steps + 1, W): row 0's state, every row's precomputed columns
    slots: dict[str, slice]
    H: np.ndarray
    C: np.ndarray
    PD: np.ndarray
    Phi: np.ndarray
    limit: np.ndarray
    plant: pin.Model
    ctrl: pin.Model
    plant_block: np.ndarray | None  # off-diagonal rotor inertia (or mimic): crba + solve
    ctrl_block: np.ndarray | None
    dynamics: Dynamics
    bias: bool
    q_ref: np.ndarray
    ki: np.ndarray | None = None
    i_limit: np.ndarray | None = None
    delay: bool = False  # the effort computed at step k acts from step k + 1 (sensing.py)
    encoder: Encoder | None = None  # quantised readings in the "enc"/"encv" slots

    @property
    def width(self) -> int:
        return self.start_rows.shape[1]


@dataclass
class RunState:
    """What one run of a plan changes, step by step."""

    rows: np.ndarray  # (steps + 1, W): the history, filled by the loop
    slots: dict[str, slice]
    plant_data: pin.Data
    ctrl_data: pin.Data
    integral: np.ndarray  # the integral term's accumulated error, per DoF
    done: int = 0  # rows 0 to done hold a state
    diverged_at: int | None = None
    ring: Any = None  # the delayed loop's working rows (ring.Ring), made on its first block

    @classmethod
    def begin(cls, plan: Plan) -> RunState:
        return cls(rows=plan.start_rows.copy(), slots=plan.slots,
                   plant_data=plan.plant.createData(), ctrl_data=plan.ctrl.createData(),
                   integral=np.zeros(plan.robot.nv))

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
