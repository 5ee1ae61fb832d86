"""A default motion the robot can follow: time-scaled to its velocity and effort limits.

Every joint moves from 25% to 75% of its range and back with minimum-jerk profiles, all with
the same move time ``T``. With ``s(tau)`` the unit profile, the reference is
``q = low + d s(t/T)``, ``qd = d s'/T``, ``qdd = d s''/T^2``; so joint and actuator speeds
scale with ``1/T`` and the torque ``tau = (M qdd + C qd) / T^2 + D qd / T + g + F sign(qd)``
(each term computed once at ``T = 1`` on the unit profile) is checked for any ``T`` without
more dynamics. The smallest ``T`` that keeps every joint and actuator speed and every actuator
effort (through the plant's effort map) within ``MARGIN`` of its limit, and the predicted
tracking error of the sampled loop within ``LAG_SHARE`` of the tolerance, is chosen.

That error comes from the torque the controller applies being older than the state it acts on.
The plant integrates damping implicitly while the controller compensates it from the last
reading, so a damped joint is short ``D qdd dt`` of torque; with the loop's one-period delay
(:mod:`txtool.simulation.sensing`) the whole computed torque also acts one period late, short
``dtau/dt dt`` (twice as much damping). Feedback turns the acceleration this lacks,
``M^-1 dtorque``, into an error of about ``M^-1 dtorque / kp``: large where the effective
inertia is small (a light damped link; two joint axes nearly aligned). :class:`Lag` has the
details. With ``tau`` split as
above, ``dtau/dt = Q'/T^3 + L'/T^2 + g'/T`` along the unit profile (primes in ``t/T``).
When the run's length is fixed (``--duration`` or the params file), amplitudes shrink
instead; a joint whose gravity and friction alone exceed its actuator's limit is held still.
Every such choice is a note.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from txtool.simulation.counterbalance import Counterbalance
from txtool.simulation.reference import (
    SHIFT,
    Reference,
    default_shifts,
    minimum_jerk,
    step_times,
)

MARGIN = 0.8  # a reference peak may use this share of a speed or effort limit
LAG_SHARE = 0.15  # share of the tolerance the predicted lag of a damped light link may use
LONGEST_MOVE = 120.0  # s: the default run grows to at most 2 x this
SAMPLES = 120  # points of the unit profile where the dynamics are evaluated
GRID = 1.03  # ratio between move times tried

Parts = tuple[np.ndarray, np.ndarray, np.ndarray]
# (q, qd, qdd) rows -> joint torques (M qdd + C qd, D qd, g + F sign qd): what scales with
# 1/T^2, with 1/T, and not at all
Dynamics = Callable[[np.ndarray, np.ndarray, np.ndarray], Parts]


@dataclass(frozen=True)
class Limits:
    """What the default motion must respect, per joint (nv) and per plant actuator (na)."""

    joints: tuple[str, ...]
    velocity: np.ndarray  # joint velocity limits (inf: none)
    vel_j2a: np.ndarray  # (na, nv) plant velocity map
    eff_j2a: np.ndarray  # (na, nv) plant effort map
    actuators: tuple[str, ...]
    actuator_speed: np.ndarray
    actuator_effort: np.ndarray
    dt: float  # control period
    delay: bool  # one period from reading to acting (sensing.py)
    kp: np.ndarray  # per joint position and velocity gains
    kd: np.ndarray
    damping: np.ndarray  # per joint viscous damping
    inverse_mass: Callable[[np.ndarray], np.ndarray]  # joint rows -> (rows, nv, nv) M^-1


@dataclass(frozen=True)
class Motion:
    move: float  # seconds per move (the run is two moves)
    amplitude: np.ndarray  # per joint, share of the 25%..75% move
    binding: str  # what set the move time
    notes: tuple[str, ...]
    cannot_hold: tuple[str, ...] = ()  # why actuators cannot hold their joints at rest
    carry: Counterbalance | None = None  # static loads carried beside the actuators
    shrunk: str = ""  # how much the amplitudes were cut, and why (for the header)


def unit_profile(ranges: list[tuple[float, float]], amplitude: np.ndarray
                 ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(q, q', q'') on SAMPLES points of the up move then the down move, for T = 1."""
    tau = np.linspace(0.0, 1.0, SAMPLES)
    low, high = _ends(ranges, amplitude)
    up = minimum_jerk(tau[:, None], 0.0, 1.0, low, high)
    down = minimum_jerk(tau[:, None], 0.0, 1.0, high, low)
    return tuple(np.vstack([a, b]) for a, b in zip(up, down, strict=True))  # type: ignore[return-value]


def _ends(ranges: list[tuple[float, float]], amplitude: np.ndarray
          ) -> tuple[np.ndarray, np.ndarray]:
    lo = np.array([r[0] for r in ranges])
    hi = np.array([r[1] for r in ranges])
    middle = (lo + hi) / 2 + (hi - lo) * default_shifts(len(ranges))
    half = 0.25 * (hi - lo) * amplitude
    return middle - half, middle + half


def plan_motion(ranges: list[tuple[float, float]], limits: Limits, dynamics: Dynamics,
                move: float, fixed: bool, tolerance: float,
                counterbalance: Callable[[np.ndarray], Counterbalance] | None = None) -> Motion:
    """The move time and amplitudes; ``move`` is the default (or, with ``fixed``, the only).

    ``counterbalance`` finds, from the gravity along the full motion, the static loads to take
    off the actuators (:mod:`txtool.simulation.counterbalance`).
    """
    amplitude = np.ones(len(ranges))
    q, qd, qdd = unit_profile(ranges, amplitude)
    carry, relieved, refused = _counterbalanced(counterbalance, dynamics, q)
    still = _held_still(limits, relieved(q, qd, qdd)[2])
    for v in still:
        amplitude[v] = 0.0
    q, qd, qdd = unit_profile(ranges, amplitude)
    if still:  # the counterbalance of the motion that runs: the held joints held
        carry, relieved, refused = _counterbalanced(counterbalance, dynamics, q)
    dynamics = relieved
    notes = refused + [f"joint '{limits.joints[v]}' is held still: {why}"
                       for v, why in still.items()]
    parts = dynamics(q, qd, qdd)
    weak = _cannot_hold(limits, parts[2])
    lag = Lag.along(limits, q, qdd, parts, dynamics(q, 0 * qd, 0 * qdd)[2],
                    LAG_SHARE * tolerance)
    longest = move if fixed else max(move, LONGEST_MOVE)
    needed, binding = _move_time(limits, qd, parts, lag, move)
    if needed <= longest:
        chosen = max(move, needed)
        return Motion(chosen, amplitude, binding if chosen > move else "", tuple(notes), weak,
                      carry)
    scale, why = _amplitude_scale(limits, qd, parts, lag, longest,
                                  lambda share: dynamics(*unit_profile(ranges, amplitude * share)))
    cut = np.nonzero(scale < 1)[0]
    shrunk = [f"'{limits.joints[v]}' {100 * scale[v]:.0f}%" for v in cut]
    header = ""
    if shrunk:
        notes.append(f"to stay within the limits at {longest:g} s per move, joints move this "
                     "share of the default amplitude: " + ", ".join(shrunk))
        low, high = 100 * scale[cut].min(), 100 * scale[cut].max()
        share = f"{low:.0f}%" if round(low) == round(high) else f"{low:.0f}-{high:.0f}%"
        fit = (f"to fit the given duration of {2 * longest:g} s" if fixed else
               f"to keep the run within {2 * longest:g} s")
        header = (f"amplitude cut to {share} of the default for {len(cut)} of {len(scale)} "
                  f"joints {fit} ({', '.join(why)}; see the notes)")
    return Motion(longest, amplitude * scale, "", tuple(notes), weak, carry, header)


def _counterbalanced(counterbalance: Callable[[np.ndarray], Counterbalance] | None,
                     dynamics: Dynamics, q: np.ndarray
                     ) -> tuple[Counterbalance | None, Dynamics, list[str]]:
    """(the counterbalance of the static loads along the poses ``q``, or None; ``dynamics``
    relieved of it; the notes on the loads too large to be one)."""
    if counterbalance is None:
        return None, dynamics, []
    carry = counterbalance(dynamics(q, np.zeros_like(q), np.zeros_like(q))[2])
    if not carry.active:
        return None, dynamics, carry.refused
    return carry, carry.relieve(dynamics), carry.refused


@dataclass(frozen=True)
class Lag:
    """The predicted tracking error of the sampled loop along the unit profile.

    Two effects, each scaled by the joints' amplitudes:

    * the torque the delay leaves out, ``d3/T^3 + d1/T`` (joint torques: the change of
      ``M qdd + C qd`` and of gravity over one period), costs the acceleration ``M^-1 @`` that;
    * damping compensated from an older reading makes a joint act ``rho = 1 + c dt D / m``
      times heavier than the controller assumes (``m`` its effective inertia, ``c`` = 1, or 2
      with the delay): the loop's gains are divided by ``rho`` and a share ``1 - 1/rho`` of
      the reference acceleration is missing.

    The error is that acceleration through the error dynamics ``e'' + kd/rho e' + kp/rho e = a``
    (bounded by ``max |a| rho / kp`` for real poles, which is tried first), so a brief shortfall,
    such as passing two aligned axes, costs less than a steady one.
    """

    d3: np.ndarray  # (samples, nv) torques
    d1: np.ndarray
    damped: np.ndarray  # (samples, nv) accelerations, scaling with 1 / T^2
    inverse: np.ndarray  # (samples, nv, nv) M^-1 / rho (rows)
    kp: np.ndarray  # kp / rho, kd / rho (worst along the profile)
    kd: np.ndarray
    budget: float

    @staticmethod
    def along(limits: Limits, q: np.ndarray, qdd: np.ndarray, parts: Parts,
              gravity: np.ndarray, budget: float) -> Lag:
        quadratic, _, _ = parts
        delay, dt = float(limits.delay), limits.dt
        inverse = np.nan_to_num(limits.inverse_mass(q))
        diagonal = np.einsum("njj->nj", inverse)
        rho = 1.0 + (1.0 + delay) * dt * limits.damping * np.maximum(diagonal, 0.0)
        worst = rho.max(axis=0, initial=1.0)
        return Lag(delay * dt * _rate(quadratic), delay * dt * _rate(gravity),
                   (1.0 - 1.0 / rho) * qdd, inverse / rho[:, :, None],
                   limits.kp / worst, limits.kd / worst, budget)

    def acceleration(self, move: float, scale: np.ndarray | None = None) -> np.ndarray:
        """(samples, nv): the acceleration each joint lacks, with amplitudes ``scale``."""
        torque = self.d3 / move**3 + self.d1 / move
        damped = self.damped / move**2
        if scale is not None:
            torque, damped = torque * scale, damped * scale
        return np.einsum("nij,nj->ni", self.inverse, torque) + damped

    def error(self, move: float, scale: np.ndarray | None = None) -> np.ndarray:
        """Per joint, the largest predicted error over the run."""
        lacking = self.acceleration(move, scale)
        with np.errstate(divide="ignore", invalid="ignore"):
            bound = np.nan_to_num(np.abs(lacking).max(axis=0, initial=0.0) / self.kp)
        close = (bound > self.budget) | (self.kd**2 < 4 * self.kp)  # complex poles overshoot
        if close.any():
            bound[close] = _filtered(lacking[:, close], self.kp[close], self.kd[close],
                                     move / (SAMPLES - 1))
        return bound

    def culprits(self, move: float, scale: np.ndarray, joint: int) -> np.ndarray:
        """The joints whose lagging torque makes most of ``joint``'s worst shortfall."""
        torque = (self.d3 / move**3 + self.d1 / move) * scale
        share = self.inverse[:, joint, :] * torque
        share[:, joint] += self.damped[:, joint] * scale[joint] / move**2
        worst = int(np.argmax(np.abs(share.sum(axis=1))))
        size = np.abs(share[worst])
        return np.nonzero(size >= 0.5 * size.max())[0]


def _filtered(lacking: np.ndarray, kp: np.ndarray, kd: np.ndarray, h: float) -> np.ndarray:
    """Peak |e| of ``e'' + kd e' + kp e = a`` from rest, ``a`` held over samples ``h`` apart."""
    n, nv = lacking.shape
    system = np.zeros((nv, 3, 3))
    system[:, 0, 1] = 1.0
    system[:, 1, 0], system[:, 1, 1], system[:, 1, 2] = -kp, -kd, 1.0
    step = _expm(system * h)
    Ad, Bd = step[:, :2, :2], step[:, :2, 2]
    response = np.zeros((n, nv))  # e at sample k after a unit input held over sample 0
    state = Bd.copy()
    for k in range(1, n):
        response[k] = state[:, 0]
        state = np.einsum("jab,jb->ja", Ad, state)
    size = 1 << (2 * n - 1).bit_length()
    error = np.fft.irfft(np.fft.rfft(lacking, size, axis=0) * np.fft.rfft(response, size, axis=0),
                         size, axis=0)[:n]
    return np.abs(error).max(axis=0)


def _expm(a: np.ndarray) -> np.ndarray:
    """exp of a stack of small matrices: scaling and squaring of a Taylor series."""
    norm = float(np.abs(a).sum(axis=-1).max(initial=0.0))
    squarings = max(0, int(np.ceil(np.log2(norm / 0.25))) if norm > 0.25 else 0)
    x = a / 2.0**squarings
    term = np.broadcast_to(np.eye(a.shape[-1]), a.shape).copy()
    total = term.copy()
    for k in range(1, 12):
        term = term @ x / k
        total += term
    for _ in range(squarings):
        total = total @ total
    return total


def _rate(values: np.ndarray) -> np.ndarray:
    """d/ds along the unit profile, each move (SAMPLES rows) on its own."""
    ds = 1.0 / (SAMPLES - 1)
    return np.vstack([np.gradient(values[:SAMPLES], ds, axis=0),
                      np.gradient(values[SAMPLES:], ds, axis=0)])


def _cannot_hold(limits: Limits, static: np.ndarray) -> tuple[str, ...]:
    """Why actuators cannot hold the robot still on the reference (gravity, friction)."""
    effort = np.abs(static @ limits.eff_j2a.T).max(axis=0)
    reasons = []
    for a in np.nonzero(effort > limits.actuator_effort)[0]:
        joints = ", ".join(f"'{limits.joints[v]}'" for v in np.nonzero(limits.eff_j2a[a])[0])
        reasons.append(f"actuator '{limits.actuators[a]}': holding joint {joints} against "
                       f"gravity needs {effort[a]:.4g}, beyond its effort limit "
                       f"{limits.actuator_effort[a]:.4g} (the URDF may lack a counterbalance "
                       "or spring)")
    return tuple(reasons)


def _held_still(limits: Limits, static: np.ndarray) -> dict[int, str]:
    """Joints whose actuator cannot even hold gravity and Coulomb friction along the path."""
    effort = np.abs(static @ limits.eff_j2a.T).max(axis=0)
    held: dict[int, str] = {}
    for a in np.nonzero(effort > MARGIN * limits.actuator_effort)[0]:
        percent = 100 * effort[a] / limits.actuator_effort[a]
        for v in np.nonzero(limits.eff_j2a[a])[0]:
            held.setdefault(int(v), f"gravity and friction alone need {percent:.0f}% of "
                                    f"actuator '{limits.actuators[a]}''s effort limit")
    return held


def _move_time(limits: Limits, qd: np.ndarray, parts: Parts, lag: Lag, start: float
               ) -> tuple[float, str]:
    """The shortest move time (at least ``start``) within every limit, and what binds it."""
    speed = np.abs(qd).max(axis=0)
    candidates = [(start, "")]
    with np.errstate(divide="ignore", invalid="ignore"):
        joint = speed / (MARGIN * limits.velocity)
        actuator = np.abs(qd @ limits.vel_j2a.T).max(axis=0) / (MARGIN * limits.actuator_speed)
    for values, what in ((joint, "joint '{}' velocity limit"),
                         (actuator, "actuator '{}' speed limit")):
        values = np.nan_to_num(values, nan=0.0, posinf=0.0)
        if len(values) and values.max() > 0:
            k = int(np.argmax(values))
            names = limits.actuators if "actuator" in what else limits.joints
            candidates.append((float(values[k]), what.format(names[k])))
    move, binding = candidates[0]
    for value, what in candidates[1:]:  # the first named wins a tie (a joint, its actuator)
        if value > move * (1 + 1e-9):
            move, binding = value, what
    quadratic, linear, static = parts
    limit = MARGIN * limits.actuator_effort
    hopeless = np.abs(static @ limits.eff_j2a.T).max(axis=0) > limit  # no move time helps
    for _ in range(400):
        effort = np.abs((quadratic / move**2 + linear / move + static) @ limits.eff_j2a.T)
        over = (effort.max(axis=0) > limit) & ~hopeless
        late = lag.error(move) > lag.budget
        if not (over.any() or late.any()):
            return move, binding
        move *= GRID
        if over.any():
            binding = f"actuator '{limits.actuators[int(np.argmax(over))]}' effort limit"
        else:
            binding = (f"the tracking lag of joint '{limits.joints[int(np.argmax(late))]}' "
                       "(torque applied a period late)")
    return move, binding


def _amplitude_scale(limits: Limits, qd: np.ndarray, parts: Parts, lag: Lag, move: float,
                     exact: Callable[[np.ndarray], Parts]) -> tuple[np.ndarray, list[str]]:
    """Per joint, the share of the default amplitude that fits in ``move`` seconds, and which
    limits cut it.

    Efforts are evaluated on the shrunk motion itself (``exact(scale)``): a joint's torque
    also carries the other joints' accelerations, which shrink by their own shares.
    """
    scale = np.ones(qd.shape[1])
    speed = np.abs(qd).max(axis=0) / move
    with np.errstate(divide="ignore", invalid="ignore"):
        scale = np.minimum(scale, np.nan_to_num(MARGIN * limits.velocity / speed, nan=1.0))
    why = dict.fromkeys(("joint velocity limits", "actuator speed limits",
                         "actuator effort limits", "tracking lag of the delayed loop"), False)
    why["joint velocity limits"] = bool((scale < 1).any())
    static = parts[2]
    hopeless = np.abs(static @ limits.eff_j2a.T).max(axis=0) > MARGIN * limits.actuator_effort
    for _ in range(200):
        a_speed = np.abs((qd * scale) @ limits.vel_j2a.T).max(axis=0) / move
        quadratic, linear, static = exact(scale)
        effort = np.abs((quadratic / move**2 + linear / move + static)
                        @ limits.eff_j2a.T).max(axis=0)
        over = (a_speed > MARGIN * limits.actuator_speed) \
            | ((effort > MARGIN * limits.actuator_effort) & ~hopeless)
        late = np.nonzero(lag.error(move, scale) > lag.budget)[0]
        if not (over.any() or len(late)):
            break
        why["actuator speed limits"] |= bool((a_speed > MARGIN * limits.actuator_speed).any())
        why["actuator effort limits"] |= bool((over & ~(a_speed > MARGIN
                                                        * limits.actuator_speed)).any())
        why["tracking lag of the delayed loop"] |= bool(len(late))
        shrink = np.abs(limits.vel_j2a[over]).sum(axis=0) + np.abs(limits.eff_j2a[over]).sum(axis=0)
        joints = set(np.nonzero(shrink)[0].tolist())
        for v in late:
            joints.update(lag.culprits(move, scale, int(v)).tolist())
        scale[sorted(joints)] *= 0.95
    return scale, [what for what, cut in why.items() if cut]


def sample(ranges: list[tuple[float, float]], motion: Motion, dt: float) -> Reference:
    """The reference of ``motion`` at every control step (two moves: up, then back).

    Each move is evaluated on its own steps only, for every joint at once: the profile's
    powers of the normalised time are shared, and each value is the same IEEE operation as
    evaluating the joints one by one over the whole run.
    """
    t = step_times(2 * motion.move, dt)
    low, high = _ends(ranges, motion.amplitude)
    second = t >= motion.move  # the times increase: the up move's rows come first
    up = minimum_jerk(t[~second, None], 0.0, motion.move, low, high)
    down = minimum_jerk(t[second, None], motion.move, 2 * motion.move, high, low)
    q, qd, qdd = (np.concatenate(pair) for pair in zip(up, down, strict=True))
    return Reference(t, q, qd, qdd, describe(motion))


def describe(motion: Motion) -> str:
    text = f"minimum-jerk 25% -> 75% -> 25% of each range, {motion.move:.3g} s per move"
    if len(motion.amplitude) > 1:
        text = (f"minimum-jerk 25% -> 75% -> 25% of each range, shifted by a share of its own "
                f"per joint (within ±{100 * SHIFT:.0f}%), {motion.move:.3g} s per move")
    if motion.binding:
        text += f" (slowed for {motion.binding})"
    if motion.shrunk:
        text += f"; {motion.shrunk}"
    return text
