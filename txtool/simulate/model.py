"""The rigid-body model: Pinocchio built from the URDF text after xacro, fixed base.

Joint coordinates ``x`` are one number per velocity DoF (the unwrapped angle for continuous
joints); :meth:`RobotModel.config` turns them into Pinocchio's configuration (``cos, sin`` for
continuous joints), which is what ``pin.integrate`` produces for them. Mimic joints follow their
leader inside Pinocchio (``mimic=True``); they have no DoF of their own and no transmission.
"""

from __future__ import annotations

import contextlib
import math
import os
import sys
import tempfile
from collections.abc import Iterator
from dataclasses import dataclass

import numpy as np
import pinocchio as pin

from txtool.io.xmlio import InputError, Source, serialize
from txtool.model.robot import JointInfo, robot_joints

MOVING = ("revolute", "continuous", "prismatic")


@dataclass
class RobotModel:
    path: str
    model: pin.Model
    joints: tuple[str, ...]  # DoF order (= Pinocchio's velocity order)
    kinds: tuple[str, ...]  # revolute | continuous | prismatic
    info: dict[str, JointInfo]
    lower: np.ndarray  # position limits, -inf/+inf where none
    upper: np.ndarray
    effort: np.ndarray  # URDF joint effort limits, inf where none
    velocity: np.ndarray
    damping: np.ndarray
    friction: np.ndarray
    mimic: tuple[str, ...]

    @property
    def nv(self) -> int:
        return int(self.model.nv)

    @property
    def has_continuous(self) -> bool:
        return "continuous" in self.kinds

    def units(self, joint: str) -> str:
        return "m" if self.kinds[self.joints.index(joint)] == "prismatic" else "rad"

    def config_indices(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """(plain q idx, plain v idx, continuous cos q idx, continuous v idx)."""
        plain_q, plain_v, cos_q, cont_v = [], [], [], []
        for v, name in enumerate(self.joints):
            joint = self.model.joints[self.model.getJointId(name)]
            if self.kinds[v] == "continuous":
                cos_q.append(joint.idx_q)
                cont_v.append(v)
            else:
                plain_q.append(joint.idx_q)
                plain_v.append(v)
        return tuple(np.array(i, dtype=int) for i in (plain_q, plain_v, cos_q, cont_v))  # type: ignore[return-value]

    def config(self, x: np.ndarray) -> np.ndarray:
        """Pinocchio configuration(s) for coordinates ``x`` of shape (..., nv)."""
        plain_q, plain_v, cos_q, cont_v = self.config_indices()
        q = np.zeros((*x.shape[:-1], self.model.nq))
        q[..., plain_q] = x[..., plain_v]
        q[..., cos_q] = np.cos(x[..., cont_v])
        q[..., cos_q + 1] = np.sin(x[..., cont_v])
        return q


def build(source: Source) -> RobotModel:
    """The model of ``source`` (its xacro expansion for .xacro files)."""
    info = robot_joints(source.root)
    for name, joint in info.items():
        if joint.type in ("floating", "planar"):
            raise InputError(f"{source.path}:{joint.line}: joint '{name}' is {joint.type}; "
                             "simulate supports fixed-base robots with 1-DoF joints")
    mimic = tuple(n for n, j in info.items() if j.mimic is not None and j.type in MOVING)
    text = serialize(source.tree).decode("utf-8")
    with captured_stderr() as said:
        try:
            model = pin.buildModelFromXML(text, bool(mimic))
        except (RuntimeError, ValueError) as exc:
            model = None
            error = str(exc).strip().splitlines()[0] if str(exc).strip() else type(exc).__name__
    if model is None:
        detail = next((line.removeprefix("Error:").strip() for line in said
                       if line.startswith("Error:")), error)
        raise InputError(f"{source.path}: pinocchio cannot build the model: {detail}")
    joints: list[str] = []
    for name, joint in zip(model.names[1:], model.joints[1:], strict=True):
        if joint.nv == 0:
            continue  # a mimic joint
        joints.append(name)
    if not joints:
        raise InputError(f"{source.path}: the robot has no moving joints")
    order = sorted(joints, key=lambda n: model.joints[model.getJointId(n)].idx_v)
    return _robot_model(source.path, model, tuple(order), info, mimic)


@contextlib.contextmanager
def captured_stderr() -> Iterator[list[str]]:
    """Collect what C++ code writes to file descriptor 2 (urdfdom's console logging)."""
    lines: list[str] = []
    sys.stderr.flush()
    saved = os.dup(2)
    with tempfile.TemporaryFile(mode="w+b") as sink:
        os.dup2(sink.fileno(), 2)
        try:
            yield lines
        finally:
            os.dup2(saved, 2)
            os.close(saved)
            sink.seek(0)
            lines.extend(sink.read().decode("utf-8", "replace").splitlines())


def _robot_model(path: str, model: pin.Model, joints: tuple[str, ...],
                 info: dict[str, JointInfo], mimic: tuple[str, ...]) -> RobotModel:
    kinds, lower, upper, effort, velocity, damping, friction = [], [], [], [], [], [], []
    for name in joints:
        joint = info.get(name)
        if joint is None or joint.type not in MOVING:
            raise InputError(f"{path}: joint '{name}' is not a revolute, continuous or "
                             "prismatic URDF joint")
        kinds.append(joint.type)
        bounded = joint.type != "continuous" and joint.lower is not None \
            and joint.upper is not None and joint.lower < joint.upper
        lower.append(joint.lower if bounded else -math.inf)
        upper.append(joint.upper if bounded else math.inf)
        effort.append(joint.effort if joint.effort and joint.effort > 0 else math.inf)
        velocity.append(joint.velocity if joint.velocity and joint.velocity > 0 else math.inf)
        damping.append(max(joint.damping, 0.0))
        friction.append(max(joint.friction, 0.0))
    arrays = (np.array(v, dtype=float) for v in (lower, upper, effort, velocity, damping, friction))
    return RobotModel(path, model, joints, tuple(kinds), info, *arrays, mimic=mimic)
