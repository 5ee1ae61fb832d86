"""One simulate run per candidate config: load, build, run the loop, judge."""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field, replace

import numpy as np

from txtool.io.load import load
from txtool.io.xmlio import InputError, Source, XacroOptions
from txtool.lint.config import readers_of
from txtool.lint.readers import FileReaders, record
from txtool.simulation import (
    checks,
    controlled,
    counterbalance,
    feasible,
    gains,
    loop,
    reference,
    result,
    setup,
)
from txtool.simulation.drive import Drive, read_drive
from txtool.simulation.model import Massless, RobotModel, build
from txtool.simulation.parameter_files import load_params
from txtool.simulation.params import Params, merge
from txtool.simulation.plan import Controller, Plan, RunState
from txtool.simulation.sensing import Sensing

DEFAULTS = {"bandwidth": 20.0, "duration": 5.0, "dt": 0.001, "tolerance": 0.01}
MAX_STEPS = 20_000_000
MAX_SETTING = 1e9  # of --bandwidth, --duration, --dt, --tolerance (far beyond any robot's)
# What a run holds per step and per joint or actuator, measured (reference, loop state and
# series: about 17 floats), and the most a run may hold: priced before anything is allocated.
BYTES_PER_STEP_AND_COLUMN = 160
MAX_RUN_BYTES = 2 * 1024**3

Progress = Callable[[int, int], None]  # (steps done, steps in all)


@dataclass(frozen=True)
class Options:
    """Run settings; None means "from the params file, else the default"."""

    robot: str
    configs: tuple[str, ...] = ()
    labels: tuple[str, ...] = ()  # display names for configs (default: their paths)
    params: str | tuple[str, ...] | None = None
    bandwidth: float | None = None
    duration: float | None = None
    dt: float | None = None
    tolerance: float | None = None
    trajectory: str | None = None
    interpolation: str = "cubic"
    allow_saturation: bool = False
    loader: str = "auto"
    convention: str | None = None  # the controller's effort maps; None: each file's loader
    xacro: XacroOptions = field(default_factory=XacroOptions)
    jobs: int = 1
    keep_series: bool = True
    skip: tuple[str, ...] = ()  # transmission names left out (joints driven directly)
    delay: bool = True  # one control period between read and write (sensing.py)
    encoder_counts: int | None = None
    counterbalance: bool = True  # static loads beyond the effort limits: counterbalance.py
    ros_distro: str | None = None  # --ros-distro: the distribution reading the files
    controllers: tuple[str, ...] = ()  # --controllers: the configurations of the controllers


@dataclass(frozen=True)
class Settings:
    bandwidth: float
    duration: float
    dt: float
    tolerance: float


def settings(options: Options, params: Params) -> Settings:
    values = {}
    for key, default in DEFAULTS.items():
        given = getattr(options, key)
        value = given if given is not None else params.run.get(key, default)
        if not (math.isfinite(value) and value > 0):
            raise InputError(f"--{key}: must be a positive number, got {value!r}")
        if value > MAX_SETTING:  # (a bandwidth of 1e307 overflowed the gains' powers)
            raise InputError(f"--{key}: at most {MAX_SETTING:g}, got {value!r}")
        values[key] = float(value)
    if values["dt"] > values["duration"]:
        raise InputError(f"--dt: {values['dt']:g} s is longer than the run "
                         f"({values['duration']:g} s)")
    if values["duration"] / values["dt"] > MAX_STEPS:
        raise InputError(f"--duration/--dt: more than {MAX_STEPS} steps")
    return Settings(**values)


def price(duration: float, dt: float, columns: int, what: str) -> None:
    """Refuse, in one line, a run of ``duration`` at ``dt`` whose arrays for ``columns``
    joints and actuators would exceed :data:`MAX_RUN_BYTES` (before they are allocated)."""
    steps = duration / dt + 1
    needed = steps * max(columns, 1) * BYTES_PER_STEP_AND_COLUMN
    if needed > MAX_RUN_BYTES:
        raise InputError(f"{what}: {steps:.0f} steps of {columns} joints and actuators would "
                         f"hold about {needed / 1024**3:.1f} GiB (at most "
                         f"{MAX_RUN_BYTES // 1024**3} GiB): a shorter run or a longer --dt")


@dataclass
class Prepared:
    """Everything a run needs, built: the loop's :class:`plan.Plan` and what judges it."""

    options: Options
    config: str | None
    label: str
    robot: RobotModel
    plant: Drive
    ctrl: Drive
    binding: setup.Binding
    plan: Plan
    ref: reference.Reference
    settings: Settings
    duration: float
    effort_limit: np.ndarray
    speed_limit: np.ndarray
    setup_s: float
    reference_notes: list[str] = field(default_factory=list)
    cannot_hold: list[str] = field(default_factory=list)  # the robot, not the config, is short
    controller: Controller | None = None
    readers: dict[str, FileReaders] = field(default_factory=dict)
    gains: dict[str, result.GainsUsed] = field(default_factory=dict)
    notes: tuple[str, ...] = ()
    carried: dict[str, dict[str, float | str]] = field(default_factory=dict)
    unstable: list[str] = field(default_factory=list)  # joints whose sampled loop is unstable
    controllers: dict[str, controlled.Driver | None] = field(default_factory=dict)


@dataclass
class Unchecked:
    """A run with nothing to check: the config has no transmission that can be simulated.

    It is judged before any motion is planned or simulated: driving every joint directly
    would only test the controller against itself.
    """

    options: Options
    label: str
    notes: list[str]
    coverage: result.Coverage
    readers: dict[str, FileReaders] = field(default_factory=dict)
    causes: list[result.Cause] = field(default_factory=list)  # the config's fault, seen unrun

    def judged(self) -> result.RunResult:
        return result.RunResult(
            robot=self.options.robot, config=self.label, dt=0.0, steps=0, duration=0.0,
            reference="not simulated", joints={}, actuators={},
            reasons=[cause.text for cause in self.causes], notes=self.notes,
            coverage=self.coverage, readers=self.readers, causes=list(self.causes))


def dropped(plant: Drive, ctrl: Drive) -> list[result.Cause]:
    """A candidate without any transmission where the robot simulates some: each of the
    robot's is missing (its joints driven directly), a fault no run needs to show."""
    if ctrl.names or ctrl.unread:
        return []
    return [result.Cause("missing_transmission",
                         f"the config has no transmission '{m.name}': "
                         f"{_named('joint', m.joints)} driven directly where the robot has a "
                         f"{_KINDS[m.kind]} transmission to {_named('actuator', m.actuators)}")
            for m in plant.maps]


def _named(what: str, names: tuple[str, ...]) -> str:
    """``joint 'a' is`` or ``joints 'a', 'b' are`` (``actuator 'm'``, ``actuators ...``)."""
    quoted = ", ".join(f"'{name}'" for name in names)
    verb = "" if what == "actuator" else (" is" if len(names) == 1 else " are")
    return f"{what}{'' if len(names) == 1 else 's'} {quoted}{verb}"


_KINDS = {"simple": "simple", "differential": "differential", "four_bar": "four-bar"}


def _nothing_to_move(options: Options, candidate: Source, label: str,
                     readers: dict[str, FileReaders], massless: Massless) -> Unchecked:
    """A robot without inertials whose config has no transmission either: nothing of the
    config is there to check (inconclusive), whether or not the robot could be simulated.
    With a transmission to check, the robot's missing inertials are the input error."""
    from txtool.dialects.read import read_source

    if read_source(candidate, locate=False):
        raise massless
    note = f"the robot could not be simulated either: {massless}"
    return Unchecked(options, label, [note], result.Coverage(), readers)


def coverage_of(robot: RobotModel, ctrl: Drive) -> result.Coverage:
    """What a run of ``ctrl`` on ``robot`` checks: the transmissions it drives, of those read."""
    return result.Coverage(
        transmissions=len(ctrl.names), simulated=tuple(m.name for m in ctrl.maps),
        skipped=tuple(ctrl.skipped.items()), joints=len(robot.joints),
        joints_checked=len(robot.joints) - len(ctrl.direct), unread=tuple(ctrl.unread.items()))


def prepare(options: Options, config: str | None, label: str | None = None
            ) -> Prepared | Unchecked:
    """Load ROBOT and the config, build the model, parameters, reference and loop matrices."""
    started = time.perf_counter()
    # The command says once whether --xacro-arg reaches any of its files (a plain candidate
    # beside a xacro robot is no reason for a warning).
    source = load(options.robot, xacro=options.xacro, warn_unused=False)
    # Each file's transmissions as its readers read them (validate's decision).
    robot_readers = readers_of(source, options.ros_distro)
    candidate, config_readers = source, robot_readers
    if config is not None:
        candidate = load(config, xacro=options.xacro, warn_unused=False)
        config_readers = readers_of(candidate, options.ros_distro)
    readers = {"robot": record(source.path, robot_readers)}
    if config is not None:
        readers["config"] = record(candidate.path, config_readers)
    label = label or (config if config is not None else options.robot)
    try:
        robot = build(source)
    except Massless as massless:
        return _nothing_to_move(options, candidate, label, readers, massless)
    # The plant is physics: power-conserving effort maps (ros2_control's). The controller
    # runs the maps of the loader that reads its file, unless --effort-convention says.
    plant = read_drive(source, robot, loader=options.loader, readers=robot_readers,
                       convention="ros2", skip=options.skip)
    ctrl = read_drive(candidate, robot, loader=options.loader, readers=config_readers,
                      convention=options.convention, skip=options.skip)
    unknown = sorted(set(options.skip) - set(plant.names) - set(ctrl.names))
    if unknown:
        raise InputError(f"--skip: no transmission named {', '.join(map(repr, unknown))} in "
                         f"{options.robot}" + (f" or {config}" if config else ""))
    covered = coverage_of(robot, ctrl)
    drives = None
    if options.controllers:
        drives = controlled.read(options.controllers, candidate, robot.joints,
                                 frozenset(robot.followers))
        if drives.refused or not drives.drivers:
            return _uncontrolled(options, label, drives, readers)
    if covered.nothing:
        return Unchecked(options, label, _notes(robot, plant, ctrl, config is not None), covered,
                         readers, dropped(plant, ctrl) if config is not None else [])
    params = _params(options, drives)
    params.check_names(set(plant.actuators) | set(ctrl.actuators), set(robot.joints),
                       options.robot)
    run_settings = settings(options, params)
    columns = len(robot.joints) + len(plant.actuators)
    price(run_settings.duration, run_settings.dt, columns, "--duration/--dt")
    binding = setup.bind(plant, ctrl)
    rotor = (setup.rotor_inertias(plant.actuators, params, plant, ctrl),
             setup.rotor_inertias(ctrl.actuators, params, plant, ctrl))
    effort_limit, speed_limit = setup.actuator_limits(robot, plant, params)
    inertia = plant.reflected_inertia(rotor[0])
    table = None if options.trajectory is None else _table(options, robot)
    params, converted = gains.in_acceleration(params, robot, plant, rotor[0],
                                              _start(robot, table))
    controller = setup.controller(robot, params, run_settings.bandwidth)
    finder = _finder(robot, plant, effort_limit) if options.counterbalance else None
    if table is None:
        fixed = options.duration is not None or "duration" in params.run
        limits = setup.motion_limits(robot, plant, inertia, controller, effort_limit,
                                     speed_limit, run_settings.dt, options.delay)
        ref, duration, ref_notes, weak, carry = _default_reference(
            robot, run_settings, limits, setup.reference_dynamics(robot, inertia), fixed, finder,
            drives.held if drives is not None else ())
    else:
        ref, duration, ref_notes = _reference(options, table, robot, run_settings)
        weak, carry = [], None
    if drives is not None and drives.held:
        ref = reference.hold(ref, robot.joints, drives.held)
        ref_notes.append(_held_note(drives.held, table is None))
    if table is not None and finder is not None:  # found on every tenth pose, used at every step
        carry = finder(setup.gravity_along(robot, ref.q[::10]))
    carried, carry_notes, carry_table = None, [], {}
    if table is not None and carry is not None:
        carry_notes = carry.refused  # (the default motion's planner notes them itself)
    if carry is not None and carry.active:
        gravity = setup.gravity_along(robot, ref.q)
        carried = carry.carried(gravity)
        carry_notes, carry_table = carry_notes + carry.notes(gravity), carry.table(gravity)
    plan = setup.build_plan(robot, plant, ctrl, binding, rotor, effort_limit, controller, ref,
                            run_settings.dt, Sensing(options.delay, options.encoder_counts),
                            carried)
    used = gains.used(robot, params, controller, run_settings.bandwidth, converted)
    stiff, unstable = _stability(robot, inertia, ref, used, plan)
    return Prepared(options, config, label, robot, plant, ctrl, binding, plan, ref,
                    run_settings, duration, effort_limit, speed_limit,
                    time.perf_counter() - started, carry_notes + ref_notes, weak, controller,
                    readers, used, params.notes + tuple(stiff), carry_table, unstable,
                    drives.report(robot.joints) if drives is not None else {})


def _params(options: Options, drives: controlled.Controlled | None) -> Params:
    """The parameter files' values over the gains of the controllers driving the joints:
    ``--params`` is the tuning asked for."""
    params = load_params(options.params, options.robot)
    if drives is None:
        return params
    return replace(merge([drives.params, params]), notes=drives.notes + params.notes)


def _uncontrolled(options: Options, label: str, drives: controlled.Controlled,
                  readers: dict[str, FileReaders]) -> Unchecked:
    """A run the controller configuration stops before it starts: a controller its manager
    refuses (a failure, with the findings as validate gives them), or no controller
    commanding a joint of the model (nothing to check)."""
    causes = [result.Cause("controller_refused", str(p)) for p in drives.refused]
    why = "" if causes else (f"no controller of {', '.join(drives.files)} commands a moving "
                             "joint of the robot")
    return Unchecked(options, label, [] if causes else list(drives.notes),
                     result.Coverage(why=why), readers, causes)


def _stability(robot: RobotModel, inertia: np.ndarray, ref: reference.Reference,
               used: dict[str, result.GainsUsed], plan: Plan) -> tuple[list[str], list[str]]:
    """(notes, reasons) of :func:`gains.stability` at poses along the reference."""
    poses = np.arange(0, len(ref.q), max(1, len(ref.q) // setup.SAMPLES))
    with np.errstate(divide="ignore", invalid="ignore"):
        rates = np.where(robot.damping > 0, robot.damping
                         / setup.effective_inertias(robot, inertia, ref.q[poses]), 0.0)
    return gains.stability(used, plan.dt, plan.delay, np.nan_to_num(rates, posinf=0.0),
                           ref.time[poses], plan.dynamics.substeps)


def _finder(robot: RobotModel, plant: Drive, effort_limit: np.ndarray
            ) -> Callable[[np.ndarray], counterbalance.Counterbalance]:
    """Gravity rows -> the counterbalance of the joints whose actuators cannot hold them."""
    units = tuple(robot.units(j) for j in robot.joints)
    return lambda gravity: counterbalance.find(robot.joints, units, gravity, plant.eff_j2a,
                                               effort_limit)


STILL = 0.005  # a joint moving less than this share of the default move is not moved


def _still(p: Prepared) -> tuple[str, ...]:
    """The checked joints the reference moves less than STILL of the default 25% -> 75%."""
    ranges = _ranges(p.robot)
    return tuple(j for v, j in enumerate(p.robot.joints) if j not in p.ctrl.direct
                 and np.ptp(p.ref.q[:, v]) < STILL * 0.5 * (ranges[v][1] - ranges[v][0]))


def simulate_one(options: Options, config: str | None, label: str | None = None,
                 progress: Progress | None = None) -> result.RunResult:
    """Simulate ``options.robot`` controlled through ``config`` (None: the robot's own)."""
    return complete(prepare(options, config, label), progress)


def complete(p: Prepared | Unchecked, progress: Progress | None = None) -> result.RunResult:
    """Run a prepared loop to its end and judge it."""
    if isinstance(p, Unchecked):
        return p.judged()
    started = time.perf_counter()
    steps = p.plan.steps
    state = loop.run(p.plan, (lambda done: progress(done, steps)) if progress else None)
    return finish(p, state, time.perf_counter() - started)


def finish(p: Prepared, state: RunState, loop_s: float) -> result.RunResult:
    """Metrics, reasons and notes of a prepared run whose loop has run (to ``state``)."""
    with np.errstate(all="ignore"):  # a diverged run may hold huge values
        series = _series(p.plan, state, p.robot, p.plant, p.ref, p.effort_limit, p.speed_limit)
        run = _judge(p, state, series)
    run.config = p.label
    run.reference = p.ref.source
    run.notes = _notes(p.robot, p.plant, p.ctrl, p.config is not None) + list(p.notes) \
        + p.reference_notes
    if p.plan.dynamics.note:
        run.notes.append(p.plan.dynamics.note)
    run.gains, run.tolerance = p.gains, p.settings.tolerance
    run.counterbalance = p.carried
    run.coverage = replace(coverage_of(p.robot, p.ctrl), still=_still(p))
    run.readers = p.readers
    run.controllers = p.controllers
    checks.judge(run, series, p.plant, p.ctrl, p.binding.S, p.config is not None,
                 p.plan.encoder, p.plan.delay)
    run.timings = {"setup_s": p.setup_s, "loop_s": loop_s,
                   "step_us": 1e6 * loop_s / max(state.done, 1)}
    if not p.options.keep_series:
        run.series = None
    return run


def _ranges(robot: RobotModel) -> list[tuple[float, float]]:
    return [reference.joint_range(k, lo, hi)
            for k, lo, hi in zip(robot.kinds, robot.lower, robot.upper, strict=True)]


def _default_reference(robot: RobotModel, s: Settings, limits: feasible.Limits,
                       dynamics: feasible.Dynamics, fixed: bool,
                       finder: Callable[[np.ndarray], counterbalance.Counterbalance] | None,
                       held: tuple[str, ...] = ()
                       ) -> tuple[reference.Reference, float, list[str], list[str],
                                  counterbalance.Counterbalance | None]:
    """The minimum-jerk motion, slowed (or, with a fixed duration, shrunk) to be feasible;
    the ``held`` joints stay at the middle of their range (a range of none to plan)."""
    ranges = [((lo + hi) / 2, (lo + hi) / 2) if joint in held else (lo, hi)
              for joint, (lo, hi) in zip(robot.joints, _ranges(robot), strict=True)]
    chosen = feasible.plan_motion(ranges, limits, dynamics, s.duration / 2, fixed, s.tolerance,
                                  finder)
    price(2 * chosen.move, s.dt, 2 * len(robot.joints), "the motion slowed to be feasible")
    ref = feasible.sample(ranges, chosen, s.dt)
    ref = reference.follow(ref, robot.joints, robot.followers)
    ref, notes = reference.saturate(ref, robot.joints, robot.lower, robot.upper,
                                    robot.velocity, s.dt)
    wide = [j for j, k, lo, hi in zip(robot.joints, robot.kinds, robot.lower, robot.upper,
                                       strict=True)
            if k != "continuous" and math.isfinite(hi - lo) and reference.limitless(lo, hi)]
    if wide:
        notes.insert(0, f"limits more than {reference.LIMITLESS:g} apart taken as none: "
                        + ", ".join(f"'{j}'" for j in wide)
                        + " move in a range of 2 near 0, as continuous joints do")
    return (ref, float(ref.time[-1]), list(chosen.notes) + notes, list(chosen.cannot_hold),
            chosen.carry)


def _held_note(held: tuple[str, ...], default: bool) -> str:
    where = "the middle of their range" if default else "the start of the trajectory"
    return (f"held at {where}: no controller commands them, so their drive keeps them where "
            "they are: " + ", ".join(f"'{j}'" for j in held))


def _table(options: Options, robot: RobotModel) -> reference.Table:
    assert options.trajectory is not None
    return reference.read_csv(options.trajectory, set(robot.joints))


def _start(robot: RobotModel, table: reference.Table | None) -> np.ndarray:
    """Where effort gains are turned into acceleration gains: the trajectory's first row
    (joints it leaves out at the middle of their range), or the middle of each range, around
    which the default motion moves."""
    ranges = _ranges(robot)
    hold = np.array([(lo + hi) / 2 for lo, hi in ranges])
    if table is None:
        return hold
    t = reference.step_times(0.0, 1.0)
    return reference.from_table(table, robot.joints, hold, t, "linear").q[0]


def _reference(options: Options, table: reference.Table, robot: RobotModel, s: Settings
               ) -> tuple[reference.Reference, float, list[str]]:
    """The reference from ``--trajectory``, saturated to the joint limits as the controller does."""
    ranges = _ranges(robot)
    duration = s.duration
    if options.duration is None and len(table.time) > 1:
        duration = table.end
    if duration / s.dt > MAX_STEPS:
        raise InputError(f"{options.trajectory}: more than {MAX_STEPS} steps at --dt {s.dt:g}")
    price(duration, s.dt, 2 * len(robot.joints), f"{options.trajectory}")
    hold = np.array([(lo + hi) / 2 for lo, hi in ranges])
    t = reference.step_times(duration, s.dt)
    ref = reference.from_table(table, robot.joints, hold, t, options.interpolation)
    given = {f: lead for f, lead in robot.followers.items() if f not in table.joints}
    ref = reference.follow(ref, robot.joints, given)
    ref, notes = reference.saturate(ref, robot.joints, robot.lower, robot.upper,
                                    robot.velocity, s.dt)
    return ref, duration, notes


def _series(plan: Plan, state: RunState, robot: RobotModel, plant: Drive,
            ref: reference.Reference, effort_limit: np.ndarray, speed_limit: np.ndarray
            ) -> result.Series:
    end = state.done if state.diverged_at is None else max(state.diverged_at - 1, 0)
    rows = state.rows[: end + 1]
    velocity = rows[:, plan.slots["v"]] @ plant.vel_j2a.T
    return result.Series(
        time=ref.time[: end + 1], joints=robot.joints,
        units=tuple(robot.units(j) for j in robot.joints), actuators=plant.actuators,
        transmission_of=plant.transmission_of, q_ref=ref.q[: end + 1],
        q=rows[:, plan.slots["x"]].copy(), effort_demand=rows[:end, plan.slots["ta"]].copy(),
        effort=rows[:end, plan.slots["sat"]].copy(), velocity=velocity,
        effort_limit=effort_limit, velocity_limit=speed_limit,
        lower=robot.lower, upper=robot.upper,
        joint_actuators={j: plant.actuators_of(j) for j in robot.joints},
    )


def _judge(p: Prepared, state: RunState, series: result.Series) -> result.RunResult:
    options, plan, binding, s, duration = p.options, p.plan, p.binding, p.settings, p.duration
    plant, ctrl = p.plant, p.ctrl
    joints = result.joint_stats(series)
    actuators = result.actuator_stats(series)
    reasons = [] if options.allow_saturation else list(p.cannot_hold)
    if state.diverged_at is not None:
        cause = setup.divergence_cause(plan, state, p.controller) if p.controller else ""
        reasons.append(f"the simulation diverged at t={state.diverged_at * s.dt:.3f} s: {cause}")
    reasons += p.unstable
    for name in binding.unbound:
        reasons.append(f"actuator '{name}' of the config is not an actuator of the robot")
    for name in binding.uncommanded:
        why = _skipped_cause(name, plant, ctrl)
        reasons.append(f"actuator '{name}' of the robot gets no command from the config{why}")
    for name in binding.unobserved:
        reasons.append(f"joint '{name}': the config cannot measure it")
    reasons += result.verdict_reasons(series, joints, actuators, s.tolerance,
                                      options.allow_saturation)
    if reasons and p.ref.saturated:
        names = ", ".join(f"'{j}'" for j in p.ref.saturated)
        reasons.insert(0, f"the reference exceeds the limits of joint {names} and was saturated "
                          "(see the notes): the failures may come from the reference, not the "
                          "config")
    return result.RunResult(
        robot=options.robot, config="", dt=s.dt, steps=plan.steps, duration=duration,
        reference="", joints=joints, actuators=actuators, reasons=reasons, notes=[],
        series=series,
    )


def _skipped_cause(actuator: str, plant: Drive, ctrl: Drive) -> str:
    """Why the config does not command ``actuator``, when the config left its transmission out."""
    name = plant.transmission_of[plant.actuators.index(actuator)]
    why = ctrl.skipped.get(name)
    return f" (its transmission '{name}' is not simulated in the config: {why})" if why else ""


def _notes(robot: RobotModel, plant: Drive, ctrl: Drive, candidate: bool) -> list[str]:
    notes = list(robot.notes) + plant.notes
    ros1 = [m.name for m in ctrl.maps if m.kind == "four_bar" and m.convention == "ros1"]
    if ros1:
        notes.append("the controller maps efforts of four-bar " + ", ".join(map(repr, ros1))
                     + " as ros_control does (ROS 1; not power-conserving, ros_control#523); "
                     "the plant is physics (--effort-convention ros2: ros2_control's map)")
    if candidate:
        notes += [f"config: {note}" for note in ctrl.notes]
    if plant.direct:
        notes.append("driven directly (no transmission in the robot, identity map): "
                     + ", ".join(plant.direct))
    if candidate and ctrl.direct and ctrl.direct != plant.direct:
        notes.append("no transmission in the config (identity assumed): " + ", ".join(ctrl.direct))
    if robot.mimic:
        notes.append("mimic joints follow their leaders: " + ", ".join(robot.mimic))
    for name, tags in plant.drake.items():
        ratio = tags.get("gear_ratio")
        if ratio is None or name not in plant.actuators:
            continue
        i = plant.actuators.index(name)
        reduction = float(np.abs(plant.vel_j2a[i]).max())
        if not math.isclose(ratio[0], reduction, rel_tol=1e-9):
            notes.append(f"actuator '{name}': drake:gear_ratio {ratio[0]:g} differs from the "
                         f"transmission's reduction {reduction:g} (the transmission is used)")
    return notes


def candidates(options: Options) -> list[tuple[str | None, str | None]]:
    """(config path, label) pairs: the robot's own config when none is given."""
    if not options.configs:
        return [(None, None)]
    labels = options.labels or options.configs
    return list(zip(options.configs, labels, strict=True))


EXIT_INCONCLUSIVE = 3


def exit_code(runs: list[result.RunResult]) -> int:
    """0 when every run passes, 1 when one fails, else 3: a run that checked nothing."""
    if any(run.failed for run in runs):
        return 1
    return EXIT_INCONCLUSIVE if any(run.coverage.nothing for run in runs) else 0
