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

Three step loops give the same numbers (to round-off) where more than one applies:
:func:`general_steps` (every feature), :func:`plain_steps` (the loop as described above) and
:func:`txtool.simulation.ring.delayed_steps` (the default settings: the delay on a simple
plant). :func:`step_loop` picks the one a plan needs; :func:`run` takes another as an argument.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import pinocchio as pin

from txtool.simulation.model import RobotModel
from txtool.simulation.plan import Plan, RunState
from txtool.simulation.ring import delayed_steps

CHUNK = 500

# Steps start to stop of a run: (plan, state, start, stop).
StepLoop = Callable[[Plan, RunState, int, int], None]


def make_model(robot: RobotModel, inertia: np.ndarray) -> tuple[pin.Model, np.ndarray | None]:
    """A model copy with the diagonal of ``inertia`` as armature; the rest as a block (or None)."""
    model = pin.Model(robot.model)
    model.armature = np.diag(inertia).copy()
    off = inertia - np.diag(np.diag(inertia))
    return model, (off if np.any(off) else None)


def needs_general(plan: Plan) -> bool:
    """An integral term, continuous joints, an encoder, or a plant with friction, sub-steps or
    coupled inertia: only :func:`general_steps` runs those."""
    return plan.ki is not None or plan.robot.has_continuous or plan.encoder is not None \
        or not plan.dynamics.simple


def step_loop(plan: Plan) -> StepLoop:
    """The step loop ``plan`` needs: the general one, else the ring (with the delay, the
    default settings) or the plain one."""
    if needs_general(plan):
        return general_steps
    return delayed_steps if plan.delay else plain_steps


def run(plan: Plan, progress: Callable[[int], None] | None = None, *,
        steps: StepLoop | None = None) -> RunState:
    """Run ``plan`` from a fresh state to its last step (or to divergence) with the step loop
    ``steps`` (default: :func:`step_loop`); ``progress(steps_done)``."""
    state = RunState.begin(plan)
    advance = steps or step_loop(plan)
    with np.errstate(all="ignore"):
        if plan.delay and plan.steps > 0:
            _first_step_with_delay(plan, state)
        while state.done < plan.steps:
            stop = min(state.done + CHUNK, plan.steps)
            try:
                advance(plan, state, state.done, stop)
            except np.linalg.LinAlgError:
                # A state run away far enough leaves the plant's equations singular or
                # non-finite: the rows not reached are marked so, and judged as divergence.
                # (Rows start as zeros: the ones after the last with a non-zero state were
                # not reached.)
                ahead = state.rows[state.done + 1 : stop + 1]
                moved = np.flatnonzero(ahead[:, plan.slots["x"].start : plan.slots["v"].stop]
                                       .any(axis=1))
                ahead[(int(moved[-1]) + 1 if len(moved) else 0):] = np.nan
            if not np.isfinite(state.rows[state.done + 1 : stop + 1, plan.slots["x"]]).all():
                bad = np.nonzero(~np.isfinite(state.rows[state.done : stop + 1]).all(axis=1))[0]
                state.diverged_at = state.done + int(bad[0])
                state.done = stop
                break
            state.done = stop
            if progress is not None:
                progress(stop)
    return state


def _first_step_with_delay(plan: Plan, state: RunState) -> None:
    """Step 0 as if the loop had been holding the start: its own command acts at once too.

    The command of step 0 is then also the one that acts during step 1 (written to row 1).
    """
    undelayed = general_steps if needs_general(plan) else plain_steps
    undelayed(plan, state, 0, 1, lag=0)
    sat = plan.slots["sat"]
    state.rows[1, sat] = state.rows[0, sat]
    state.done = 1


def _views(plan: Plan, state: RunState, start: int, stop: int, lag: int) -> zip:
    """Per step: the history row, its x, v, demanded effort, where the clipped demand goes
    (this row's applied effort, or the next row's with a ``lag`` of 1), the next [x v], k.

    Iterating 2-D column views yields each step's 1-D views more cheaply than indexing.
    """
    rows, s = state.rows, plan.slots
    span, state_cols = slice(start, stop), slice(s["x"].start, s["v"].stop)
    return zip(rows[span], rows[span, s["x"]], rows[span, s["v"]], rows[span, s["ta"]],
               rows[start + lag : stop + lag, s["sat"]], rows[start + 1 : stop + 1, state_cols],
               range(start, stop), strict=True)


def plain_steps(plan: Plan, state: RunState, start: int, stop: int,
                lag: int | None = None) -> None:
    """The loop as the module describes it, for a simple plant (revolute and prismatic joints,
    viscous damping, diagonal rotor inertia): what runs with the delay off (``--no-delay``).
    The default settings (the delay on) run :func:`ring.delayed_steps`, which agrees with this
    loop to round-off. ``lag``: 1 when the demand acts from the next step (default:
    ``plan.delay``)."""
    nv = plan.robot.nv
    lag = int(plan.delay) if lag is None else lag
    H, C, PD, Phi = plan.H, plan.C, plan.PD, plan.Phi
    A = state.rows[:, plan.slots["a"]]
    limit, neg_limit = plan.limit, -plan.limit
    cm, cdata, pm, pdata = plan.ctrl, state.ctrl_data, plan.plant, state.plant_data
    rnea, aba, dot, minimum, maximum = pin.rnea, pin.aba, np.dot, np.minimum, np.maximum
    out, tj = np.empty(H.shape[0]), np.empty(nv)
    xh, vh, acc, bias = out[:nv], out[nv : 2 * nv], out[2 * nv : 3 * nv], out[3 * nv :]
    if plan.bias:
        for row, x, v, ta, sat, nxt, k in _views(plan, state, start, stop, lag):
            dot(H, row, out=out)
            dot(C, rnea(cm, cdata, xh, vh, acc), out=ta)
            ta += bias
            minimum(ta, limit, out=sat)
            maximum(sat, neg_limit, out=sat)
            dot(PD, row, out=tj)
            A[k] = aba(pm, pdata, x, v, tj)
            dot(Phi, row, out=nxt)
        return
    for row, x, v, ta, sat, nxt, k in _views(plan, state, start, stop, lag):
        dot(H, row, out=out)
        dot(C, rnea(cm, cdata, xh, vh, acc), out=ta)
        minimum(ta, limit, out=sat)
        maximum(sat, neg_limit, out=sat)
        dot(PD, row, out=tj)
        A[k] = aba(pm, pdata, x, v, tj)
        dot(Phi, row, out=nxt)


def general_steps(plan: Plan, state: RunState, start: int, stop: int,
                  lag: int | None = None) -> None:
    """Every feature: integral term, continuous joints, the plant's friction and sub-steps.
    ``lag`` as for :func:`plain_steps`."""
    robot, nv = plan.robot, plan.robot.nv
    lag = int(plan.delay) if lag is None else lag
    rows, H, C, PD = state.rows, plan.H, plan.C, plan.PD
    limit = plan.limit
    cm, cdata = plan.ctrl, state.ctrl_data
    out, tj = np.empty(H.shape[0]), np.empty(nv)
    xh, vh, acc, bias = out[:nv], out[nv : 2 * nv], out[2 * nv : 3 * nv], out[3 * nv :]
    A = rows[:, plan.slots["a"]]
    config = configurer(robot) if robot.has_continuous else None
    qh = np.zeros(robot.model.nq) if config else xh
    advance = plan.dynamics.advance
    ki, i_limit, z = plan.ki, plan.i_limit, state.integral
    ctrl_block, dt, q_ref = plan.ctrl_block, plan.dt, plan.q_ref
    read = None
    if plan.encoder is not None:
        read = plan.encoder.reader(rows, plan.slots["enc"], plan.slots["encv"], dt)
    for row, x, v, ta, sat, nxt, k in _views(plan, state, start, stop, lag):
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
