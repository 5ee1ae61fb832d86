"""One simulate run per candidate config: load, build, run the loop, judge."""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from txtool.io.load import load
from txtool.io.xmlio import InputError, XacroOptions
from txtool.simulate import gains, loop, reference, result, setup
from txtool.simulate.drive import Drive, read_drive
from txtool.simulate.model import RobotModel, build
from txtool.simulate.params import Params, load_params

DEFAULTS = {"bandwidth": 20.0, "duration": 5.0, "dt": 0.001, "tolerance": 0.01}
MAX_STEPS = 20_000_000

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
    convention: str = "ros2"
    xacro: XacroOptions = field(default_factory=XacroOptions)
    jobs: int = 1
    keep_series: bool = True


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
        values[key] = float(value)
    if values["dt"] > values["duration"]:
        raise InputError(f"--dt: {values['dt']:g} s is longer than the run "
                         f"({values['duration']:g} s)")
    if values["duration"] / values["dt"] > MAX_STEPS:
        raise InputError(f"--duration/--dt: more than {MAX_STEPS} steps")
    return Settings(**values)


@dataclass
class Prepared:
    """Everything a run needs, built: the loop's :class:`loop.Plan` and what judges it."""

    options: Options
    config: str | None
    label: str
    robot: RobotModel
    plant: Drive
    ctrl: Drive
    binding: setup.Binding
    plan: loop.Plan
    ref: reference.Reference
    settings: Settings
    duration: float
    effort_limit: np.ndarray
    speed_limit: np.ndarray
    setup_s: float
    gains: dict[str, result.GainsUsed] = field(default_factory=dict)
    notes: tuple[str, ...] = ()


def prepare(options: Options, config: str | None, label: str | None = None) -> Prepared:
    """Load ROBOT and the config, build the model, parameters, reference and loop matrices."""
    started = time.perf_counter()
    source = load(options.robot, xacro=options.xacro)
    robot = build(source)
    plant = read_drive(source, robot, loader=options.loader, convention="ros2")
    if config is not None:
        ctrl = read_drive(load(config, xacro=options.xacro), robot, loader=options.loader,
                          convention=options.convention)
    elif options.convention == "loader":
        ctrl = read_drive(source, robot, loader=options.loader, convention="loader")
    else:
        ctrl = plant
    params = load_params(options.params, options.robot)
    params.check_names(set(plant.actuators) | set(ctrl.actuators), set(robot.joints),
                       options.robot)
    run_settings = settings(options, params)
    ref, duration = _reference(options, robot, run_settings)
    binding = setup.bind(plant, ctrl)
    rotor = (setup.rotor_inertias(plant.actuators, params, plant, ctrl),
             setup.rotor_inertias(ctrl.actuators, params, plant, ctrl))
    effort_limit, speed_limit = setup.actuator_limits(robot, plant, params)
    params, inertia = gains.in_acceleration(params, robot, plant, rotor[0], ref.q[0])
    controller = setup.controller(robot, params, run_settings.bandwidth)
    plan = setup.build_plan(robot, plant, ctrl, binding, rotor, effort_limit, controller, ref,
                            run_settings.dt)
    used, stiff = gains.used(robot, params, controller, run_settings.bandwidth, inertia,
                             run_settings.dt)
    return Prepared(options, config, label or (config if config is not None else options.robot),
                    robot, plant, ctrl, binding, plan, ref, run_settings, duration, effort_limit,
                    speed_limit, time.perf_counter() - started, used, params.notes + tuple(stiff))


def simulate_one(options: Options, config: str | None, label: str | None = None,
                 progress: Progress | None = None) -> result.RunResult:
    """Simulate ``options.robot`` controlled through ``config`` (None: the robot's own)."""
    return complete(prepare(options, config, label), progress)


def complete(p: Prepared, progress: Progress | None = None) -> result.RunResult:
    """Run a prepared loop to its end and judge it."""
    started = time.perf_counter()
    steps = p.plan.steps
    loop.run(p.plan, (lambda done: progress(done, steps)) if progress else None)
    return finish(p, time.perf_counter() - started)


def finish(p: Prepared, loop_s: float) -> result.RunResult:
    """Metrics, reasons and notes of a prepared run whose loop has run."""
    with np.errstate(all="ignore"):  # a diverged run may hold huge values
        series = _series(p.plan, p.robot, p.plant, p.ref, p.effort_limit, p.speed_limit)
        run = _judge(p.options, series, p.plan, p.binding, p.settings, p.duration)
    run.config = p.label
    run.reference = p.ref.source
    run.notes = _notes(p.robot, p.plant, p.ctrl, p.config is not None) + list(p.notes)
    run.gains, run.tolerance = p.gains, p.settings.tolerance
    run.timings = {"setup_s": p.setup_s, "loop_s": loop_s,
                   "step_us": 1e6 * loop_s / max(p.plan.done, 1)}
    if not p.options.keep_series:
        run.series = None
    return run


def _reference(options: Options, robot: RobotModel, s: Settings
               ) -> tuple[reference.Reference, float]:
    ranges = [reference.joint_range(k, lo, hi)
              for k, lo, hi in zip(robot.kinds, robot.lower, robot.upper, strict=True)]
    if options.trajectory is None:
        return reference.default_motion(ranges, s.duration, s.dt), s.duration
    table = reference.read_csv(options.trajectory, set(robot.joints))
    duration = s.duration
    if options.duration is None and len(table.time) > 1:
        duration = table.end
    if duration / s.dt > MAX_STEPS:
        raise InputError(f"{options.trajectory}: more than {MAX_STEPS} steps at --dt {s.dt:g}")
    hold = np.array([(lo + hi) / 2 for lo, hi in ranges])
    t = reference.step_times(duration, s.dt)
    return reference.from_table(table, robot.joints, hold, t, options.interpolation), duration


def _series(plan: loop.Plan, robot: RobotModel, plant: Drive, ref: reference.Reference,
            effort_limit: np.ndarray, speed_limit: np.ndarray) -> result.Series:
    end = plan.done if plan.diverged_at is None else max(plan.diverged_at - 1, 0)
    rows = plan.rows[: end + 1]
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


def _judge(options: Options, series: result.Series, plan: loop.Plan, binding: setup.Binding,
           s: Settings, duration: float) -> result.RunResult:
    joints = result.joint_stats(series)
    actuators = result.actuator_stats(series)
    reasons = []
    if plan.diverged_at is not None:
        reasons.append(f"the simulation diverged at t={plan.diverged_at * s.dt:.3f} s "
                       "(a singular mass matrix or an unstable loop)")
    for name in binding.unbound:
        reasons.append(f"actuator '{name}' of the config is not an actuator of the robot")
    for name in binding.uncommanded:
        reasons.append(f"actuator '{name}' of the robot gets no command from the config")
    for name in binding.unobserved:
        reasons.append(f"joint '{name}': the config cannot measure it")
    reasons += result.verdict_reasons(series, joints, actuators, s.tolerance,
                                      options.allow_saturation)
    return result.RunResult(
        robot=options.robot, config="", dt=s.dt, steps=plan.steps, duration=duration,
        reference="", joints=joints, actuators=actuators, reasons=reasons, notes=[],
        series=series,
    )


def _notes(robot: RobotModel, plant: Drive, ctrl: Drive, candidate: bool) -> list[str]:
    notes = []
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


def exit_code(runs: list[result.RunResult]) -> int:
    return 0 if all(run.passed for run in runs) else 1
