"""Rigid-body dynamics of a URDF written from scratch, to check the simulator's physics.

Nothing here comes from Pinocchio or from txtool's simulation: the URDF is read with lxml and
its dynamics computed with Featherstone's spatial-vector algebra (Rigid Body Dynamics
Algorithms, 2008: Plücker transforms, ch. 2; the recursive Newton-Euler algorithm, table 5.1;
the mass matrix by unit accelerations). Fixed joints fold their child's inertia into the parent
body. Revolute, continuous and prismatic joints; a fixed base; gravity along -z.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from lxml import etree

GRAVITY = 9.81


def _skew(p: np.ndarray) -> np.ndarray:
    return np.array([[0.0, -p[2], p[1]], [p[2], 0.0, -p[0]], [-p[1], p[0], 0.0]])


def _rpy(rpy: np.ndarray) -> np.ndarray:
    """Rotation of roll, pitch, yaw about fixed x, y, z (URDF): ``Rz Ry Rx``."""
    r, p, y = rpy
    rx = np.array([[1, 0, 0], [0, np.cos(r), -np.sin(r)], [0, np.sin(r), np.cos(r)]])
    ry = np.array([[np.cos(p), 0, np.sin(p)], [0, 1, 0], [-np.sin(p), 0, np.cos(p)]])
    rz = np.array([[np.cos(y), -np.sin(y), 0], [np.sin(y), np.cos(y), 0], [0, 0, 1]])
    return rz @ ry @ rx


def _axis_angle(axis: np.ndarray, angle: float) -> np.ndarray:
    k = _skew(axis)
    return np.eye(3) + np.sin(angle) * k + (1 - np.cos(angle)) * k @ k


def plucker(rotation: np.ndarray, position: np.ndarray) -> np.ndarray:
    """Motion transform from a frame A to a frame B whose axes are ``rotation`` (columns in A)
    and whose origin is ``position`` (in A)."""
    e = rotation.T
    x = np.zeros((6, 6))
    x[:3, :3] = e
    x[3:, 3:] = e
    x[3:, :3] = -e @ _skew(position)
    return x


def _cross_motion(v: np.ndarray) -> np.ndarray:
    w, u = _skew(v[:3]), _skew(v[3:])
    out = np.zeros((6, 6))
    out[:3, :3] = w
    out[3:, 3:] = w
    out[3:, :3] = u
    return out


def _spatial_inertia(mass: float, com: np.ndarray, inertia_at_com: np.ndarray) -> np.ndarray:
    c = _skew(com)
    out = np.zeros((6, 6))
    out[:3, :3] = inertia_at_com + mass * c @ c.T
    out[:3, 3:] = mass * c
    out[3:, :3] = mass * c.T
    out[3:, 3:] = mass * np.eye(3)
    return out


def _vector(text: str | None, default: tuple[float, float, float]) -> np.ndarray:
    return np.array([float(t) for t in text.split()]) if text else np.array(default, float)


def _origin(element: etree._Element | None) -> tuple[np.ndarray, np.ndarray]:
    origin = element.find("origin") if element is not None else None
    if origin is None:
        return np.eye(3), np.zeros(3)
    return _rpy(_vector(origin.get("rpy"), (0, 0, 0))), _vector(origin.get("xyz"), (0, 0, 0))


def _link_inertia(link: etree._Element) -> np.ndarray:
    inertial = link.find("inertial")
    if inertial is None:
        return np.zeros((6, 6))
    rotation, com = _origin(inertial)
    mass = float(inertial.find("mass").get("value"))
    i = inertial.find("inertia")
    g = {k: float(i.get(k, 0.0)) for k in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")}
    tensor = np.array([[g["ixx"], g["ixy"], g["ixz"]], [g["ixy"], g["iyy"], g["iyz"]],
                       [g["ixz"], g["iyz"], g["izz"]]])
    return _spatial_inertia(mass, com, rotation @ tensor @ rotation.T)


@dataclass
class Body:
    name: str  # the joint moving it
    kind: str  # revolute | continuous | prismatic
    parent: int  # index of the parent body, -1 for the base
    tree: np.ndarray  # parent body frame -> this joint's frame at q = 0
    axis: np.ndarray
    inertia: np.ndarray  # of everything rigidly attached, in the joint's frame


class Chain:
    """The moving bodies of a URDF, one per non-fixed joint, parents first."""

    def __init__(self, urdf: bytes) -> None:
        root = etree.fromstring(urdf)
        links = {link.get("name"): link for link in root.findall("link")}
        joints = root.findall("joint")  # not the <joint>s of transmissions
        children = {j.find("child").get("link") for j in joints}
        (base,) = [name for name in links if name not in children]
        self.bodies: list[Body] = []
        self.base_inertia = np.zeros((6, 6))
        self._attach(base, -1, np.eye(6), joints, links)

    def _attach(self, link: str, body: int, placement: np.ndarray,
                joints: list[etree._Element], links: dict[str, etree._Element]) -> None:
        """Add ``link`` (``placement``: ``body``'s frame -> the link's) and what hangs on it."""
        inertia = placement.T @ _link_inertia(links[link]) @ placement
        if body >= 0:
            self.bodies[body].inertia += inertia
        for joint in joints:
            if joint.find("parent").get("link") != link:
                continue
            rotation, position = _origin(joint)
            to_joint = plucker(rotation, position) @ placement
            child = joint.find("child").get("link")
            kind = joint.get("type")
            if kind == "fixed":
                self._attach(child, body, to_joint, joints, links)
                continue
            assert kind in ("revolute", "continuous", "prismatic"), kind
            axis = _vector(joint.find("axis").get("xyz") if joint.find("axis") is not None
                           else None, (1, 0, 0))
            self.bodies.append(Body(joint.get("name"), kind, body, to_joint,
                                    axis / np.linalg.norm(axis), np.zeros((6, 6))))
            self._attach(child, len(self.bodies) - 1, np.eye(6), joints, links)

    @property
    def names(self) -> list[str]:
        return [b.name for b in self.bodies]

    def _motion(self, body: Body, q: float) -> tuple[np.ndarray, np.ndarray]:
        """(joint transform, motion subspace) of ``body`` at coordinate ``q``."""
        if body.kind == "prismatic":
            return plucker(np.eye(3), body.axis * q), np.concatenate([np.zeros(3), body.axis])
        return plucker(_axis_angle(body.axis, q), np.zeros(3)), np.concatenate(
            [body.axis, np.zeros(3)])

    def kinematics(self, q: np.ndarray) -> list[tuple[np.ndarray, np.ndarray]]:
        """(transform from the parent body, motion subspace) of each body at ``q``: what
        every pass of the algorithms below at the same ``q`` shares."""
        found = []
        for i, body in enumerate(self.bodies):
            joint, s = self._motion(body, q[i])
            found.append((joint @ body.tree, s))
        return found

    def inverse_dynamics(self, q: np.ndarray, v: np.ndarray, a: np.ndarray,
                         gravity: float = GRAVITY,
                         kinematics: list[tuple[np.ndarray, np.ndarray]] | None = None,
                         ) -> np.ndarray:
        """Joint forces for accelerations ``a`` at ``(q, v)``: the recursive Newton-Euler
        algorithm (gravity as an upward acceleration of the base)."""
        n = len(self.bodies)
        up, vel, acc, force, subspace = [], [], [], [], []
        base_acc = np.array([0, 0, 0, 0, 0, gravity], dtype=float)
        for i, (body, (x, s)) in enumerate(zip(self.bodies, kinematics or self.kinematics(q),
                                               strict=True)):
            parent_v = vel[body.parent] if body.parent >= 0 else np.zeros(6)
            parent_a = acc[body.parent] if body.parent >= 0 else base_acc
            vi = x @ parent_v + s * v[i]
            ai = x @ parent_a + s * a[i] + _cross_motion(vi) @ (s * v[i])
            fi = body.inertia @ ai - _cross_motion(vi).T @ (body.inertia @ vi)
            up.append(x)
            vel.append(vi)
            acc.append(ai)
            force.append(fi)
            subspace.append(s)
        tau = np.zeros(n)
        for i in reversed(range(n)):
            tau[i] = subspace[i] @ force[i]
            parent = self.bodies[i].parent
            if parent >= 0:
                force[parent] = force[parent] + up[i].T @ force[i]
        return tau

    def mass_matrix(self, q: np.ndarray,
                    kinematics: list[tuple[np.ndarray, np.ndarray]] | None = None) -> np.ndarray:
        """Column j: the joint forces of a unit acceleration of joint j at rest without
        gravity; the recursive Newton-Euler algorithm run on every column at once (at rest,
        no velocity term couples them)."""
        n = len(self.bodies)
        unit = np.eye(n)
        acc: list[np.ndarray] = []
        force: list[np.ndarray] = []
        motion = kinematics or self.kinematics(q)
        for i, (body, (x, s)) in enumerate(zip(self.bodies, motion, strict=True)):
            parent_a = acc[body.parent] if body.parent >= 0 else np.zeros((6, n))
            ai = x @ parent_a + np.outer(s, unit[i])
            acc.append(ai)
            force.append(body.inertia @ ai)
        mass = np.zeros((n, n))
        for i in reversed(range(n)):
            x, s = motion[i]
            mass[i] = s @ force[i]
            parent = self.bodies[i].parent
            if parent >= 0:
                force[parent] = force[parent] + x.T @ force[i]
        return mass

    def bias(self, q: np.ndarray, v: np.ndarray) -> np.ndarray:
        """Coriolis, centrifugal and gravity forces."""
        return self.inverse_dynamics(q, v, np.zeros(len(self.bodies)))

    def acceleration(self, q: np.ndarray, v: np.ndarray, tau: np.ndarray,
                     armature: np.ndarray, damping: np.ndarray) -> np.ndarray:
        motion = self.kinematics(q)
        mass = self.mass_matrix(q, motion) + np.diag(armature)
        bias = self.inverse_dynamics(q, v, np.zeros(len(self.bodies)), kinematics=motion)
        return np.linalg.solve(mass, tau - bias - damping * v)


def rk4(chain: Chain, q: np.ndarray, v: np.ndarray, tau: np.ndarray, dt: float, steps: int,
        armature: np.ndarray, damping: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``(q, v)`` after ``dt`` with ``tau`` held, in ``steps`` classical Runge-Kutta steps."""
    h = dt / steps

    def f(state: np.ndarray) -> np.ndarray:
        n = len(q)
        return np.concatenate([state[n:], chain.acceleration(state[:n], state[n:], tau,
                                                             armature, damping)])

    state = np.concatenate([q, v])
    for _ in range(steps):
        k1 = f(state)
        k2 = f(state + h / 2 * k1)
        k3 = f(state + h / 2 * k2)
        k4 = f(state + h * k3)
        state = state + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
    return state[: len(q)], state[len(q):]
