"""Dialect-neutral views of a transmission, for proving that a conversion kept everything.

Each field is read with the semantics of the transmission's own loader (a ROS 1 simple
reduction from the actuator, a ROS 2 one from the joint, ros2_control's silent defaults), so
a ROS 1 original and its ROS 2 conversion have equal views exactly when nothing was lost.
"""

from __future__ import annotations

from typing import Any

from txtool.dialects.translate import interface_kind
from txtool.model.core import Member, Number, Transmission

FIELDS = ("reduction", "offset", "direction", "roles", "interfaces")


def _loaded(number: Number | None, default: float | None, ros2: bool) -> float | None:
    if number is None:
        return default
    if number.value is None:
        return default if ros2 else None
    return number.value


def _sign(value: float | None) -> int | None:
    if value is None:
        return None
    return -1 if value < 0 else 1


def _interfaces(member: Member, ros2: bool) -> frozenset[str]:
    if not ros2:
        return frozenset(k for k in map(interface_kind, member.interfaces) if k is not None)
    kinds = {i for i in member.interfaces if i in ("position", "velocity", "effort")}
    if not kinds and member.state_interfaces:
        kinds = {"state"}
    return frozenset(kinds)


def view(t: Transmission) -> dict[str, Any]:
    """name, kind and the five compared fields (see :data:`FIELDS`)."""
    ros2 = t.dialect != "ros1"
    reductions: dict[str, float | None] = {}
    if t.kind == "simple":
        if ros2:
            joint = t.joints[0] if t.joints else None
            n = _loaded(joint.mechanical_reduction if joint else None, 1.0, True)
        else:
            actuator = t.actuators[0] if t.actuators else None
            n = _loaded(actuator.mechanical_reduction if actuator else None, None, False)
        reductions["*"] = n
        roles: Any = None
    else:
        for joint in t.joints:
            reductions[joint.name] = _loaded(joint.mechanical_reduction, 1.0, ros2)
        for actuator in t.actuators:
            default = 1.0 if ros2 else None
            reductions[actuator.name] = _loaded(actuator.mechanical_reduction, default, ros2)
        roles = {m.name: m.role for m in t.joints + t.actuators}
    return {
        "name": t.name,
        "kind": t.kind,
        "reduction": reductions,
        "offset": {j.name: _loaded(j.offset, 0.0, ros2) for j in t.joints},
        "direction": {k: _sign(v) for k, v in reductions.items()},
        "roles": roles,
        "interfaces": {j.name: _interfaces(j, ros2) for j in t.joints},
    }
