"""One sample of a campaign: a candidate simulated on a perturbed robot, as a plain record.

:func:`run_sample` is a pure function of its :class:`Task` (robot, config, perturbation, seed):
it runs in this process (``--serial``) or in a Dask worker, and gives the same record to the
bit either way. Only the plant, standing in for the real hardware, is perturbed: a payload on
a link, viscous damping and Coulomb friction added to every joint, the rotor inertias scaled,
noise on the actuator position readings. The controller keeps the URDF's model and the
reference planned for it, and runs its gains scaled by ``gains``.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np
import pinocchio as pin

from txtool.io.xmlio import InputError
from txtool.simulation import loop, setup
from txtool.simulation.campaign_file import Payload
from txtool.simulation.model import RobotModel
from txtool.simulation.parameter_files import load_params
from txtool.simulation.plan import Controller, Plan
from txtool.simulation.run import Options, Prepared, Unchecked, finish, prepare
from txtool.simulation.sensing import Encoder, Reader, Sensing

Record = dict[str, Any]


@dataclass(frozen=True)
class Task:
    """Everything one sample needs; picklable, so that it can go to another machine."""

    options: Options
    config: str | None  # None: the robot's own config
    label: str
    sample: int  # its index: with ``seed``, the sensor noise's generator
    perturbation: dict[str, float]
    seed: int
    payload: Payload | None = None
    payload_where: str = ""  # ``path:line: bounds.payload.link`` for messages about the link


def run_sample(task: Task) -> Record:
    """The record of one sample: verdict, tracking margin, first reason; or an input error."""
    try:
        return _run(task)
    except InputError as exc:
        return {"sample": task.sample, "error": str(exc)}


def _run(task: Task) -> Record:
    prepared = prepare(task.options, task.config, task.label)
    record: Record = {"sample": task.sample, "perturbation": dict(task.perturbation)}
    if isinstance(prepared, Unchecked):
        return {**record, "verdict": "inconclusive", "margin": None, "joint": None,
                "max_error": None, "units": None, "reason": None}
    plan = perturbed_plan(prepared, task)
    started = time.perf_counter()
    state = loop.run(plan)
    run = finish(replace(prepared, plan=plan, controller=_scaled(prepared, task)), state,
                 time.perf_counter() - started)
    tolerance = run.tolerance
    assert tolerance is not None  # a simulated run is judged against its tolerance
    joint, worst = max(run.joints.items(), key=lambda item: item[1].max_error / tolerance)
    diverged = state.diverged_at is not None  # its errors say how far it ran away, no more
    return {**record, "verdict": run.verdict, "joint": joint, "units": worst.units,
            "margin": None if diverged else 1.0 - worst.max_error / tolerance,
            "max_error": None if diverged else worst.max_error,
            "reason": run.reasons[0] if run.reasons else None}


def _scaled(p: Prepared, task: Task) -> Controller:
    gains = p.controller
    assert gains is not None  # a prepared run always has its controller
    factor = task.perturbation.get("gains", 1.0)
    return replace(gains, kp=gains.kp * factor, kd=gains.kd * factor, ki=gains.ki * factor,
                   i_limit=gains.i_limit / factor)  # i_clamp bounds ki * integral


def perturbed_plan(p: Prepared, task: Task) -> Plan:
    """The prepared run's loop with the plant perturbed and the controller's model unchanged."""
    sample, options = task.perturbation, p.options
    params = load_params(options.params, options.robot)
    rotor = (setup.rotor_inertias(p.plant.actuators, params, p.plant, p.ctrl)
             * sample.get("rotor_inertia", 1.0),
             setup.rotor_inertias(p.ctrl.actuators, params, p.plant, p.ctrl))
    noise = sample.get("sensor_noise")
    counts = options.encoder_counts
    # A noisy reading needs the reading columns of the loop (counts 1 only lays them out).
    sensing = Sensing(options.delay, counts if noise is None else counts or 1)
    carried = p.plan.start_rows[:, p.plan.slots["cb"]].copy() if "cb" in p.plan.slots else None
    plan = setup.build_plan(plant_robot(p.robot, sample, task), p.plant, p.ctrl, p.binding,
                            rotor, p.effort_limit, _scaled(p, task), p.ref, p.settings.dt,
                            sensing, carried)
    # The controller's model: the URDF's (built from the same rotors).
    plan = replace(plan, ctrl=p.plan.ctrl)
    if noise is not None:
        assert plan.encoder is not None
        step = plan.encoder.step if counts else np.zeros_like(plan.encoder.step)
        generator = np.random.default_rng([task.seed, task.sample])
        plan = replace(plan, encoder=NoisyEncoder(
            counts or 0, step, plan.encoder.pos_j2a, plan.encoder.pos_j2a_c.copy(),
            plan.encoder.vel_j2a, generator.normal(0.0, noise, (plan.steps + 1, len(step))),
            exact_speeds=not counts))
    return plan


def plant_robot(robot: RobotModel, sample: dict[str, float], task: Task) -> RobotModel:
    """The robot as the plant sees it: payload on its link, more damping and friction."""
    model = pin.Model(robot.model)
    if task.payload is not None:  # its link is checked even where the mass is 0
        _add_payload(model, task.payload, sample.get("payload_mass", 0.0), task.payload_where)
    return replace(robot, model=model,
                   damping=robot.damping + sample.get("damping", 0.0),
                   friction=robot.friction + sample.get("friction", 0.0))


def _add_payload(model: pin.Model, payload: Payload, mass: float, where: str) -> None:
    if not model.existFrame(payload.link, pin.FrameType.BODY):
        raise InputError(f"{where}: no link '{payload.link}' in the robot")
    frame = model.frames[model.getFrameId(payload.link, pin.FrameType.BODY)]
    if frame.parentJoint == 0:
        raise InputError(f"{where}: link '{payload.link}' is fixed to the base; a payload "
                         "on it moves no joint")
    if mass == 0:
        return
    point = pin.Inertia(mass, np.array(payload.xyz), np.zeros((3, 3)))
    model.inertias[frame.parentJoint] = model.inertias[frame.parentJoint] \
        + frame.placement.act(point)


@dataclass(frozen=True)
class NoisyEncoder(Encoder):
    """Readings with noise: ``noise[k]`` (per actuator, in its own units) is added to the true
    actuator position before it is quantised (``step`` 0: not quantised). Speeds are finite
    differences of the readings with encoders (``--encoder-counts``), else exact, as the
    unperturbed run reads them."""

    noise: np.ndarray = field(default_factory=lambda: np.zeros((0, 0)))
    exact_speeds: bool = False

    def reader(self, rows: np.ndarray, position: slice, speed: slice, dt: float) -> Reader:
        # The plain reader adds ``pos_j2a_c`` (this encoder's own copy) to every reading when
        # it is called: step k's noise is folded into it just before.
        offset = self.pos_j2a_c
        base, noise, velocity = offset.copy(), self.noise, self.vel_j2a
        read = super().reader(rows, position, speed, dt)
        exact = self.exact_speeds

        def noisy(row: np.ndarray, x: np.ndarray, v: np.ndarray, k: int) -> None:
            np.add(base, noise[k], out=offset)
            read(row, x, v, k)
            if exact:
                np.dot(velocity, v, out=row[speed])

        return noisy
