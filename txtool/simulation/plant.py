"""The plant's integration over one control period: implicit damping, stiction, sub-steps.

The actuator efforts are held over the control period (zero-order hold). Within it the plant
takes ``substeps`` steps of ``h = dt / substeps``, each a linearly implicit Euler step::

    (M + h D) (v' - v) = h (tau - nle(q, v) - D v - f),    x' = x + h v'

so viscous damping ``D`` is integrated implicitly (stable for any ``h``; Pinocchio's
``armature`` carries the ``h D`` term, so ``aba`` solves it when nothing else is needed). The
Coulomb friction impulse ``h f`` is the one that makes the step a proximal (velocity-level)
problem: each joint with friction either slides, ``f = F sign(v')``, or sticks, ``v' = 0`` with
``|f| <= F``. That is a small LCP in the friction joints on the Delassus matrix
``G = (M + h D)^-1`` restricted to them, solved exactly by an active set. A joint held below
its friction torque stays still (no chatter); one pushed past it slides.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
import pinocchio as pin

MAX_SUBSTEPS = 4
STIFF = 2.0  # largest h * damping / inertia per sub-step (implicit Euler is stable beyond)
ACTIVE_SET_ROUNDS = 12
PGS_SWEEPS = 200
PGS_TOL = 1e-12


@dataclass
class Dynamics:
    """How the plant advances over one control step ``dt``."""

    model: pin.Model  # armature = rotor inertia + h * damping
    data: pin.Data
    dt: float
    substeps: int
    damping: np.ndarray
    friction: np.ndarray | None  # Coulomb friction per DoF, None when there is none
    block: np.ndarray | None  # off-diagonal rotor inertia, or zeros for mimic joints
    config: Callable[[np.ndarray, np.ndarray], None] | None  # x -> Pinocchio q
    nq: int
    mode: np.ndarray = field(default_factory=lambda: np.zeros(0))  # stick 0, slide +-1
    note: str = ""  # why there are sub-steps

    @property
    def simple(self) -> bool:
        """One ``aba`` per control step with damping folded into armature (the fast loop)."""
        return self.substeps == 1 and self.friction is None and self.block is None

    def advance(self, x: np.ndarray, v: np.ndarray, tau: np.ndarray, out: np.ndarray) -> None:
        """Write the state ``[x' v']`` after one control step into ``out`` (``tau`` held)."""
        nv = len(v)
        h = self.dt / self.substeps
        xs, vs = x.copy(), v.copy()
        q = np.zeros(self.nq) if self.config is not None else xs
        for _ in range(self.substeps):
            if self.config is not None:
                self.config(xs, q)
            vs = self._velocity(q, vs, tau, h)
            xs += h * vs
        out[:nv] = xs
        out[nv:] = vs

    def _velocity(self, q: np.ndarray, v: np.ndarray, tau: np.ndarray, h: float) -> np.ndarray:
        rhs = tau - self.damping * v
        if self.friction is None and self.block is None:
            return v + h * pin.aba(self.model, self.data, q, v, rhs)
        rhs -= pin.nonLinearEffects(self.model, self.data, q, v)
        if self.block is None:
            inverse = pin.computeMinverse(self.model, self.data, q)
        else:
            mass = pin.crba(self.model, self.data, q).copy()  # its upper triangle is filled
            lower = np.tril_indices(len(v), -1)
            mass[lower] = mass.T[lower]
            mass += self.block
            if self.friction is None:
                return v + h * np.linalg.solve(mass, rhs)
            inverse = np.linalg.inv(mass)
        free = v + h * (inverse @ rhs)
        return self._stick_or_slide(inverse, free, h * self.friction)  # type: ignore[operator]

    def _stick_or_slide(self, inverse: np.ndarray, free: np.ndarray, bound: np.ndarray
                        ) -> np.ndarray:
        """Velocity after the friction impulses ``p`` (``|p_i| <= bound_i``), exactly.

        Active set: each friction joint sticks (``w_i = 0``, ``|p_i| <= b_i``) or slides
        (``p_i = b_i sign(w_i)``); the guess starts from the last step and is corrected until
        consistent. Projected Gauss-Seidel settles the rare case where that cycles.
        """
        rows = np.flatnonzero(bound > 0)
        b = bound[rows]
        columns = inverse[:, rows]
        G = columns[rows]
        w_free = free[rows]
        mode = self.mode if len(self.mode) == len(rows) else np.sign(w_free)
        for _ in range(ACTIVE_SET_ROUNDS):
            p = b * mode
            stuck = np.flatnonzero(mode == 0)
            if stuck.size:
                slide = np.flatnonzero(mode)
                held = G[stuck]
                p[stuck] = np.linalg.solve(held[:, stuck],
                                           w_free[stuck] - held[:, slide] @ p[slide])
            w = w_free - G @ p
            breaks_free = stuck[np.abs(p[stuck]) > b[stuck]]
            stops = np.flatnonzero((w * mode <= 0) & (mode != 0))
            if not (breaks_free.size or stops.size):
                break
            mode = mode.copy()
            mode[breaks_free] = np.sign(p[breaks_free])
            mode[stops] = 0.0
        else:
            p = self._gauss_seidel(G, w_free, b)
            mode = np.where(np.abs(p) < b, 0.0, np.sign(p))
        self.mode = mode
        velocity = free - columns @ p
        velocity[rows[mode == 0]] = 0.0  # sticking: exactly at rest, not round-off
        return velocity

    def _gauss_seidel(self, G: np.ndarray, w_free: np.ndarray, b: np.ndarray) -> np.ndarray:
        p = np.zeros(len(b))
        diag = np.diag(G)
        for _ in range(PGS_SWEEPS):
            change = 0.0
            for i in range(len(b)):
                wi = w_free[i] - G[i] @ p
                new = min(max(p[i] + wi / diag[i], -b[i]), b[i])
                change = max(change, abs(new - p[i]))
                p[i] = new
            if change <= PGS_TOL * (1.0 + float(b.max())):
                break
        return p


def substeps_for(dt: float, damping: np.ndarray, inertia: np.ndarray) -> tuple[int, int | None]:
    """Sub-steps so that ``h * damping / inertia <= STIFF`` (capped); (count, stiffest DoF)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        rate = np.where(damping > 0, damping / inertia, 0.0)
    if not np.any(rate > 0):
        return 1, None
    stiffest = int(np.argmax(rate))
    wanted = dt * float(rate[stiffest]) / STIFF
    needed = math.ceil(wanted) if math.isfinite(wanted) else MAX_SUBSTEPS
    return max(1, min(needed, MAX_SUBSTEPS)), stiffest


def smallest_inertia(model: pin.Model, configs: np.ndarray) -> np.ndarray:
    """Per DoF, the smallest effective inertia ``1 / (M^-1)_jj`` over ``configs``.

    That is the inertia a joint's own torque meets when the other joints are free to move
    (armature included); it is at most the diagonal ``M_jj`` and smaller where joints couple.
    """
    data = model.createData()
    smallest = np.full(model.nv, math.inf)
    lower = np.tril_indices(model.nv, -1)
    for q in configs:
        mass = pin.crba(model, data, q).copy()
        mass[lower] = mass.T[lower]
        with np.errstate(divide="ignore"):
            try:
                effective = 1.0 / np.diag(np.linalg.inv(mass))
            except np.linalg.LinAlgError:
                effective = np.diag(mass)
        smallest = np.minimum(smallest, effective)
    return smallest
