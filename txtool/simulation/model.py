"""The rigid-body model: Pinocchio built from the URDF text after xacro, fixed base.

Joint coordinates ``x`` are one number per velocity DoF (the unwrapped angle for continuous
joints); :meth:`RobotModel.config` turns them into Pinocchio's configuration (``cos, sin`` for
continuous joints), which is what ``pin.integrate`` produces for them. Mimic joints follow their
leader inside Pinocchio (``mimic=True``); they have no DoF of their own and no transmission.
"""

from __future__ import annotations

import contextlib
import copy
import math
import os
import sys
import tempfile
from collections.abc import Iterator
from dataclasses import dataclass, field

import numpy as np
import pinocchio as pin

from txtool.io.xmlio import InputError, Source, local, serialize
from txtool.model.robot import JointInfo, joint_elements, robot_joints

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
    followers: dict[str, tuple[str, float, float]] = field(default_factory=dict)
    locked: dict[str, tuple[str, ...]] = field(default_factory=dict)  # joint -> massless links
    notes: list[str] = field(default_factory=list)

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


class Massless(InputError):
    """The robot has moving joints but none moves a link with mass or inertia."""


def build(source: Source) -> RobotModel:
    """The model of ``source`` (its xacro expansion for .xacro files)."""
    info = robot_joints(source.root)
    for name, joint in info.items():
        if joint.type in ("floating", "planar"):
            raise InputError(f"{source.path}:{joint.line}: joint '{name}' is {joint.type}; "
                             "simulate supports fixed-base robots with 1-DoF joints")
    mimic = tuple(n for n, j in info.items() if j.mimic is not None and j.type in MOVING)
    _refuse_crowded_elements(source)
    text = serialize(source.tree).decode("utf-8")
    notes: list[str] = []
    followers: dict[str, tuple[str, float, float]] = {}
    model, why = _pinocchio(text, bool(mimic))
    if model is None and mimic:
        model, _ = _pinocchio(text, False)
        if model is not None:
            followers = _followers(source, mimic, info)
            notes.append(f"pinocchio cannot place the mimic joints ({why}): they move as "
                         "independent joints whose reference follows their leader: "
                         + ", ".join(followers))
            mimic = ()
    if model is None:
        raise InputError(f"{source.path}: pinocchio cannot build the model: {why}")
    locked = _massless(model, source)
    if locked:
        model = _locked_model(source, set(locked), bool(mimic))
        for joint, links in locked.items():
            notes.append(f"joint '{joint}' moves only links without mass or inertia "
                         f"({', '.join(links)}): it is locked and not simulated")
    joints = [name for name, joint in zip(model.names[1:], model.joints[1:], strict=True)
              if joint.nv > 0]  # a mimic joint has no DoF of its own
    if not joints and locked:
        raise Massless(f"{source.path}: no joint moves a link with mass or inertia "
                       f"(joints {', '.join(sorted(locked))}): simulate needs the URDF's "
                       "<inertial> elements")
    if not joints:
        raise InputError(f"{source.path}: the robot has no moving joints")
    order = sorted(joints, key=lambda n: model.joints[model.getJointId(n)].idx_v)
    robot = _robot_model(source.path, model, tuple(order), info, mimic)
    robot.followers = {k: f for k, f in followers.items() if k in robot.joints
                       and f[0] in robot.joints}
    robot.locked, robot.notes = locked, notes
    return robot


MAX_ATTRIBUTES = 256  # a URDF element has about ten; Pinocchio's parser is quadratic in them


def _refuse_crowded_elements(source: Source) -> None:
    """One line, before Pinocchio parses a document with an element of absurdly many
    attributes (16,000 on one element take it about a second, 64,000 about fifteen)."""
    for element in source.root.iter():
        if len(element.attrib) > MAX_ATTRIBUTES:
            raise InputError(
                f"{source.path}:{element.sourceline}: <{local(element)}> has "
                f"{len(element.attrib)} attributes; simulate refuses more than {MAX_ATTRIBUTES} "
                "on one element (Pinocchio's URDF parser slows down quadratically on them)")


def _pinocchio(text: str, mimic: bool) -> tuple[pin.Model | None, str]:
    """The model, or None and the first line of Pinocchio's (or urdfdom's) complaint."""
    with captured_stderr() as said:
        try:
            return pin.buildModelFromXML(text, mimic), ""
        except (RuntimeError, ValueError) as exc:
            error = str(exc).strip().splitlines()[0] if str(exc).strip() else type(exc).__name__
    detail = next((line.removeprefix("Error:").strip() for line in said
                   if line.startswith("Error:")), error)
    return None, detail


def _followers(source: Source, mimic: tuple[str, ...], info: dict[str, JointInfo]
               ) -> dict[str, tuple[str, float, float]]:
    """Mimic joint -> (leader, multiplier, offset), as URDF ``<mimic>`` gives them."""
    elements = joint_elements(source.root)
    result = {}
    for name in mimic:
        tag = next(elements[name].iterchildren("{*}mimic"), None)
        leader = info[name].mimic
        if tag is None or leader is None:
            continue
        multiplier = _number(tag.get("multiplier"), 1.0)
        offset = _number(tag.get("offset"), 0.0)
        result[name] = (leader, multiplier, offset)
    return result


def _number(text: str | None, default: float) -> float:
    try:
        value = float(text) if text is not None else default
    except ValueError:
        return default
    return value if math.isfinite(value) else default


def _massless(model: pin.Model, source: Source) -> dict[str, tuple[str, ...]]:
    """Joints whose moving links have no mass and no inertia: their mass-matrix entry is 0."""
    data = model.createData()
    mass = pin.crba(model, data, pin.neutral(model))
    found = {}
    for joint_id in range(1, model.njoints):
        joint = model.joints[joint_id]
        if joint.nv == 0 or mass[joint.idx_v, joint.idx_v] > 0.0:
            continue
        if any(model.inertias[j].mass > 0 for j in _subtree(model, joint_id)):
            continue
        name = model.names[joint_id]
        found[name] = _links_moved(source, name)
    return found


def _subtree(model: pin.Model, joint_id: int) -> list[int]:
    return [j for j in range(joint_id, model.njoints)
            if joint_id in _ancestors(model, j)]


def _ancestors(model: pin.Model, joint_id: int) -> set[int]:
    seen = set()
    while joint_id > 0:
        seen.add(joint_id)
        joint_id = model.parents[joint_id]
    return seen


def _links_moved(source: Source, joint: str) -> tuple[str, ...]:
    """The links downstream of ``joint`` in the URDF (its child and everything fixed below)."""
    elements = joint_elements(source.root)
    below: dict[str, list[str]] = {}
    for element in elements.values():
        parent, child = element.find("{*}parent"), element.find("{*}child")
        if parent is not None and child is not None:
            below.setdefault(parent.get("link", ""), []).append(child.get("link", ""))
    child = elements[joint].find("{*}child")
    stack = [child.get("link", "")] if child is not None else []
    links: list[str] = []
    while stack:
        link = stack.pop()
        links.append(link)
        stack.extend(below.get(link, []))
    return tuple(links)


def _locked_model(source: Source, locked: set[str], mimic: bool) -> pin.Model:
    tree = copy.deepcopy(source.tree)
    for name, element in joint_elements(tree.getroot()).items():
        if name in locked:
            element.set("type", "fixed")
    model, why = _pinocchio(serialize(tree).decode("utf-8"), mimic)
    if model is None:
        raise InputError(f"{source.path}: pinocchio cannot build the model with "
                         f"{', '.join(sorted(locked))} locked: {why}")
    return model


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
