"""The default loop (one-period delay, simple plant) on a ring of working rows.

A step is one ``rnea``, one ``aba``, a copy of each result and one matrix product
(:func:`next_row`) that gives the next step's estimates, plant effort and state at once. The
steps run on ``RING + 1`` preallocated working rows, so every argument is a view made once per
run; the records of a block of steps go to the history in one copy, and the precomputed columns
(reference feed-forward, counterbalance torque, ...) of the next block come in with one copy.

The clip of the demanded efforts to the effort limits is left out while it changes nothing: a
block runs without it, then its demands are checked against the limits at once, and a block in
which an actuator saturated runs again from its start with the clip. A clip that changes no bit
leaves every later value unchanged, so both give the same numbers, to the bit. After a block
that saturated, the next block clips at once; a block that then saturates nowhere goes back to
the check. The demanded effort of step ``k`` is the applied effort of step ``k + 1`` when
nothing is clipped, so the history's demand column is filled from that column.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

import numpy as np
import pinocchio as pin

if TYPE_CHECKING:
    from txtool.simulation.plan import Plan, RunState

RING = 64  # steps per block


class Ring:
    """Working rows and their views; built once per run (``state.ring``)."""

    def __init__(self, plan: Plan) -> None:
        s, nv, width, na = plan.slots, plan.robot.nv, plan.width, plan.limit.size
        self.big = next_row(plan)
        self.static = slice(s["one"].start, width)
        self.record = slice(0, s["one"].start)
        self.head = slice(0, s["v"].stop)
        length = width + na + width - self.static.start
        # Rows padded to 64 bytes, so that every row's vectors have the same alignment.
        self.work = np.zeros((RING + 1, -(-length // 8) * 8))
        self.satn = slice(width, width + na)
        self.later = slice(width + na, length)
        self.checked: list[tuple[np.ndarray, ...]] = []  # the demand goes to satn, unclipped
        self.clipped: list[tuple[np.ndarray, ...]] = []  # to ta, then clipped to satn
        tail = slice(s["x"].start, length)
        for i in range(RING):
            w, est = self.work[i], self.work[i, s["est"]]
            ta, satn = w[s["ta"]], w[self.satn]
            common = (w[s["x"]], w[s["v"]], w[s["tj"]], w[s["a"]], w[tail],
                      self.work[i + 1, self.head])
            control = (est[:nv], est[nv : 2 * nv], est[2 * nv : 3 * nv],
                       est[3 * nv : 3 * nv + na])
            self.checked.append((*control, satn, satn, *common))
            self.clipped.append((*control, ta, satn, *common))
        self.clip = clipper()
        self.scratch = np.empty((RING, na))
        self.saved = np.empty(self.work.shape[1])  # row 0 at the start of a checked block
        # The controller's efforts C tau: a copy when C is the identity (reductions of 1,
        # direct joints), a product otherwise.
        self.same = plan.C.shape[0] == plan.C.shape[1] and np.array_equal(
            plan.C, np.eye(plan.C.shape[0]))
        self.saturated = False  # in the last block: the next one clips at once


def delayed_steps(plan: Plan, state: RunState, start: int, stop: int) -> None:
    """Steps ``start`` to ``stop`` of the delayed loop; row ``start`` holds x, v and the
    applied effort, and row ``stop`` gets them."""
    ring = state.ring
    if not isinstance(ring, Ring):
        ring = state.ring = Ring(plan)
    rows, s, work = state.rows, plan.slots, ring.work
    work[0, : rows.shape[1]] = rows[start]
    est = work[0, s["est"]]
    est[: plan.H.shape[0]] = plan.H @ rows[start]
    work[0, s["tj"]] = plan.PD @ rows[start]
    low, limit = -plan.limit, plan.limit
    k = start
    while k < stop:
        n = min(RING, stop - k)
        work[:n, ring.later] = rows[k + 1 : k + n + 1, ring.static]
        if ring.saturated:
            _block(plan, state, ring, ring.clipped, n, clip=True)
            ring.saturated = _changed(work[:n, s["ta"]], work[:n, ring.satn])
        else:
            ring.saved[...] = work[0]
            _block(plan, state, ring, ring.checked, n, clip=False)
            demand = work[:n, ring.satn]
            if _changed(demand, ring.clip(demand, low, limit, out=ring.scratch[:n])):
                work[0] = ring.saved
                _block(plan, state, ring, ring.clipped, n, clip=True)
                ring.saturated = True
            else:
                work[:n, s["ta"]] = demand
        rows[k : k + n, ring.record] = work[:n, ring.record]
        work[0, ring.head] = work[n, ring.head]
        k += n
    rows[stop, ring.head] = work[0, ring.head]


def _changed(a: np.ndarray, b: np.ndarray) -> bool:
    """Whether two float arrays differ in any bit (a NaN equals itself, 0.0 differs from -0.0)."""
    return not np.array_equal(a.view(np.uint64), b.view(np.uint64))


def _block(plan: Plan, state: RunState, ring: Ring, views: list[tuple[np.ndarray, ...]], n: int,
           *, clip: bool) -> None:
    """``n`` steps on working rows 0 to n; the last step's head lands in row n."""
    cm, cdata, pm, pdata = plan.ctrl, state.ctrl_data, plan.plant, state.plant_data
    # The method skips np.dot's dispatch (about 1,400 of a step's 40,000 instructions).
    rnea, aba, step, C = pin.rnea, pin.aba, ring.big.dot, plan.C
    if ring.same and not plan.bias and not clip:  # the common case, without branches
        for xh, vh, acc, _, demand, _, x, v, tj, a, tail, head in views[:n]:
            demand[...] = rnea(cm, cdata, xh, vh, acc)
            a[...] = aba(pm, pdata, x, v, tj)
            step(tail, head)
        return
    limit, low, clipper, bias, same = plan.limit, -plan.limit, ring.clip, plan.bias, ring.same
    for xh, vh, acc, off, demand, satn, x, v, tj, a, tail, head in views[:n]:
        if same:
            demand[...] = rnea(cm, cdata, xh, vh, acc)
        else:
            C.dot(rnea(cm, cdata, xh, vh, acc), demand)
        if bias:
            demand += off
        if clip:
            clipper(demand, low, limit, out=satn)
        a[...] = aba(pm, pdata, x, v, tj)
        step(tail, head)


def next_row(plan: Plan) -> np.ndarray:
    """The matrix from a working row's tail (x, v, a of step k; then the clipped demand
    ``satn`` and the precomputed columns of step k + 1) to step k + 1's head: applied effort,
    the controller's estimates (``H``), the plant's joint effort (``PD``), ta (zero), x, v.

    Folding ``Phi`` into ``H`` and ``PD`` saves two products per step; only the rounding of
    the sums changes (results agree with the unfolded loop to about 1e-15).
    """
    s, nv, width, na = plan.slots, plan.robot.nv, plan.width, plan.limit.size
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


def clipper() -> Callable[..., np.ndarray]:
    """numpy's clip ufunc (one call) when this numpy exposes it, else minimum then maximum."""
    ufunc = getattr(getattr(getattr(np, "_core", None), "umath", None), "clip", None)
    if isinstance(ufunc, np.ufunc):
        return ufunc

    def clip(value: np.ndarray, low: np.ndarray, high: np.ndarray, out: np.ndarray
             ) -> np.ndarray:
        np.minimum(value, high, out=out)
        return np.maximum(out, low, out=out)

    return clip
