"""What a ROS loader actually builds from a transmission: the parameters the maths uses.

ros_control (ROS 1) takes the parameters of a coupled transmission by ``<role>`` but fills
the joint and actuator data in XML order (so a member listed against its role is driven with
the other member's values, TX404), and reads the simple reduction from the actuator.
ros2_control reads the simple reduction from the joint, takes coupled parameters in XML order,
and then orders the joint and actuator handles by name
(a ``std::set``) when the hardware plugin configures the transmission. :func:`effective` returns
the parameters bound to each index together with the names at that index, so two configs
behave alike exactly when their :class:`Effective` values are equal.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal

from txtool.model.core import Member, Number, Transmission
from txtool.model.distro import Distro, NumberReading, numbers_of
from txtool.model.numbers import parse_ros2, ros2_readings_differ

Loader = Literal["ros1", "ros2"]
ROLES_JOINT = ("joint1", "joint2")
ROLES_ACTUATOR = ("actuator1", "actuator2")


def against_roles(members: tuple[Member, ...], roles: tuple[str, str]) -> bool:
    """A coupled pair written role 2 first: ros_control takes the values by role but the data
    in XML order (joint_state_interface_provider.cpp), so the two swap values."""
    return [m.role for m in members] == [roles[1], roles[0]]


def listed_against_roles(t: Transmission) -> bool:
    """A coupled member pair of ``t`` written role 2 first (see :func:`against_roles`)."""
    return against_roles(t.joints, ROLES_JOINT) or against_roles(t.actuators, ROLES_ACTUATOR)


class NotLoadable(ValueError):
    """The loader would refuse this transmission; the message says why."""


@dataclass(frozen=True)
class Effective:
    """Parameters as the transmission maths sees them: index i of each tuple goes together."""

    name: str
    kind: Literal["simple", "differential", "four_bar"]
    joints: tuple[str, ...]
    actuators: tuple[str, ...]
    actuator_reduction: tuple[float, ...]
    joint_reduction: tuple[float, ...]
    joint_offset: tuple[float, ...]
    loader: Loader

    @property
    def directions(self) -> tuple[int, ...]:
        """Sign of the effective reduction per joint: -1 where the joint runs reversed."""
        signs = []
        for i in range(len(self.joints)):
            product = self.joint_reduction[i] * self.actuator_reduction[i]
            signs.append(-1 if product < 0 else 1)
        return tuple(signs)


def loader_of(transmission: Transmission) -> Loader:
    return "ros1" if transmission.dialect == "ros1" else "ros2"


def effective(transmission: Transmission, distro: Distro | None = None,
              added_actuators: tuple[str, ...] = ()) -> Effective:
    """The loaded parameters, or :class:`NotLoadable` with the loader's reason.

    ``distro`` says which build of ros2_control reads a ROS 2 transmission's numbers
    (Humble's ``istringstream`` or Jazzy's and later ``from_chars``); None: the value every
    ROS 2 distribution reads, the default where they read the text differently or not at all
    (:func:`ros2_values_differ` tells these apart). ROS 1 reads with ``std::stod`` always.
    ``added_actuators``: what ros2_control's parser appends (``actuator1`` in an actuator
    component), which configure() takes as one more actuator handle.
    """
    if transmission.kind == "other":
        raise NotLoadable(f"custom type '{transmission.type}' has no standard maths")
    if loader_of(transmission) == "ros1":
        result = _ros1(transmission)
    else:
        reading = None if distro is None else numbers_of(distro)
        result = _ros2(transmission, reading, added_actuators)
    for value in result.actuator_reduction + result.joint_reduction:
        if value == 0.0:
            raise NotLoadable("reduction ratio cannot be zero")
        if not math.isfinite(value):
            raise NotLoadable(f"reduction {value!r} is not finite")
    for value in result.joint_offset:
        if not math.isfinite(value):
            raise NotLoadable(f"offset {value!r} is not finite")
    return result


def _required(number: Number | None, what: str) -> float:
    if number is None:
        raise NotLoadable(f"{what} is missing")
    if number.value is None:
        raise NotLoadable(f"{what} '{number.text}' is not a number")
    return number.value


def _ros1(t: Transmission) -> Effective:
    want = 1 if t.kind == "simple" else 2
    if len(t.actuators) != want:
        raise NotLoadable(f"expected {want} actuator(s), got {len(t.actuators)}")
    if len(t.joints) != want:
        raise NotLoadable(f"expected {want} joint(s), got {len(t.joints)}")
    if t.kind == "simple":
        joint, actuator = t.joints[0], t.actuators[0]
        return Effective(
            name=t.name,
            kind="simple",
            joints=(joint.name,),
            actuators=(actuator.name,),
            actuator_reduction=(
                _required(actuator.mechanical_reduction, _what(actuator, "reduction")),
            ),
            joint_reduction=(1.0,),
            joint_offset=(_value_ros1_optional(joint.offset, 0.0, _what(joint, "offset")),),
            loader="ros1",
        )
    # Parameters by <role>, data in XML order (see txtool.views.effective for the source).
    joints = by_role(t.joints, ROLES_JOINT, "joint")
    actuators = by_role(t.actuators, ROLES_ACTUATOR, "actuator")
    return Effective(
        name=t.name,
        kind=t.kind,  # type: ignore[arg-type]
        joints=tuple(j.name for j in t.joints),
        actuators=tuple(a.name for a in t.actuators),
        actuator_reduction=tuple(
            _required(a.mechanical_reduction, _what(a, "reduction")) for a in actuators
        ),
        joint_reduction=tuple(
            _value_ros1_optional(j.mechanical_reduction, 1.0, _what(j, "reduction"))
            for j in joints
        ),
        joint_offset=tuple(_value_ros1_optional(j.offset, 0.0, _what(j, "offset")) for j in joints),
        loader="ros1",
    )


def _value_ros1_optional(number: Number | None, default: float, what: str) -> float:
    if number is None:
        return default
    if number.value is None:
        raise NotLoadable(f"{what} '{number.text}' is not a number")
    return number.value


def _what(member: Member, field: str) -> str:
    return f"'{member.name}' {field}"


def by_role(members: tuple[Member, ...], roles: tuple[str, str], noun: str) -> list[Member]:
    by_role: dict[str, Member] = {}
    for member in members:
        if member.role not in roles:
            raise NotLoadable(
                f"{noun} '{member.name}' has role {member.role!r}, expected {' or '.join(roles)}"
            )
        if member.role in by_role:
            raise NotLoadable(f"{noun}s '{by_role[member.role].name}' and '{member.name}' "
                              f"both have role '{member.role}'")
        by_role[member.role] = member
    return [by_role[role] for role in roles]


def ros2_value(number: Number | None, default: float, distro: Distro | None = None) -> float:
    """What ros2_control's parser stores for ``number`` (``<mechanical_reduction>`` or
    ``<offset>``, as :mod:`txtool.dialects.read` found it): the default where it is absent or
    its text does not convert (component_parser.cpp ``get_parameter_value_or``)."""
    return _ros2_number(number, default, None if distro is None else numbers_of(distro))


def ros2_values_differ(t: Transmission) -> bool:
    """Some number of ROS 2 ``t`` is read differently by different ROS 2 distributions."""
    if t.dialect == "ros1":
        return False
    for member in (*t.joints, *t.actuators):
        for number in (member.mechanical_reduction, member.offset):
            if number is not None and ros2_readings_differ(number.text):
                return True
    return False


def _ros2_number(number: Number | None, default: float, reading: NumberReading | None) -> float:
    # ros2_control silently falls back to the default for absent or unparsable text.
    if number is None:
        return default
    value = number.value if reading is None else parse_ros2(number.text, reading)
    return default if value is None else value


def _ros2(t: Transmission, reading: NumberReading | None, added: tuple[str, ...]) -> Effective:
    if not t.joints:
        raise NotLoadable("no joints (ros2_control's loader reads joints.at(0))")
    if t.kind == "simple":
        # SimpleTransmission::configure (simple_transmission.hpp) takes one handle name each:
        # "Joint names given to transmissions should be identical", likewise actuators.
        for noun, names in (("joint", [j.name for j in t.joints]),
                            ("actuator", [a.name for a in t.actuators] + list(added))):
            if len(set(names)) > 1:
                listed = ", ".join(f"'{n}'" for n in dict.fromkeys(names))
                raise NotLoadable(f"a simple transmission takes one {noun}, found {listed} "
                                  f"(configure: {noun} names should be identical)")
        joint = t.joints[0]
        actuator = t.actuators[0].name if t.actuators else (added or ("actuator1",))[0]
        return Effective(
            name=t.name,
            kind="simple",
            joints=(joint.name,),
            actuators=(actuator,),
            actuator_reduction=(1.0,),
            joint_reduction=(_ros2_number(joint.mechanical_reduction, 1.0, reading),),
            joint_offset=(_ros2_number(joint.offset, 0.0, reading),),
            loader="ros2",
        )
    if len(t.joints) < 2 or len(t.actuators) < 2:
        raise NotLoadable(
            f"needs 2 joints and 2 actuators, got {len(t.joints)} and {len(t.actuators)}"
        )
    joint_names = sorted({j.name for j in t.joints})
    actuator_names = sorted({a.name for a in t.actuators})
    if len(joint_names) != 2 or len(actuator_names) != 2:
        raise NotLoadable("there should be exactly two unique joint and actuator names")
    # configure() takes the handles of each of the two names for every interface and wants two:
    # a hardware plugin passes one handle per listed member, so a name listed twice makes
    # three ("Not enough valid or required ... handles were present";
    # differential_transmission.hpp and four_bar_linkage_transmission.hpp, configure).
    for noun, members in (("joint", t.joints), ("actuator", t.actuators)):
        if len(members) != 2:
            raise NotLoadable(f"{len(members)} {noun}s listed for two {noun} names: configure() "
                              f"takes one handle per listed {noun} and wants exactly two")
    return Effective(
        name=t.name,
        kind=t.kind,  # type: ignore[arg-type]
        joints=tuple(joint_names),
        actuators=tuple(actuator_names),
        actuator_reduction=tuple(
            _ros2_number(a.mechanical_reduction, 1.0, reading) for a in t.actuators[:2]
        ),
        joint_reduction=tuple(
            _ros2_number(j.mechanical_reduction, 1.0, reading) for j in t.joints[:2]
        ),
        joint_offset=tuple(_ros2_number(j.offset, 0.0, reading) for j in t.joints[:2]),
        loader="ros2",
    )
