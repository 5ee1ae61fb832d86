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
from dataclasses import dataclass, field

import numpy as np
import pinocchio as pin

from txtool.simulation.model import RobotModel
from txtool.simulation.plant import Dynamics
from txtool.simulation.sensing import Encoder

CHUNK = 500


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
            _steps(plan, plan.done, stop)
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


def _next_row(plan: Plan) -> np.ndarray:
    """The matrix from a working row's tail (x, v, a of step k; then the clipped demand
    ``satn`` and the precomputed columns of step k + 1) to step k + 1's head: applied effort,
    the controller's estimates (``H``), the plant's joint effort (``PD``), ta (zero), x, v.

    Folding ``Phi`` into ``H`` and ``PD`` saves two products per step; only the rounding of
    the sums changes (results agree with the unfolded loop to about 1e-15).
    """
    s, nv, width, na = plan.slots, plan.robot.nv, plan.rows.shape[1], plan.limit.size
    dynamic = ("a", "ta", "est", "tj")
    for matrix in (plan.H, plan.PD):
        if any(np.any(matrix[:, s[name]]) for name in dynamic):
            raise ValueError("H and PD read only x, v, sat and the precomputed columns")
    first = s["x"].start  # the tail read starts here
    static = slice(s["one"].start, width)
    row = slice(0, width - first)
    satn = slice(width - first, width - first + na)
    later = slice(satn.stop, satn.stop + width - static.start)
    phi = plan.Phi[:, first:]
    out = np.zeros((s["v"].stop, later.stop))
    out[s["x"].start : s["v"].stop, row] = phi
    out[s["sat"], satn] = np.eye(na)
    for rows, matrix in ((s["est"], plan.H), (s["tj"], plan.PD)):
        block = out[rows.start : rows.start + matrix.shape[0]]
        block[:, row] += matrix[:, s["x"]] @ phi[:nv] + matrix[:, s["v"]] @ phi[nv:]
        block[:, satn] += matrix[:, s["sat"]]
        block[:, later] += matrix[:, static]
    return out


def _delayed_steps(plan: Plan, start: int, stop: int) -> None:
    """The fast loop with the one-period delay, on two working rows used in turn.

    A step costs one ``rnea``, one ``aba``, two matrix products (the controller's efforts,
    and :func:`_next_row`), a clip and three row copies (the acceleration, the precomputed
    columns of the next step, the record of this one); each step makes two views.
    """
    s, nv, rows = plan.slots, plan.robot.nv, plan.rows
    width, na = rows.shape[1], plan.limit.size
    big = plan.extras.get("next_row")
    if big is None:
        big = plan.extras["next_row"] = _next_row(plan)
    static = slice(s["one"].start, width)
    record = slice(0, s["one"].start)
    head, tail = slice(0, s["v"].stop), slice(s["x"].start, None)
    work = [np.zeros(width + na + width - static.start) for _ in range(2)]
    first = work[0]
    first[:width] = rows[start]
    est = first[s["est"]]
    est[: plan.H.shape[0]] = plan.H @ rows[start]
    first[s["tj"]] = plan.PD @ rows[start]
    bias_at = 3 * nv
    views: list[tuple[np.ndarray, ...]] = []
    for w in work:
        e = w[s["est"]]
        views.append((e[:nv], e[nv : 2 * nv], e[2 * nv : 3 * nv], e[bias_at : bias_at + na],
                      w[s["ta"]], w[width : width + na], w[s["x"]], w[s["v"]], w[s["tj"]],
                      w[s["a"]], w[width + na :], w[record], w[head], w[tail]))
    (cm, cdata), (pm, pdata) = plan.ctrl, plan.plant
    rnea, aba, dot, C, limit, low = pin.rnea, pin.aba, np.dot, plan.C, plan.limit, -plan.limit
    clip, bias = _clip(), plan.bias
    # Two steps per iteration, one per working row, so that every view is made once.
    (xh0, vh0, acc0, off0, ta0, satn0, x0, v0, tj0, a0, later0, mine0, head0, tail0), \
        (xh1, vh1, acc1, off1, ta1, satn1, x1, v1, tj1, a1, later1, mine1, head1, tail1) = views
    upcoming = rows[start + 1 : stop + 1, static]
    past = rows[start:stop, record]
    pairs = (stop - start) // 2
    # The controller's efforts C tau: a copy when C is the identity (reductions of 1, direct
    # joints), a product otherwise.
    same = C.shape[0] == C.shape[1] and np.array_equal(C, np.eye(C.shape[0]))
    for up0, up1, past0, past1 in zip(upcoming[0 : 2 * pairs : 2], upcoming[1 : 2 * pairs : 2],
                                      past[0 : 2 * pairs : 2], past[1 : 2 * pairs : 2],
                                      strict=True):
        if same:
            ta0[...] = rnea(cm, cdata, xh0, vh0, acc0)
        else:
            dot(C, rnea(cm, cdata, xh0, vh0, acc0), out=ta0)
        if bias:
            ta0 += off0
        clip(ta0, low, limit, out=satn0)
        a0[...] = aba(pm, pdata, x0, v0, tj0)
        later0[...] = up0
        dot(big, tail0, out=head1)
        past0[...] = mine0
        if same:
            ta1[...] = rnea(cm, cdata, xh1, vh1, acc1)
        else:
            dot(C, rnea(cm, cdata, xh1, vh1, acc1), out=ta1)
        if bias:
            ta1 += off1
        clip(ta1, low, limit, out=satn1)
        a1[...] = aba(pm, pdata, x1, v1, tj1)
        later1[...] = up1
        dot(big, tail1, out=head0)
        past1[...] = mine1
    last = head0
    if (stop - start) % 2:
        dot(C, rnea(cm, cdata, xh0, vh0, acc0), out=ta0)
        if bias:
            ta0 += off0
        clip(ta0, low, limit, out=satn0)
        a0[...] = aba(pm, pdata, x0, v0, tj0)
        later0[...] = upcoming[-1]
        dot(big, tail0, out=head1)
        past[-1] = mine0
        last = head1
    rows[stop, head] = last  # x, v, applied effort (and estimates) of the last row


def _clip() -> Callable[..., np.ndarray]:
    """numpy's clip ufunc (one call) when this numpy exposes it, else minimum then maximum."""
    ufunc = getattr(getattr(getattr(np, "_core", None), "umath", None), "clip", None)
    if isinstance(ufunc, np.ufunc):
        return ufunc

    def clip(value: np.ndarray, low: np.ndarray, high: np.ndarray, out: np.ndarray
             ) -> np.ndarray:
        np.minimum(value, high, out=out)
        return np.maximum(out, low, out=out)

    return clip


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
