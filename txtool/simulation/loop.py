"""The closed loop: computed-torque control through two sets of transmissions.

Everything linear is folded into a few matrices that act on one history row per step::

    row = [x | v | 1 | a | ff | (q_ref v_ref) | (friction ff) | (readings) | tau_a demanded
           | tau_a applied]

``H @ row`` gives the controller's joint estimates (decoded with the candidate from the actuator
readings the plant produces with the robot's maps), the acceleration command
``qdd_ref + kp e + kd e_dot`` (``ff = qdd_ref + kp q_ref + kd v_ref`` is precomputed) and, when
needed, an actuator-effort bias (damping and friction compensation, off-diagonal rotor inertia).
``PD @ row`` is the plant's joint effort from the applied actuator efforts (minus joint damping
on the fast path), and ``Phi @ row`` is the semi-implicit Euler step. So a step costs one
``rnea``, one ``aba``, four small matrix products, a clip and a few views, with no Python loop
over transmissions. Damping is implicit there through the plant's armature (see
:mod:`txtool.simulation.plant`); friction, sub-steps and coupled inertia go through
:meth:`plant.Dynamics.advance`.

With ``plan.delay`` the clipped demand of row ``k`` becomes the applied effort of row ``k + 1``
(read -> update -> write, see :mod:`txtool.simulation.sensing`). With an encoder, the estimates
are decoded from the quantised actuator readings in the row instead of from ``x`` and ``v``.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import pinocchio as pin

from txtool.simulation.model import RobotModel
from txtool.simulation.plan import Plan
from txtool.simulation.ring import delayed_steps as _delayed_steps

CHUNK = 500


def make_model(robot: RobotModel, inertia: np.ndarray) -> tuple[pin.Model, np.ndarray | None]:
    """A model copy with the diagonal of ``inertia`` as armature; the rest as a block (or None)."""
    model = pin.Model(robot.model)
    model.armature = np.diag(inertia).copy()
    off = inertia - np.diag(np.diag(inertia))
    return model, (off if np.any(off) else None)


def run(plan: Plan, progress: Callable[[int], None] | None = None) -> Plan:
    """Advance ``plan`` to its last step (or to divergence); ``progress(steps_done)``."""
    with np.errstate(all="ignore"):
        if plan.delay and plan.done == 0 and plan.steps > 0:
            _first_step_with_delay(plan)
        while plan.done < plan.steps:
            stop = min(plan.done + CHUNK, plan.steps)
            try:
                _steps(plan, plan.done, stop)
            except np.linalg.LinAlgError:
                # A state run away far enough leaves the plant's equations singular or
                # non-finite: the rows not reached are marked so, and judged as divergence.
                # (Rows start as zeros: the ones after the last with a non-zero state were
                # not reached.)
                ahead = plan.rows[plan.done + 1 : stop + 1]
                moved = np.flatnonzero(ahead[:, plan.slots["x"].start : plan.slots["v"].stop]
                                       .any(axis=1))
                ahead[(int(moved[-1]) + 1 if len(moved) else 0):] = np.nan
            if not np.isfinite(plan.rows[plan.done + 1 : stop + 1, plan.slots["x"]]).all():
                bad = np.nonzero(~np.isfinite(plan.rows[plan.done : stop + 1]).all(axis=1))[0]
                plan.diverged_at = plan.done + int(bad[0])
                plan.done = stop
                break
            plan.done = stop
            if progress is not None:
                progress(stop)
    return plan


def _first_step_with_delay(plan: Plan) -> None:
    """Step 0 as if the loop had been holding the start: its own command acts at once too.

    The command of step 0 is then also the one that acts during step 1 (written to row 1).
    """
    plan.delay = False
    try:
        _steps(plan, 0, 1)
    finally:
        plan.delay = True
    sat = plan.slots["sat"]
    plan.rows[1, sat] = plan.rows[0, sat]
    plan.done = 1


def _steps(plan: Plan, start: int, stop: int) -> None:
    general = plan.ki is not None or plan.robot.has_continuous or plan.encoder is not None \
        or not plan.dynamics.simple
    if general:
        _general_steps(plan, start, stop)
    elif plan.delay:
        _delayed_steps(plan, start, stop)
    else:
        _fast_steps(plan, start, stop)


def _views(plan: Plan, start: int, stop: int) -> zip:
    """Per step: the history row, its x, v, demanded effort, where the clipped demand goes
    (this row's applied effort, or the next row's with ``plan.delay``), the next [x v], k.

    Iterating 2-D column views yields each step's 1-D views more cheaply than indexing.
    """
    rows, s = plan.rows, plan.slots
    span, lag, state = slice(start, stop), int(plan.delay), slice(s["x"].start, s["v"].stop)
    return zip(rows[span], rows[span, s["x"]], rows[span, s["v"]], rows[span, s["ta"]],
               rows[start + lag : stop + lag, s["sat"]], rows[start + 1 : stop + 1, state],
               range(start, stop), strict=True)


def _fast_steps(plan: Plan, start: int, stop: int) -> None:
    """The common case: revolute/prismatic joints, viscous damping, diagonal rotor inertia."""
    nv = plan.robot.nv
    H, C, PD, Phi = plan.H, plan.C, plan.PD, plan.Phi
    A = plan.rows[:, plan.slots["a"]]
    limit, neg_limit = plan.limit, -plan.limit
    (cm, cdata), (pm, pdata) = plan.ctrl, plan.plant
    rnea, aba, dot, minimum, maximum = pin.rnea, pin.aba, np.dot, np.minimum, np.maximum
    out, tj = np.empty(H.shape[0]), np.empty(nv)
    xh, vh, acc, bias = out[:nv], out[nv : 2 * nv], out[2 * nv : 3 * nv], out[3 * nv :]
    if plan.bias:
        for row, x, v, ta, sat, nxt, k in _views(plan, start, stop):
            dot(H, row, out=out)
            dot(C, rnea(cm, cdata, xh, vh, acc), out=ta)
            ta += bias
            minimum(ta, limit, out=sat)
            maximum(sat, neg_limit, out=sat)
            dot(PD, row, out=tj)
            A[k] = aba(pm, pdata, x, v, tj)
            dot(Phi, row, out=nxt)
        return
    for row, x, v, ta, sat, nxt, k in _views(plan, start, stop):
        dot(H, row, out=out)
        dot(C, rnea(cm, cdata, xh, vh, acc), out=ta)
        minimum(ta, limit, out=sat)
        maximum(sat, neg_limit, out=sat)
        dot(PD, row, out=tj)
        A[k] = aba(pm, pdata, x, v, tj)
        dot(Phi, row, out=nxt)


def _general_steps(plan: Plan, start: int, stop: int) -> None:
    """Every feature: integral term, continuous joints, the plant's friction and sub-steps."""
    robot, nv = plan.robot, plan.robot.nv
    rows, H, C, PD = plan.rows, plan.H, plan.C, plan.PD
    limit = plan.limit
    cm, cdata = plan.ctrl
    out, tj = np.empty(H.shape[0]), np.empty(nv)
    xh, vh, acc, bias = out[:nv], out[nv : 2 * nv], out[2 * nv : 3 * nv], out[3 * nv :]
    A = rows[:, plan.slots["a"]]
    config = configurer(robot) if robot.has_continuous else None
    qh = np.zeros(robot.model.nq) if config else xh
    advance = plan.dynamics.advance
    ki, i_limit, z = plan.ki, plan.i_limit, plan.extras.setdefault("z", np.zeros(nv))
    ctrl_block, dt, q_ref = plan.ctrl_block, plan.dt, plan.q_ref
    read = None
    if plan.encoder is not None:
        read = plan.encoder.reader(rows, plan.slots["enc"], plan.slots["encv"], dt)
    for row, x, v, ta, sat, nxt, k in _views(plan, start, stop):
        if read is not None:
            read(row, x, v, k)
        np.dot(H, row, out=out)
        if ki is not None:
            z += dt * (q_ref[k] - xh)
            np.clip(z, -i_limit, i_limit, out=z)  # type: ignore[arg-type]
            acc += ki * z
        if config is not None:
            config(xh, qh)
        tau = pin.rnea(cm, cdata, qh, vh, acc)
        if ki is not None and ctrl_block is not None:
            tau += ctrl_block @ (ki * z)
        np.dot(C, tau, out=ta)
        if plan.bias:
            ta += bias
        np.clip(ta, -limit, limit, out=sat)
        np.dot(PD, row, out=tj)
        advance(x, v, tj, nxt)
        np.subtract(nxt[nv:], v, out=A[k])
        A[k] /= dt


def configurer(robot: RobotModel) -> Callable[[np.ndarray, np.ndarray], None]:
    plain_q, plain_v, cos_q, cont_v = robot.config_indices()
    sin_q = cos_q + 1

    def config(x: np.ndarray, q: np.ndarray) -> None:
        q[plain_q] = x[plain_v]
        angles = x[cont_v]
        q[cos_q] = np.cos(angles)
        q[sin_q] = np.sin(angles)

    return config
