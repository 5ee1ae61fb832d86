"""A joint's URDF limits seen from the actuator, like Beam Bots' motor profiles.

Position limits go through the offset and reduction and are then ordered (a negative reduction
swaps them); speed and effort limits are magnitudes. For coupled transmissions each actuator
limit is the worst case over the box of joint limits: the maps are linear (affine for position),
so the extremes sit at the box corners.
"""

from __future__ import annotations

import itertools
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from txtool.mechanics.maps import TransmissionMap
from txtool.model.robot import JointInfo


@dataclass(frozen=True)
class ActuatorLimit:
    """Limits of one actuator; a field is None when a joint it depends on has no such limit,
    or when the limit is beyond the floating-point range (huge limits times huge reductions)."""

    actuator: str
    position: tuple[float, float] | None
    velocity: float | None
    effort: float | None


def actuator_limits(
    tmap: TransmissionMap, joints: Mapping[str, JointInfo]
) -> list[ActuatorLimit]:
    """One entry per actuator, in ``tmap.actuators`` order."""
    infos = [joints.get(name) for name in tmap.joints]
    position = [_position_range(info) for info in infos]
    velocity = [_symmetric(info.velocity if info else None) for info in infos]
    effort = [_symmetric(info.effort if info else None) for info in infos]
    # Which joints each actuator's value depends on, per quantity.
    unit = np.eye(tmap.size)
    motion = tmap.joint_to_actuator("velocity", unit).T != 0.0
    force = tmap.joint_to_actuator("effort", unit).T != 0.0
    return [
        ActuatorLimit(
            actuator=name,
            position=_interval(tmap, "position", position, motion[i], i),
            velocity=_magnitude(tmap, "velocity", velocity, motion[i], i),
            effort=_magnitude(tmap, "effort", effort, force[i], i),
        )
        for i, name in enumerate(tmap.actuators)
    ]


def _position_range(info: JointInfo | None) -> tuple[float, float] | None:
    if info is None or info.type == "continuous" or info.lower is None or info.upper is None:
        return None
    return (info.lower, info.upper)


def _symmetric(limit: float | None) -> tuple[float, float] | None:
    return None if limit is None else (-abs(limit), abs(limit))


def _corner_values(
    tmap: TransmissionMap,
    quantity: str,
    boxes: list[tuple[float, float] | None],
    needed: np.ndarray,
    index: int,
) -> np.ndarray | None:
    """Actuator ``index``'s value at every corner of the joint box; None if a bound is absent."""
    sides = []
    for box, need in zip(boxes, needed, strict=True):
        if box is None and need:
            return None
        # A joint this actuator does not depend on can sit anywhere: use 0.
        sides.append(box if box is not None and need else (0.0,))
    corners = np.array(list(itertools.product(*sides)), dtype=float)
    return tmap.joint_to_actuator(quantity, corners)[:, index]


def _interval(
    tmap: TransmissionMap,
    quantity: str,
    boxes: list[tuple[float, float] | None],
    needed: np.ndarray,
    index: int,
) -> tuple[float, float] | None:
    values = _corner_values(tmap, quantity, boxes, needed, index)
    if values is None or not np.isfinite(values).all():
        return None
    # + 0.0 turns -0.0 (a reversed zero bound) into 0.0.
    return (float(values.min()) + 0.0, float(values.max()) + 0.0)


def _magnitude(
    tmap: TransmissionMap,
    quantity: str,
    boxes: list[tuple[float, float] | None],
    needed: np.ndarray,
    index: int,
) -> float | None:
    values = _corner_values(tmap, quantity, boxes, needed, index)
    if values is None or not np.isfinite(values).all():
        return None
    return float(np.abs(values).max())
