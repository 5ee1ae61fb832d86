"""What a run produced (time series) and what it means (metrics, verdict, reasons)."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from txtool.lint.readers import FileReaders
from txtool.simulation.params import GainSource

if TYPE_CHECKING:
    from txtool.simulation.controlled import Driver

LIMIT_SLACK = 1e-9  # position limits: ignore round-off at a limit
SHOWN_REASONS = 2  # why a run checked nothing: the first reasons, in the verdict line

# What a cause is about (``Cause.kind``), for programs that read the result.
KINDS = (
    "direction",  # a joint or actuator reversed
    "reduction",  # a reduction off by a factor (perhaps reversed too)
    "offset",  # a joint offset differs
    "joints_swapped",  # joints read each other's positions
    "actuators_swapped",  # actuators read each other's positions
    "roles_swapped",  # ROS 1 roles given to other joints or actuators than the robot's
    "coupling",  # joints coupled otherwise, no simpler reading
    "effort_convention",  # an effort map that is not the robot's
    "transmission_kind",  # another kind of transmission, or one the robot lacks
    "missing_transmission",  # a joint the config gives no transmission
    "xml_order",  # ROS 2: parameters in XML order, bound to the names sorted
    "interface",  # commanded through other interfaces than the robot's
    "not_transmissions",  # the maps agree: the failure comes from elsewhere
    "controller_refused",  # --controllers: the controller manager refuses a controller
)


@dataclass(frozen=True)
class Cause:
    """One difference between the candidate and the robot: its kind and its sentence."""

    kind: str
    text: str

    def __post_init__(self) -> None:
        if self.kind not in KINDS:
            raise ValueError(f"unknown cause kind {self.kind!r}")


@dataclass
class Series:
    """Time series of one run; efforts are defined on [0, steps), states on [0, steps]."""

    time: np.ndarray
    joints: tuple[str, ...]
    units: tuple[str, ...]
    actuators: tuple[str, ...]
    transmission_of: tuple[str, ...]
    q_ref: np.ndarray
    q: np.ndarray
    effort_demand: np.ndarray
    effort: np.ndarray
    velocity: np.ndarray  # actuator speeds
    effort_limit: np.ndarray
    velocity_limit: np.ndarray
    lower: np.ndarray
    upper: np.ndarray
    joint_actuators: dict[str, list[int]] = field(default_factory=dict)


@dataclass
class JointStats:
    max_error: float
    rms_error: float
    max_error_time: float
    limit_margin: float | None  # smallest distance to a position limit (negative: outside)
    units: str
    transmission: str = ""  # "" when driven directly


def effort_units(joint_units: str) -> str:
    return "N" if joint_units == "m" else "N·m"


def speed_units(joint_units: str) -> str:
    return f"{joint_units}/s"


@dataclass
class ActuatorStats:
    peak_effort: float
    effort_limit: float
    rms_effort: float
    peak_velocity: float
    velocity_limit: float
    saturated_fraction: float
    first_violation: float | None
    transmission: str
    units: str = "rad"  # of its joints: "rad" (rotary, N·m, rad/s), "m" (linear, N, m/s) or "mixed"

    @property
    def effort_units(self) -> str:
        return "N·m|N" if self.units == "mixed" else effort_units(self.units)

    @property
    def speed_units(self) -> str:
        return "rad/s|m/s" if self.units == "mixed" else speed_units(self.units)

    @property
    def effort_percent(self) -> float:
        return _percent(self.peak_effort, self.effort_limit)

    @property
    def velocity_percent(self) -> float:
        return _percent(self.peak_velocity, self.velocity_limit)


def _percent(value: float, limit: float) -> float:
    if math.isinf(limit):
        return 0.0
    return math.inf if limit == 0 else 100.0 * value / limit


@dataclass(frozen=True)
class GainsUsed:
    """The acceleration gains a joint ran with and where they came from."""

    kp: float  # 1/s^2
    kd: float  # 1/s
    ki: float  # 1/s^3
    i_clamp: float | None  # bound of |ki * integral(e)| in rad/s^2 (m/s^2); None: no bound
    units: str  # of the joint: rad | m
    source: GainSource | None  # None: the default, critically damped at ``bandwidth``
    bandwidth: float | None = None
    inertia: float | None = None  # effort gains were divided by this M_ii (kg m^2 or kg)


@dataclass(frozen=True)
class Coverage:
    """What a run checked: the config's transmissions driven through their maps, of those read.

    A transmission that cannot be simulated (a custom type, a loader refusal, ``--skip``...)
    leaves its joints driven directly, so nothing about it is checked.
    """

    transmissions: int = 0  # read from the config
    simulated: tuple[str, ...] = ()  # driven and tracked through their maps
    skipped: tuple[tuple[str, str], ...] = ()  # (transmission, why) left out
    joints: int = 0  # moving joints of the model
    joints_checked: int = 0  # joints driven through a simulated transmission
    unread: tuple[tuple[str, str], ...] = ()  # (transmission, why) no reader of the file reads
    still: tuple[str, ...] = ()  # checked joints the reference does not move (limits cut it)
    why: str = ""  # why nothing was checked, when no transmission was the reason

    @property
    def nothing(self) -> bool:
        return not self.simulated

    @property
    def in_file(self) -> int:
        """The config's transmissions, read or not: the count of the file."""
        return self.transmissions + len(self.unread)

    @property
    def partial(self) -> bool:
        return bool(self.simulated) and (len(self.simulated) < self.in_file
                                         or self.joints_checked < self.joints
                                         or bool(self.still))

    def summary(self) -> str:
        unread = f" ({len(self.unread)} read by no reader of the file)" if self.unread else ""
        named = ", ".join(f"'{j}'" for j in self.still[:SHOWN_REASONS])
        if len(self.still) > SHOWN_REASONS:
            named += f" and {len(self.still) - SHOWN_REASONS} more"
        still = (f"; the reference does not move {len(self.still)} of them ({named}: see the "
                 "notes)" if self.still else "")
        return (f"checked {len(self.simulated)} of {self.in_file} transmissions{unread} and "
                f"{self.joints_checked} of {self.joints} joints{still}")

    def why_nothing(self) -> str:
        if self.why:
            return self.why
        if not self.transmissions and self.unread:
            return (f"no reader of the config reads any of its {len(self.unread)} "
                    f"transmissions ({self.unread[0][1]})")
        if not self.transmissions:
            return "the config has no transmission: every joint is driven directly"
        reasons = list(dict.fromkeys(why for _, why in self.skipped))
        shown = "; ".join(reasons[:SHOWN_REASONS])
        if len(reasons) > SHOWN_REASONS:
            shown += f"; {len(reasons) - SHOWN_REASONS} more reasons in the notes"
        return f"none of the config's {self.transmissions} transmissions can be simulated ({shown})"


@dataclass
class RunResult:
    robot: str
    config: str
    dt: float
    steps: int
    duration: float
    reference: str
    joints: dict[str, JointStats]
    actuators: dict[str, ActuatorStats]
    reasons: list[str]
    notes: list[str]
    series: Series | None = None
    timings: dict[str, float] = field(default_factory=dict)
    gains: dict[str, GainsUsed] = field(default_factory=dict)
    tolerance: float | None = None
    # per joint: static_load, limit, carried (peaks) and units of an assumed counterbalance
    counterbalance: dict[str, dict[str, float | str]] = field(default_factory=dict)
    coverage: Coverage = field(default_factory=Coverage)
    # "robot" and, with --candidate, "config": the programs that read each file, and why
    readers: dict[str, FileReaders] = field(default_factory=dict)
    # what differs from the robot's config, each with its kind (diagnose.Cause)
    causes: list[Cause] = field(default_factory=list)
    # --controllers: per joint of the model, the controller commanding it (None: held)
    controllers: dict[str, Driver | None] = field(default_factory=dict)

    @property
    def failed(self) -> bool:
        return bool(self.reasons)

    @property
    def passed(self) -> bool:
        """Every check held, and at least one transmission of the config was checked."""
        return not self.reasons and not self.coverage.nothing

    @property
    def verdict(self) -> str:
        """``pass``, ``fail`` or ``inconclusive`` (nothing of the config could be checked)."""
        if self.reasons:
            return "fail"
        return "inconclusive" if self.coverage.nothing else "pass"


def joint_stats(series: Series) -> dict[str, JointStats]:
    error = series.q - series.q_ref
    stats = {}
    for v, name in enumerate(series.joints):
        column = np.abs(error[:, v])
        worst = int(np.argmax(column))
        lower, upper = series.lower[v], series.upper[v]
        margin = None
        if math.isfinite(lower) and math.isfinite(upper):
            margin = float(np.min(np.minimum(series.q[:, v] - lower, upper - series.q[:, v])))
        stats[name] = JointStats(
            max_error=float(column[worst]),
            rms_error=float(np.sqrt(np.mean(column**2))),
            max_error_time=float(series.time[worst]),
            limit_margin=margin,
            units=series.units[v],
            transmission=next((series.transmission_of[i]
                               for i in series.joint_actuators.get(name, [])), ""),
        )
    return stats


def actuator_stats(series: Series) -> dict[str, ActuatorStats]:
    demand = np.abs(series.effort_demand)
    speed = np.abs(series.velocity)
    over_effort = demand > series.effort_limit
    over_speed = speed > series.velocity_limit
    stats = {}
    for i, name in enumerate(series.actuators):
        first = _first(series.time, over_effort[:, i], over_speed[:, i])
        kinds = {series.units[series.joints.index(j)]
                 for j, owned in series.joint_actuators.items() if i in owned}
        stats[name] = ActuatorStats(
            peak_effort=float(demand[:, i].max(initial=0.0)),
            effort_limit=float(series.effort_limit[i]),
            rms_effort=float(np.sqrt(np.mean(demand[:, i] ** 2))) if len(demand) else 0.0,
            peak_velocity=float(speed[:, i].max(initial=0.0)),
            velocity_limit=float(series.velocity_limit[i]),
            saturated_fraction=float(np.mean(over_effort[:, i])) if len(demand) else 0.0,
            first_violation=first,
            transmission=series.transmission_of[i],
            units=kinds.pop() if len(kinds) == 1 else ("mixed" if kinds else "rad"),
        )
    return stats


def _first(time: np.ndarray, effort: np.ndarray, speed: np.ndarray) -> float | None:
    hits = [int(np.argmax(flags)) for flags in (effort, speed) if flags.any()]
    return float(time[min(hits)]) if hits else None


def verdict_reasons(series: Series, joints: dict[str, JointStats],
                    actuators: dict[str, ActuatorStats], tolerance: float,
                    allow_saturation: bool) -> list[str]:
    """Why the run fails (empty when it passes), worst offenders first within each check."""
    reasons = []
    for name, j in sorted(joints.items(), key=lambda kv: -kv[1].max_error):
        if not j.max_error <= tolerance:
            reasons.append(f"joint '{name}': tracking error {j.max_error:.4g} {j.units} exceeds "
                           f"the tolerance {tolerance:g} {j.units} (at t={j.max_error_time:.3f} s)")
    for v, name in enumerate(series.joints):
        j = joints[name]
        if j.limit_margin is not None and j.limit_margin < -LIMIT_SLACK:
            t = _first_outside(series, v)
            reasons.append(f"joint '{name}': leaves its position limits by "
                           f"{-j.limit_margin:.4g} {j.units} (first at t={t:.3f} s)")
    if allow_saturation:
        return reasons
    for name, a in actuators.items():
        first = f" (first at t={a.first_violation:.3f} s)" if a.first_violation is not None else ""
        effort, speed = a.effort_units, a.speed_units
        if a.peak_effort > a.effort_limit:
            reasons.append(f"actuator '{name}': effort {a.peak_effort:.4g} {effort} exceeds its "
                           f"limit {a.effort_limit:.4g} {effort}, saturated "
                           f"{100 * a.saturated_fraction:.1f}% of the time{first}")
        if a.peak_velocity > a.velocity_limit:
            reasons.append(f"actuator '{name}': speed {a.peak_velocity:.4g} {speed} exceeds its "
                           f"limit {a.velocity_limit:.4g} {speed}{first}")
    return reasons


def _first_outside(series: Series, v: int) -> float:
    q = series.q[:, v]
    outside = (q < series.lower[v] - LIMIT_SLACK) | (q > series.upper[v] + LIMIT_SLACK)
    return float(series.time[int(np.argmax(outside))])
