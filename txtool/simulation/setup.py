"""From robot, drives, parameters and reference to the matrices of :class:`plan.Plan`."""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import pinocchio as pin

from txtool.mechanics.limits import actuator_limits as implied_limits
from txtool.simulation.drive import Drive
from txtool.simulation.feasible import Limits, Parts
from txtool.simulation.gains import condition, unstable
from txtool.simulation.loop import configurer, make_model
from txtool.simulation.model import RobotModel
from txtool.simulation.params import Params
from txtool.simulation.plan import Controller, Plan, RunState, layout
from txtool.simulation.plant import Dynamics, smallest_inertia, substeps_for
from txtool.simulation.reference import Reference
from txtool.simulation.sensing import Sensing, encoder

SAMPLES = 20  # reference poses where the plant's stiffness is measured
TINY_INERTIA = 1e-12


@dataclass(frozen=True)
class Binding:
    """How the candidate's actuators meet the robot's, by name."""

    S: np.ndarray  # (na_candidate, na_robot): 1 where the names agree
    unbound: tuple[str, ...]  # candidate actuators the robot does not have
    uncommanded: tuple[str, ...]  # robot actuators the candidate never commands
    unobserved: tuple[str, ...]  # joints whose estimate needs an unbound actuator


def bind(plant: Drive, ctrl: Drive) -> Binding:
    index = {name: i for i, name in enumerate(plant.actuators)}
    S = np.zeros((ctrl.na, plant.na))
    for c, name in enumerate(ctrl.actuators):
        if name in index:
            S[c, index[name]] = 1.0
    unbound = tuple(a for a in ctrl.actuators if a not in index)
    uncommanded = tuple(a for a in plant.actuators if a not in ctrl.actuators)
    missing = [ctrl.actuators.index(a) for a in unbound]
    unobserved = tuple(
        j for v, j in enumerate(plant.joints)
        if missing and np.any(ctrl.pos_a2j[v, missing] != 0)
    )
    return Binding(S, unbound, uncommanded, unobserved)


def rotor_inertias(names: tuple[str, ...], params: Params, *drives: Drive) -> np.ndarray:
    """Per actuator: the params file, else a drake:rotor_inertia tag (robot first), else 0."""
    values = []
    for name in names:
        given = params.actuators.get(name)
        value = given.rotor_inertia if given is not None else None
        for drive in drives:
            if value is None and "rotor_inertia" in drive.drake.get(name, {}):
                value = drive.drake[name]["rotor_inertia"][0]
        values.append(value or 0.0)
    return np.array(values, dtype=float)


def actuator_limits(robot: RobotModel, plant: Drive, params: Params
                    ) -> tuple[np.ndarray, np.ndarray]:
    """Effort and speed limits per robot actuator: given, else implied by the joint limits.

    The implied limits are :func:`txtool.mechanics.limits.actuator_limits`: the worst case over
    the box of URDF joint limits (``effort / |n|`` and ``velocity * |n|`` for a simple
    transmission). A direct actuator takes its joint's limits; no (or zero) limit means none.
    """
    effort = np.full(plant.na, math.inf)
    speed = np.full(plant.na, math.inf)
    for columns, rows, tmap in plant.blocks:
        if tmap is None:
            effort[rows] = robot.effort[columns]
            speed[rows] = robot.velocity[columns]
            continue
        for i, limit in zip(rows, implied_limits(tmap, robot.info), strict=True):
            effort[i] = limit.effort or math.inf
            speed[i] = limit.velocity or math.inf
    for i, name in enumerate(plant.actuators):
        given = params.actuators.get(name)
        if given is not None and given.effort_limit is not None:
            effort[i] = given.effort_limit
        if given is not None and given.velocity_limit is not None:
            speed[i] = given.velocity_limit
    return effort, speed


def controller(robot: RobotModel, params: Params, bandwidth: float) -> Controller:
    """Gains from the params file, else critically damped at ``bandwidth`` (kp=w^2, kd=2w)."""
    n = robot.nv
    kp, kd = np.full(n, bandwidth**2), np.full(n, 2 * bandwidth)
    ki, limit = np.zeros(n), np.full(n, math.inf)
    for v, joint in enumerate(robot.joints):
        gains = params.joints.get(joint)
        if gains is None:
            continue
        kp[v] = gains.kp if gains.kp is not None else kp[v]
        kd[v] = gains.kd if gains.kd is not None else kd[v]
        ki[v] = gains.ki or 0.0
        if gains.i_clamp is not None and ki[v] > 0:
            limit[v] = gains.i_clamp / ki[v]
    return Controller(kp, kd, ki, limit, robot.damping.copy(), robot.friction.copy())


def build_plan(robot: RobotModel, plant: Drive, ctrl: Drive, binding: Binding,
               rotor: tuple[np.ndarray, np.ndarray], limit: np.ndarray, gains: Controller,
               ref: Reference, dt: float, sensing: Sensing | None = None,
               carried: np.ndarray | None = None) -> Plan:
    """``rotor`` = (per robot actuator, per candidate actuator) rotor inertias; ``carried``:
    per step, joint torques of an undescribed counterbalance (plant and controller know them)."""
    nv, na = robot.nv, plant.na
    sensing = sensing or Sensing(delay=False)
    unobserved = [robot.joints.index(j) for j in binding.unobserved]
    friction_ff = bool(np.any(gains.friction))
    s = layout(nv, na, unobserved=bool(unobserved), friction_ff=friction_ff,
               encoder=sensing.counts is not None, carried=carried is not None)
    width = max(slot.stop for slot in s.values())
    steps = len(ref.time) - 1
    rows = _rows(s, width, ref, gains)
    if carried is not None:
        rows[:, s["cb"]] = carried
    E = _estimates(s, width, nv, plant, ctrl, binding.S, unobserved)
    F = np.zeros((nv, width))
    F[:, s["ff"]] = np.eye(nv)
    F -= gains.kp[:, None] * E[:nv] + gains.kd[:, None] * E[nv:]
    C = binding.S.T @ ctrl.eff_j2a
    ctrl_model, ctrl_block = make_model(robot, ctrl.reflected_inertia(rotor[1]))
    dynamics = plant_dynamics(robot, plant.reflected_inertia(rotor[0]), ref, dt)
    bias_rows = np.diag(gains.damping) @ E[nv:]
    if ctrl_block is not None:
        bias_rows = bias_rows + ctrl_block @ F
    if friction_ff:
        bias_rows[:, s["fric"]] += np.eye(nv)
    if carried is not None:  # the controller leaves the carried torque to the counterbalance
        bias_rows[:, s["cb"]] -= np.eye(nv)
    bias = bool(np.any(bias_rows))
    H = np.vstack([E, F, C @ bias_rows] if bias else [E, F])
    use_ki = bool(np.any(gains.ki))
    general = use_ki or robot.has_continuous or sensing.counts is not None \
        or not dynamics.simple  # the loops of loop.py: only the fast one has PD damping
    PD = np.zeros((nv, width))
    PD[:, s["sat"]] = plant.eff_a2j
    if carried is not None:
        PD[:, s["cb"]] = np.eye(nv)
    if not general:  # the fast loop: damping explicit in PD, implicit through the armature
        PD[:, s["v"]] = -np.diag(robot.damping)
    return Plan(
        robot=robot, dt=dt, steps=steps, start_rows=rows, slots=s, H=H, C=C, PD=PD,
        Phi=_euler(s, width, nv, dt), limit=limit, plant=dynamics.model, ctrl=ctrl_model,
        plant_block=dynamics.block, ctrl_block=ctrl_block, dynamics=dynamics, bias=bias,
        q_ref=ref.q, ki=gains.ki if use_ki else None, i_limit=gains.i_limit if use_ki else None,
        delay=sensing.delay, encoder=encoder(sensing.counts, plant, robot),
    )


def plant_dynamics(robot: RobotModel, inertia: np.ndarray, ref: Reference, dt: float
                   ) -> Dynamics:
    """The plant's integrator: rotor inertia, implicit damping, friction, sub-steps."""
    model, block = make_model(robot, inertia)
    if block is None and robot.mimic:
        block = np.zeros((robot.nv, robot.nv))  # aba does not take mimic joints: crba + solve
    samples = ref.q[:: max(1, len(ref.q) // SAMPLES)]
    smallest = smallest_inertia(model, robot.config(samples))
    substeps, stiffest = substeps_for(dt, robot.damping, smallest)
    model.armature = model.armature + (dt / substeps) * robot.damping
    friction = robot.friction.copy() if np.any(robot.friction) else None
    config = configurer(robot) if robot.has_continuous else None
    dynamics = Dynamics(model, model.createData(), dt, substeps, robot.damping.copy(), friction,
                        block, config, robot.model.nq)
    if substeps > 1 and stiffest is not None:
        rate = robot.damping[stiffest] / smallest[stiffest]
        dynamics.note = (f"plant: {substeps} sub-steps per control step (joint "
                         f"'{robot.joints[stiffest]}': damping / inertia = {rate:.4g} 1/s)")
    return dynamics


def _rows(s: dict[str, slice], width: int, ref: Reference, gains: Controller) -> np.ndarray:
    rows = np.zeros((len(ref.time), width))
    rows[0, s["x"]] = ref.q[0]
    rows[0, s["v"]] = ref.qd[0]
    rows[:, s["one"]] = 1.0
    rows[:, s["ff"]] = ref.qdd + gains.kp * ref.q + gains.kd * ref.qd
    if "qref" in s:
        rows[:, s["qref"]] = ref.q
        rows[:, s["vref"]] = ref.qd
    if "fric" in s:
        rows[:, s["fric"]] = gains.friction * np.sign(ref.qd)
    return rows


def _estimates(s: dict[str, slice], width: int, nv: int, plant: Drive, ctrl: Drive,
               S: np.ndarray, unobserved: list[int]) -> np.ndarray:
    """Rows mapping a history row to the controller's [position; velocity] estimates."""
    E = np.zeros((2 * nv, width))
    if "enc" in s:  # from the encoder readings (sensing.py) rather than the plant's state
        E[:nv, s["enc"]] = ctrl.pos_a2j @ S
        E[:nv, s["one"]] = ctrl.pos_a2j_c[:, None]
        E[nv:, s["encv"]] = ctrl.vel_a2j @ S
    else:
        E[:nv, s["x"]] = ctrl.pos_a2j @ S @ plant.pos_j2a
        E[:nv, s["one"]] = (ctrl.pos_a2j @ S @ plant.pos_j2a_c + ctrl.pos_a2j_c)[:, None]
        E[nv:, s["v"]] = ctrl.vel_a2j @ S @ plant.vel_j2a
    for v in unobserved:
        E[v, :] = 0.0
        E[nv + v, :] = 0.0
        E[v, s["qref"].start + v] = 1.0
        E[nv + v, s["vref"].start + v] = 1.0
    return E


def _euler(s: dict[str, slice], width: int, nv: int, dt: float) -> np.ndarray:
    """Semi-implicit Euler: v' = v + dt a, x' = x + dt v' (unwrapped angles for continuous)."""
    eye = np.eye(nv)
    phi = np.zeros((2 * nv, width))
    phi[:nv, s["x"]] = eye
    phi[:nv, s["v"]] = dt * eye
    phi[:nv, s["a"]] = dt * dt * eye
    phi[nv:, s["v"]] = eye
    phi[nv:, s["a"]] = dt * eye
    return phi


def reference_dynamics(robot: RobotModel, inertia: np.ndarray
                       ) -> Callable[[np.ndarray, np.ndarray, np.ndarray], Parts]:
    """The plant's joint torques along reference rows, split as :mod:`feasible` needs them."""
    model, block = make_model(robot, inertia)
    data = model.createData()

    def parts(x: np.ndarray, xd: np.ndarray, xdd: np.ndarray) -> Parts:
        zero = np.zeros(robot.nv)
        gravity, quadratic = np.zeros_like(x), np.zeros_like(x)
        for k, q in enumerate(robot.config(x)):
            gravity[k] = pin.rnea(model, data, q, zero, zero)
            quadratic[k] = pin.rnea(model, data, q, xd[k], xdd[k]) - gravity[k]
        if block is not None:
            quadratic += xdd @ block.T
        static = gravity + robot.friction * np.sign(xd)
        return quadratic, robot.damping * xd, static

    return parts


def effective_inertias(robot: RobotModel, inertia: np.ndarray, x: np.ndarray) -> np.ndarray:
    """Rows of each DoF's effective inertia ``1 / (M^-1)_jj`` (rotor ``inertia`` included)."""
    model, block = make_model(robot, inertia)
    data = model.createData()
    lower = np.tril_indices(robot.nv, -1)
    rows = np.empty_like(x)
    for k, q in enumerate(robot.config(x)):
        mass = pin.crba(model, data, q).copy()
        mass[lower] = mass.T[lower]
        if block is not None:
            mass += block
        with np.errstate(divide="ignore"):
            rows[k] = 1.0 / np.diag(np.linalg.pinv(mass))
    return rows


def gravity_along(robot: RobotModel, x: np.ndarray) -> np.ndarray:
    """Rows of the gravity torque ``g(q)`` at the coordinates ``x`` (rows)."""
    model = robot.model
    data = model.createData()
    gravity = np.empty_like(x)
    for k, q in enumerate(robot.config(x)):
        gravity[k] = pin.computeGeneralizedGravity(model, data, q)
    return gravity


def motion_limits(robot: RobotModel, plant: Drive, inertia: np.ndarray, gains: Controller,
                  effort: np.ndarray, speed: np.ndarray, dt: float, delay: bool) -> Limits:
    """What the default motion must respect; ``inertia``: the plant's reflected rotor inertia."""
    model, block = make_model(robot, inertia)
    data = model.createData()
    lower = np.tril_indices(robot.nv, -1)

    def inverse_mass(x: np.ndarray) -> np.ndarray:
        inverses = np.empty((len(x), robot.nv, robot.nv))
        for k, q in enumerate(robot.config(x)):
            mass = pin.crba(model, data, q).copy()
            mass[lower] = mass.T[lower]
            if block is not None:
                mass += block
            inverses[k] = np.linalg.pinv(mass)
        return inverses

    return Limits(robot.joints, robot.velocity, plant.vel_j2a, plant.eff_j2a, plant.actuators,
                  speed, effort, dt, delay, gains.kp, gains.kd, robot.damping,
                  inverse_mass)


def divergence_cause(plan: Plan, state: RunState, gains: Controller) -> str:
    """Which joint ran away first and the likeliest reason, from the last finite rows."""
    end = max((state.diverged_at or 0) - 1, 0)
    start = max(end - 20, 0)
    x = state.rows[start : end + 1, plan.slots["x"]]
    error = np.abs(x - plan.q_ref[start : end + 1])
    growth = np.nan_to_num(error[-1] - error[0], nan=np.inf, posinf=np.inf)
    v = int(np.argmax(growth))
    joint = plan.robot.joints[v]
    dt, kp, kd = plan.dt, float(gains.kp[v]), float(gains.kd[v])
    if unstable(kp, kd, dt, plan.delay):
        return (f"joint '{joint}' ran away first; its gains are too high for --dt {dt:g} "
                f"(kp·dt² {kp * dt * dt:.3g}, kd·dt {kd * dt:.3g}; {condition(plan.delay)})")
    mass = smallest_inertia(plan.dynamics.model, plan.robot.config(plan.q_ref[[0, end]]))[v]
    if mass < TINY_INERTIA:
        return (f"joint '{joint}' ran away first; its inertia is {mass:.3g} (links without "
                "mass or inertia and no rotor inertia)")
    return (f"joint '{joint}' ran away first (an unstable loop: the config's maps reverse or "
            "amplify its feedback)")
