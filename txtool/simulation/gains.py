"""The gains a run uses: effort gains turned into acceleration gains, and where each came from.

simulate's law is ``tau = M(q) (qdd_ref + kp e + kd e_dot + ki int(e)) + ...``, so its gains
are accelerations per error. A controller whose PID output is the joint effort (an effort
joint_trajectory_controller, pid_controller or JointPositionController) has gains in N·m/rad
(N/m). Divided by the joint's inertia ``M_ii`` (reflected rotor inertia included) at the start
of the reference, they give the joint the same stiffness and damping around that pose.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pinocchio as pin

from txtool.simulation.drive import Drive
from txtool.simulation.model import RobotModel
from txtool.simulation.params import JointGains, Params
from txtool.simulation.plan import Controller
from txtool.simulation.result import GainsUsed


def joint_inertia(robot: RobotModel, plant: Drive, rotor: np.ndarray, x0: np.ndarray
                  ) -> np.ndarray:
    """Diagonal of the plant's joint-space inertia at ``x0``, rotor inertia included."""
    data = robot.model.createData()
    mass = pin.crba(robot.model, data, robot.config(x0))
    return np.diag(mass) + np.diag(plant.reflected_inertia(rotor))


def in_acceleration(params: Params, robot: RobotModel, plant: Drive, rotor: np.ndarray,
                    x0: np.ndarray) -> tuple[Params, dict[str, float]]:
    """``params`` with effort gains divided by M_ii; (params, M_ii per converted joint)."""
    effort = {j: g for j, g in params.joints.items() if g.per == "effort"}
    if not effort:
        return params, {}
    diagonal = joint_inertia(robot, plant, rotor, x0)
    joints = dict(params.joints)
    used: dict[str, float] = {}
    for name, gains in effort.items():
        m = float(diagonal[robot.joints.index(name)])
        used[name] = m
        joints[name] = JointGains(
            kp=_over(gains.kp, m), kd=_over(gains.kd, m), ki=_over(gains.ki, m),
            i_clamp=_over(gains.i_clamp, m), per="acceleration", source=gains.source)
    return replace(params, joints=joints), used


def _over(value: float | None, m: float) -> float | None:
    return None if value is None else value / m


def used(robot: RobotModel, params: Params, ctrl: Controller, bandwidth: float,
         inertia: dict[str, float]) -> dict[str, GainsUsed]:
    """Per joint: the gains the controller runs with, their source, the M_ii used (if any)."""
    table = {}
    for v, joint in enumerate(robot.joints):
        given = params.joints.get(joint)
        ki = float(ctrl.ki[v])
        bound = float(ctrl.i_limit[v]) * ki if ki > 0 and np.isfinite(ctrl.i_limit[v]) else None
        table[joint] = GainsUsed(
            kp=float(ctrl.kp[v]), kd=float(ctrl.kd[v]), ki=ki, i_clamp=bound,
            units=robot.units(joint), source=given.source if given is not None else None,
            bandwidth=bandwidth if given is None or None in (given.kp, given.kd) else None,
            inertia=inertia.get(joint))
    return table


def unstable(kp: float, kd: float, dt: float, delay: bool) -> bool:
    """Whether the exact-model error loop is unstable at step ``dt`` (Jury's test).

    The error obeys ``e'' = -kp e - kd e'``, stepped by semi-implicit Euler. Without delay its
    characteristic polynomial is ``z^2 - (2 - a - b) z + (1 - b)`` (``a = kp dt^2``,
    ``b = kd dt``): stable only when ``b < 2`` and ``a + 2b < 4``. With the command acting one
    period late it is ``z^3 - 2 z^2 + (1 + a + b) z - b``: stable only when ``b < 1`` and
    ``a < b (1 - b)``, a far smaller region (at most ``a < 1/4``). A model error only shrinks
    it further, so gains outside it cannot track.
    """
    a, b = kp * dt * dt, kd * dt
    if delay:
        return b >= 1 or a >= b * (1 - b)
    return b >= 2 or a + 2 * b >= 4


def condition(delay: bool) -> str:
    if delay:
        return "with the one-period delay it needs kd·dt < 1 and kp·dt² < kd·dt·(1 - kd·dt)"
    return "it needs kd·dt < 2 and kp·dt² + 2·kd·dt < 4"


def radius(kp: float, kd: float, dt: float, delay: bool, rate: float = 0.0,
           substeps: int = 1) -> float:
    """Spectral radius of one joint's sampled error loop as simulate runs it (< 1: stable).

    ``rate`` is the joint's viscous damping over its inertia (1/s). The plant steps
    ``v' = (v + h u) / (1 + h rate)``, ``x' = x + h v'`` (implicit damping, ``substeps`` of
    ``h``) with the command ``u`` held; the controller commands ``u = -kp x - kd v + rate v``
    (computed torque with the damping compensated from its reading), one period late with
    ``delay``. With ``rate = 0`` this is the region of :func:`unstable`.
    """
    h = dt / substeps
    step = np.eye(3)
    sub = np.array([[1.0, h / (1 + h * rate), h * h / (1 + h * rate)],
                    [0.0, 1 / (1 + h * rate), h / (1 + h * rate)],
                    [0.0, 0.0, 1.0]])
    for _ in range(substeps):
        step = sub @ step
    law = np.array([-kp, rate - kd])
    if delay:
        loop = np.vstack([step[:2], [law[0], law[1], 0.0]])
    else:
        loop = step[:2, :2] + np.outer(step[:2, 2], law)
    return float(np.abs(np.linalg.eigvals(loop)).max())


def stability(table: dict[str, GainsUsed], dt: float, delay: bool, rates: np.ndarray,
              times: np.ndarray, substeps: int = 1) -> tuple[list[str], list[str]]:
    """(notes, reasons) on joints whose gains the loop's step and delay make unstable.

    ``rates``: (poses, nv) damping over effective inertia at poses of the reference, reached
    at ``times``. A joint outside the undamped region (:func:`unstable`) whose damping keeps
    every pose's loop stable gets a note saying so; one unstable at some pose fails the run,
    however short: its error grows there whether or not the run lasts long enough to show it.
    """
    failing, damped, reasons = [], [], []
    for v, (name, g) in enumerate(table.items()):
        if not unstable(g.kp, g.kd, dt, delay):
            continue
        gains = f"kp·dt² {g.kp * dt * dt:.3g}, kd·dt {g.kd * dt:.3g}"
        worst = [radius(g.kp, g.kd, dt, delay, float(r), substeps) for r in rates[:, v]]
        k = int(np.argmax(worst))
        if worst[k] >= 1.0:
            failing.append(f"{name} ({gains})")
            where = f" at the pose of t={times[k]:.3f} s" if rates[:, v].any() else ""
            reasons.append(f"joint '{name}': gains too stiff for --dt {dt:g} s: the sampled "
                           f"loop is unstable, its error grows x{worst[k]:.4g} per step{where} "
                           f"({gains}; {condition(delay)})")
        else:
            damped.append(f"{name} ({gains}; x{worst[k]:.4g} per step at worst, with "
                          f"damping / inertia {rates[:, v].min():.4g}-{rates[:, v].max():.4g} "
                          "1/s)")
    notes = []
    if failing:
        notes.append(f"gains too stiff for --dt {dt:g} s, the loop cannot be stable "
                     f"({condition(delay)}): " + ", ".join(failing))
    if damped:
        notes.append(f"gains beyond the stable region of an undamped joint at --dt {dt:g} s "
                     f"({condition(delay)}); the URDF damping keeps the sampled loop stable, "
                     "so less real damping would make it oscillate: " + ", ".join(damped))
    return notes, reasons
