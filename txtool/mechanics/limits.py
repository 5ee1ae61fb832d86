"""A joint's URDF limits seen from the actuator, like Beam Bots' motor profiles.

Position limits go through the offset and reduction and are then ordered (a negative reduction
swaps them); speed and effort limits are magnitudes. For coupled transmissions each actuator
limit is the worst case over the box of joint limits: the maps are linear (affine for position),
so the extremes sit at the box corners.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Protocol

from txtool.model.robot import JointInfo


class Maps(Protocol):
    """What the limits need of a transmission's maps: :class:`txtool.mechanics.points.PointMap`
    (``show``) or :class:`txtool.mechanics.maps.TransmissionMap` (``simulate``)."""

    @property
    def joints(self) -> tuple[str, ...]: ...

    @property
    def actuators(self) -> tuple[str, ...]: ...

    def joint_to_actuator(self, quantity: str, values: Sequence[float]) -> Sequence[float]: ...


@dataclass(frozen=True)
class ActuatorLimit:
    """Limits of one actuator; a field is None when a joint it depends on has no such limit,
    or when the limit is beyond the floating-point range (huge limits times huge reductions)."""

    actuator: str
    position: tuple[float, float] | None
    velocity: float | None
    effort: float | None


Box = tuple[float, float] | None


def actuator_limits(tmap: Maps, joints: Mapping[str, JointInfo]) -> list[ActuatorLimit]:
    """One entry per actuator, in ``tmap.actuators`` order."""
    infos = [joints.get(name) for name in tmap.joints]
    position = [_position_range(info) for info in infos]
    velocity = [_symmetric(info.velocity if info else None) for info in infos]
    effort = [_symmetric(info.effort if info else None) for info in infos]
    # Which joints each actuator's value depends on, per quantity.
    motion = _dependence(tmap, "velocity")
    force = _dependence(tmap, "effort")
    return [
        ActuatorLimit(
            actuator=name,
            position=_interval(tmap, "position", position, motion[i], i),
            velocity=_magnitude(tmap, "velocity", velocity, motion[i], i),
            effort=_magnitude(tmap, "effort", effort, force[i], i),
        )
        for i, name in enumerate(tmap.actuators)
    ]


def _dependence(tmap: Maps, quantity: str) -> list[list[bool]]:
    """``[actuator][joint]``: whether the actuator's ``quantity`` moves with the joint's."""
    n = len(tmap.joints)
    columns = [tmap.joint_to_actuator(quantity, [float(j == k) for k in range(n)])
               for j in range(n)]
    return [[float(columns[j][i]) != 0.0 for j in range(n)] for i in range(len(tmap.actuators))]


def _position_range(info: JointInfo | None) -> Box:
    if info is None or info.type == "continuous" or info.lower is None or info.upper is None:
        return None
    return (info.lower, info.upper)


def _symmetric(limit: float | None) -> Box:
    return None if limit is None else (-abs(limit), abs(limit))


def _corner_values(
    tmap: Maps, quantity: str, boxes: list[Box], needed: list[bool], index: int,
) -> list[float] | None:
    """Actuator ``index``'s value at every corner of the joint box; None if a bound is absent
    or a value is not finite."""
    sides: list[Sequence[float]] = []
    for box, need in zip(boxes, needed, strict=True):
        if box is None and need:
            return None
        # A joint this actuator does not depend on can sit anywhere: use 0.
        sides.append(box if box is not None and need else (0.0,))
    values = [float(tmap.joint_to_actuator(quantity, [float(v) for v in corner])[index])
              for corner in itertools.product(*sides)]
    return values if all(math.isfinite(v) for v in values) else None


def _interval(
    tmap: Maps, quantity: str, boxes: list[Box], needed: list[bool], index: int,
) -> tuple[float, float] | None:
    values = _corner_values(tmap, quantity, boxes, needed, index)
    if values is None:
        return None
    # + 0.0 turns -0.0 (a reversed zero bound) into 0.0.
    return (min(values) + 0.0, max(values) + 0.0)


def _magnitude(
    tmap: Maps, quantity: str, boxes: list[Box], needed: list[bool], index: int,
) -> float | None:
    values = _corner_values(tmap, quantity, boxes, needed, index)
    return None if values is None else max(abs(v) for v in values)
