"""Reference motions sampled at every control step: positions, velocities, accelerations.

The default motion (minimum-jerk profiles, analytic derivatives) is planned in
:mod:`txtool.simulation.feasible`. A CSV trajectory is interpolated linearly
(piecewise-constant velocity, zero acceleration) or with a cubic spline whose end velocities are
zero, so the reference starts at rest like the plant. Either is then saturated to the joint limits
as the controller would (:func:`saturate`).
"""

from __future__ import annotations

import csv
import math
from dataclasses import dataclass, replace

import numpy as np

from txtool.io.xmlio import InputError
from txtool.model.numbers import parse_strict

CONTINUOUS_RANGE = (-1.0, 1.0)
LIMITLESS = 1e3  # rad or m: limits wider apart than this are taken as none (see limitless)
# The default motion moves each joint about a centre of its own, shifted from the middle of its
# range by up to SHIFT of the range: alike joints (twin fingers, mirrored arms) then follow
# different references however their amplitudes are cut, so a config that swaps two of them is
# wrong about where each one is, and tracks the other's reference.
SHIFT = 0.05
GOLDEN = (math.sqrt(5.0) - 1.0) / 2.0


def default_shifts(joints: int) -> np.ndarray:
    """Per joint, the shift of its motion's centre as a share of its range: 0 for the first
    joint, then the golden-ratio sequence over [-SHIFT, SHIFT) (no two joints alike, spread
    evenly)."""
    return SHIFT * (2.0 * ((0.5 + GOLDEN * np.arange(joints)) % 1.0) - 1.0)


@dataclass(frozen=True)
class Reference:
    time: np.ndarray  # (steps + 1,)
    q: np.ndarray  # (steps + 1, nv)
    qd: np.ndarray
    qdd: np.ndarray
    source: str
    saturated: tuple[str, ...] = ()  # joints whose setpoint :func:`saturate` changed


def step_times(duration: float, dt: float) -> np.ndarray:
    steps = max(1, int(round(duration / dt)))
    return np.round(np.arange(steps + 1) * dt, 12)  # 7.129, not 7.1290000000000004


def minimum_jerk(t: np.ndarray, t0: float, t1: float, a: float, b: float
                 ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Position, velocity, acceleration of a rest-to-rest move a -> b over [t0, t1]."""
    span = t1 - t0
    s = np.clip((t - t0) / span, 0.0, 1.0)
    inside = (t > t0) & (t < t1)
    d = b - a
    q = a + d * (10 * s**3 - 15 * s**4 + 6 * s**5)
    qd = np.where(inside, d * (30 * s**2 - 60 * s**3 + 30 * s**4) / span, 0.0)
    qdd = np.where(inside, d * (60 * s - 180 * s**2 + 120 * s**3) / span**2, 0.0)
    return q, qd, qdd


@dataclass(frozen=True)
class Table:
    """A parsed CSV trajectory: sample times and positions of the named joints."""

    path: str
    time: np.ndarray
    joints: tuple[str, ...]
    positions: np.ndarray  # (rows, len(joints))

    @property
    def end(self) -> float:
        return float(self.time[-1])


def read_csv(path: str, known: set[str]) -> Table:
    try:
        with open(path, newline="", encoding="utf-8") as handle:
            rows = list(csv.reader(handle))
    except FileNotFoundError:
        raise InputError(f"{path}: no such file") from None
    except (OSError, UnicodeDecodeError) as exc:
        raise InputError(f"{path}: cannot read: {exc}") from None
    if not rows:
        raise InputError(f"{path}:1: empty trajectory (expected a header time,<joint>,...)")
    header = [cell.strip() for cell in rows[0]]
    if not header or header[0] != "time" or len(header) < 2:
        raise InputError(f"{path}:1: header must be time,<joint>,... (got {','.join(header)!r})")
    for name in header[1:]:
        if name not in known:
            raise InputError(f"{path}:1: '{name}' is not a moving joint of the robot")
    if len(set(header)) != len(header):
        raise InputError(f"{path}:1: a column is repeated")
    data = _numbers(path, rows[1:], len(header))
    if not data:
        raise InputError(f"{path}:2: no samples after the header")
    table = np.array(data)
    times = table[:, 0]
    if times[0] < 0:
        raise InputError(f"{path}:2: time must not be negative")
    bad = np.nonzero(np.diff(times) <= 0)[0]
    if bad.size:
        raise InputError(f"{path}:{bad[0] + 3}: times must increase")
    return Table(path, times, tuple(header[1:]), table[:, 1:])


def _numbers(path: str, rows: list[list[str]], width: int) -> list[list[float]]:
    data = []
    for number, row in enumerate(rows, 2):
        if not row or all(not cell.strip() for cell in row):
            continue
        if len(row) != width:
            raise InputError(f"{path}:{number}: expected {width} values, got {len(row)}")
        values = [parse_strict(cell) for cell in row]
        for cell, value in zip(row, values, strict=True):
            if value is None:
                raise InputError(f"{path}:{number}: '{cell.strip()}' is not a finite number")
        data.append(values)
    return data


def from_table(table: Table, joints: tuple[str, ...], hold: np.ndarray, t: np.ndarray,
               interpolation: str) -> Reference:
    """Sample ``table`` at ``t``; joints it does not name hold ``hold``."""
    n = len(joints)
    q = np.tile(hold, (len(t), 1))
    qd = np.zeros((len(t), n))
    qdd = np.zeros((len(t), n))
    for column, name in enumerate(table.joints):
        i = joints.index(name)
        values = table.positions[:, column]
        if len(table.time) == 1:
            q[:, i] = values[0]
        elif interpolation == "linear":
            q[:, i], qd[:, i] = _linear(table.time, values, t)
        else:
            q[:, i], qd[:, i], qdd[:, i] = _cubic(table.time, values, t)
    return Reference(t, q, qd, qdd, f"{table.path} ({interpolation})")


def _linear(x: np.ndarray, y: np.ndarray, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    slope = np.diff(y) / np.diff(x)
    k = np.clip(np.searchsorted(x, t, side="right") - 1, 0, len(x) - 2)
    inside = (t >= x[0]) & (t < x[-1])
    return np.interp(t, x, y), np.where(inside, slope[k], 0.0)


def _cubic(x: np.ndarray, y: np.ndarray, t: np.ndarray
           ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Clamped cubic spline (zero end slopes), held constant outside [x0, xn]."""
    m = _clamped_second_derivatives(x, y)
    h = np.diff(x)
    k = np.clip(np.searchsorted(x, t, side="right") - 1, 0, len(x) - 2)
    tc = np.clip(t, x[0], x[-1])
    a, b = x[k + 1] - tc, tc - x[k]
    hk = h[k]
    q = (m[k] * a**3 + m[k + 1] * b**3) / (6 * hk) + (y[k] / hk - m[k] * hk / 6) * a \
        + (y[k + 1] / hk - m[k + 1] * hk / 6) * b
    qd = (-m[k] * a**2 + m[k + 1] * b**2) / (2 * hk) + (y[k + 1] - y[k]) / hk \
        - (m[k + 1] - m[k]) * hk / 6
    qdd = (m[k] * a + m[k + 1] * b) / hk
    outside = (t < x[0]) | (t > x[-1])
    return q, np.where(outside, 0.0, qd), np.where(outside, 0.0, qdd)


def _clamped_second_derivatives(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """Second derivatives at the knots (tridiagonal system, Thomas algorithm)."""
    n = len(x)
    h = np.diff(x)
    lower, diag, upper, rhs = np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n)
    slope = np.diff(y) / h
    diag[0], upper[0], rhs[0] = h[0] / 3, h[0] / 6, slope[0]
    diag[-1], lower[-1], rhs[-1] = h[-1] / 3, h[-1] / 6, -slope[-1]
    lower[1:-1], upper[1:-1] = h[:-1] / 6, h[1:] / 6
    diag[1:-1] = (h[:-1] + h[1:]) / 3
    rhs[1:-1] = slope[1:] - slope[:-1]
    for i in range(1, n):
        w = lower[i] / diag[i - 1]
        diag[i] -= w * upper[i - 1]
        rhs[i] -= w * rhs[i - 1]
    m = np.zeros(n)
    m[-1] = rhs[-1] / diag[-1]
    for i in range(n - 2, -1, -1):
        m[i] = (rhs[i] - upper[i] * m[i + 1]) / diag[i]
    return m


def joint_range(kind: str, lower: float, upper: float) -> tuple[float, float]:
    """The range the default motion moves a joint in: its limits, or, for a joint without
    limits (continuous, none given, or :func:`limitless`), CONTINUOUS_RANGE as near 0 as its
    limits allow."""
    if kind == "continuous" or not (math.isfinite(lower) and math.isfinite(upper)):
        return CONTINUOUS_RANGE
    if limitless(lower, upper):
        low, high = CONTINUOUS_RANGE
        centre = min(max(0.0, lower - low), upper - high)
        return centre + low, centre + high
    return lower, upper


def limitless(lower: float, upper: float) -> bool:
    """Limits so far apart that they say "no limit" in a number (URDFs write ±1e10 or ±1e16
    for it): 25% -> 75% of such a range is no motion a robot makes, and the speed limits would
    cut it to nothing."""
    return upper - lower > LIMITLESS


def follow(ref: Reference, joints: tuple[str, ...],
           followers: dict[str, tuple[str, float, float]]) -> Reference:
    """Mimic joints simulated as independent DoFs track ``multiplier * leader + offset``."""
    if not followers:
        return ref
    q, qd, qdd = ref.q.copy(), ref.qd.copy(), ref.qdd.copy()
    for name, (leader, multiplier, offset) in followers.items():
        f, lead = joints.index(name), joints.index(leader)
        q[:, f] = multiplier * ref.q[:, lead] + offset
        qd[:, f] = multiplier * ref.qd[:, lead]
        qdd[:, f] = multiplier * ref.qdd[:, lead]
    return Reference(ref.time, q, qd, qdd, ref.source)


def hold(ref: Reference, joints: tuple[str, ...], held: tuple[str, ...]) -> Reference:
    """``ref`` with the ``held`` joints kept at their first position, at rest (joints no
    controller commands: their drive keeps them where they are)."""
    q, qd, qdd = ref.q.copy(), ref.qd.copy(), ref.qdd.copy()
    columns = [joints.index(j) for j in held]
    q[:, columns] = ref.q[0, columns]
    qd[:, columns] = 0.0
    qdd[:, columns] = 0.0
    return replace(ref, q=q, qd=qd, qdd=qdd)


def saturate(ref: Reference, joints: tuple[str, ...], lower: np.ndarray, upper: np.ndarray,
             velocity: np.ndarray, dt: float) -> tuple[Reference, list[str]]:
    """The setpoint as computed_torque_controllers makes it: ``q_sp = saturate(q_cmd)``.

    ros_control's ``PositionJointSaturationHandle::enforceLimits`` clamps each command to
    ``[max(prev - vmax dt, lower), min(prev + vmax dt, upper)]`` (``prev``: the last setpoint),
    and the setpoint velocity is ``(q_sp - prev) / dt``. Where that changes the command, the
    velocity is that difference and the acceleration feed-forward the next one's change over
    ``dt`` (what makes the plant land on the next setpoint); elsewhere the analytic values
    stay. Meeting a limit at speed thus asks for a large effort for one step, as it would.
    Returns the setpoint (its ``saturated``: the joints whose setpoint changed) and one note per
    saturated joint.
    """
    step = velocity * dt
    slack = 1e-9 + 1e-9 * np.abs(ref.q).max(initial=0.0)
    over_position = (ref.q < lower - slack) | (ref.q > upper + slack)
    over_speed = np.abs(ref.qd) > velocity * (1 + 1e-9)
    if not (over_position.any() or over_speed.any()):
        return ref, []
    q = np.empty_like(ref.q)
    previous = np.clip(ref.q[0], lower, upper)
    q[0] = previous
    for k in range(1, len(ref.q)):
        previous = np.clip(ref.q[k], np.maximum(previous - step, lower),
                           np.minimum(previous + step, upper))
        q[k] = previous
    changed = np.abs(q - ref.q) > slack
    changed[1:] |= changed[:-1].copy()
    changed[:-1] |= changed[1:].copy()
    qd, qdd = ref.qd.copy(), ref.qdd.copy()
    speed = np.vstack([np.zeros(len(joints)), np.diff(q, axis=0) / dt])
    acceleration = np.vstack([np.diff(speed, axis=0) / dt, np.zeros(len(joints))])
    qd[changed], qdd[changed] = speed[changed], acceleration[changed]
    notes = []
    for v, name in enumerate(joints):
        if over_position[:, v].any():
            first = ref.time[int(np.argmax(over_position[:, v]))]
            notes.append(f"reference: joint '{name}' goes outside its position limits "
                         f"[{lower[v]:.4g}, {upper[v]:.4g}] from t={first:.3f} s; the setpoint "
                         "is saturated as computed_torque_controllers does (q_sp = "
                         "saturate(q_cmd))")
        if over_speed[:, v].any():
            peak = float(np.abs(ref.qd[:, v]).max())
            notes.append(f"reference: joint '{name}' moves at up to {peak:.4g}, beyond its "
                         f"velocity limit {velocity[v]:.4g}; the setpoint is rate-limited as "
                         "computed_torque_controllers does")
    saturated = tuple(name for v, name in enumerate(joints)
                      if over_position[:, v].any() or over_speed[:, v].any())
    return Reference(ref.time, q, qd, qdd, ref.source, saturated), notes
