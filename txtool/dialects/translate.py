"""Translate a canonical transmission from one dialect to another, saying what cannot be carried.

The rules (each one is tested):

* Simple: ROS 1 reads the reduction from the **actuator**, ros2_control from the **joint**; the
  value moves so that the effective reduction is unchanged.
* Coupled: members are emitted in role order (joint1, joint2 / actuator1, actuator2), since
  ros2_control binds values by XML order.
* Missing roles are written as ``joint1`` / ``actuator1`` in ROS 2 (ros2_control throws without).
* Offsets stay on the joint; direction is the sign of the effective reduction.
* A number whose text the target loader would read differently is rewritten in shortest
  round-trip form; otherwise its text is kept as written.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from functools import lru_cache
from typing import Any

from txtool.model.core import Dialect, Member, Number, Transmission, replace, standard_type
from txtool.model.numbers import format_float, parse_ros1, parse_ros2

ROS1_INTERFACE = {
    "position": "hardware_interface/PositionJointInterface",
    "velocity": "hardware_interface/VelocityJointInterface",
    "effort": "hardware_interface/EffortJointInterface",
}
ROS1_STATE_ONLY = "hardware_interface/JointStateInterface"


@dataclass
class Translation:
    transmission: Transmission
    losses: list[str] = field(default_factory=list)  # information that does not survive
    notes: list[str] = field(default_factory=list)  # changes that keep behaviour
    warnings: list[str] = field(default_factory=list)  # to look at, though nothing is lost
    interfaces_taken: bool = False  # the actuators' interfaces went to bare joints


def family(dialect: Dialect) -> str:
    return "ros1" if dialect == "ros1" else "ros2"


@lru_cache(maxsize=256)  # a document spells its interfaces a few ways: each member asks
def interface_kind(name: str) -> str | None:
    """``hardware_interface/BiDirectionalPositionJointInterface`` -> ``position``."""
    short = name.strip().rsplit("/", 1)[-1]
    short = short.removeprefix("BiDirectional")
    for kind in ("Position", "Velocity", "Effort"):
        if short == f"{kind}JointInterface":
            return kind.lower()
    if short == "JointStateInterface":
        return "state"
    if name.strip() in ("position", "velocity", "effort"):
        return name.strip()
    return None


# ros_control's combined command interfaces (hardware_interface/posvel_command_interface.h,
# posvelacc_command_interface.h): one handle commanding several values, which ros2_control
# declares as one command interface each (hardware_interface_type_values.hpp: HW_IF_POSITION,
# HW_IF_VELOCITY, HW_IF_ACCELERATION).
COMBINED = {
    "PosVelJointInterface": ("position", "velocity"),
    "PosVelAccJointInterface": ("position", "velocity", "acceleration"),
}


@lru_cache(maxsize=256)
def combined_kinds(name: str) -> tuple[str, ...] | None:
    """``hardware_interface/PosVelJointInterface`` -> ``("position", "velocity")``."""
    return COMBINED.get(name.strip().rsplit("/", 1)[-1])


def command_kinds(name: str) -> tuple[str, ...]:
    """The ros2_control command interfaces a ROS 1 hardware interface name stands for."""
    combined = combined_kinds(name)
    if combined is not None:
        return combined
    kind = interface_kind(name)
    return (kind,) if kind in ("position", "velocity", "effort") else ()


@lru_cache(maxsize=256)
def ros2_interfaces(ros1_names: tuple[str, ...]) -> tuple[tuple[str, ...], tuple[str, ...]]:
    """Command and state interfaces of a ros2_control joint for ROS 1 hardware interfaces."""
    commands: list[str] = []
    for name in ros1_names:
        for kind in command_kinds(name):
            if kind not in commands:
                commands.append(kind)
    states = ["position", "velocity"]
    if "effort" in commands:
        states.append("effort")
    return tuple(commands), tuple(states)


def translate(t: Transmission, target: Dialect) -> Translation:
    if t.kind == "other":
        result = Translation(t)
        if family(t.dialect) != family(target):
            result.losses.append(
                f"transmission '{t.name}': custom type '{t.type}' cannot be carried to "
                f"{target}; left as written"
            )
        return result
    if family(t.dialect) == family(target):
        return Translation(replace(t, dialect=target))
    if target == "ros1":
        return _to_ros1(t)
    return _to_ros2(t, target)


def is_expression(number: Number | None) -> bool:
    """A xacro expression (``${ratio}``) in an unexpanded source: carried verbatim."""
    text = number.text if number is not None else None
    return text is not None and ("${" in text or "$(" in text)


def _retext(number: Number | None, parse: Callable[[str | None], float | None]) -> Number | None:
    """Keep the text when the target loader reads it as the same value."""
    if number is None or number.value is None:
        return number
    if number.text is not None and parse(number.text) == number.value:
        return number
    return Number(value=number.value, text=format_float(number.value))


def _ordered(members: tuple[Member, ...], roles: tuple[str, str]) -> tuple[Member, ...] | None:
    """The two ``members`` in the order of ``roles``, where they have those roles."""
    if len(members) != 2:
        return None
    first, second = members
    if (first.role, second.role) == roles:
        return members
    if (second.role, first.role) == roles:
        return second, first
    return None


def _order_coupled(t: Transmission, result: Translation) -> tuple[tuple[Member, ...], ...]:
    joints = _ordered(t.joints, ("joint1", "joint2"))
    actuators = _ordered(t.actuators, ("actuator1", "actuator2"))
    if joints is None or actuators is None:
        result.losses.append(
            f"transmission '{t.name}': coupled members need roles joint1/joint2 and "
            "actuator1/actuator2 to be ordered; kept in XML order"
        )
    return joints or t.joints, actuators or t.actuators


def _to_ros2(t: Transmission, target: Dialect) -> Translation:
    result = Translation(t)
    t = _interfaces_from_actuators(t, result)
    joints, actuators = t.joints, t.actuators
    if t.kind == "simple":
        joints, actuators = _simple_to_ros2(t, result)
    else:
        joints, actuators = _order_coupled(t, result)
        joints = tuple([_ros2_joint(j, result) for j in joints])
        actuators = tuple([_ros2_actuator(a, result) for a in actuators])
    result.transmission = replace(
        t,
        type=standard_type(t.kind),
        joints=joints,
        actuators=actuators,
        dialect=target,
    )
    return result


def _interfaces_from_actuators(t: Transmission, result: Translation) -> Transmission:
    """``t`` with the actuators' hardware interfaces on each joint that names none, where
    all actuators that name some agree: the place from before ROS Indigo, which
    gazebo_ros_control still reads (gazebo_ros_control/src/default_robot_hw_sim.cpp,
    ``initSim``: "The <hardware_interface> element of tranmission ... should be nested inside
    the <joint> element, not <actuator>"), as TX301's fix moves it."""
    named = {tuple([i.strip() for i in a.interfaces]) for a in t.actuators if a.interfaces}
    if len(named) != 1 or all(j.interfaces for j in t.joints):
        return t
    interfaces = next(a.interfaces for a in t.actuators if a.interfaces)
    joints = []
    for joint in t.joints:
        if not joint.interfaces:
            result.notes.append(
                f"joint '{joint.name}': names no <hardwareInterface>; given its actuator's "
                f"({', '.join(i.strip() for i in interfaces)}), as gazebo_ros_control reads "
                "it (ros_control since Indigo skips such a joint: TX301)")
            joint = replace(joint, interfaces=interfaces)
        joints.append(joint)
    result.interfaces_taken = True
    return replace(t, joints=tuple(joints))


def _simple_to_ros2(t: Transmission, result: Translation) -> tuple[tuple[Member, ...], ...]:
    reduction = t.actuators[0].mechanical_reduction if t.actuators else None
    joints = []
    for index, joint in enumerate(t.joints):
        if joint.mechanical_reduction is not None:
            result.losses.append(
                f"joint '{joint.name}': <mechanicalReduction> {joint.mechanical_reduction.text}"
                " is ignored by ros_control for simple transmissions and has no place in ROS 2"
            )
        moved = _retext(reduction, parse_ros2) if index == 0 else None
        joints.append(_ros2_joint(joint, result, mechanical_reduction=moved,
                                  role=joint.role or "joint1"))
    actuators = tuple([
        _ros2_actuator(a, result, mechanical_reduction=None, role=a.role or "actuator1")
        for a in t.actuators
    ])
    return tuple(joints), actuators


def _ros2_joint(joint: Member, result: Translation, **changes: Any) -> Member:
    """``joint`` as ros2_control declares it (``changes``: fields the caller sets itself)."""
    commands, states = ros2_interfaces(joint.interfaces)
    if joint.interfaces:
        _tell_interfaces(joint, commands, result)
    if "mechanical_reduction" not in changes:
        changes["mechanical_reduction"] = _retext(joint.mechanical_reduction, parse_ros2)
    return replace(joint, offset=_retext(joint.offset, parse_ros2), interfaces=commands,
                   state_interfaces=states, **changes)


def _tell_interfaces(joint: Member, commands: tuple[str, ...], result: Translation) -> None:
    """What the ros2_control declaration of ``joint``'s ROS 1 interfaces leaves out or adds."""
    expressions = [i for i in joint.interfaces if "${" in i or "$(" in i]
    if expressions:
        result.losses.append(
            f"joint '{joint.name}': hardware interface {', '.join(expressions)} is a xacro "
            "expression, from which no ros2_control command interface can be derived; convert "
            "the expanded robot, or write the interface"
        )
    unknown = [i for i in joint.interfaces
               if interface_kind(i) is None and combined_kinds(i) is None
               and i not in expressions]
    for name in joint.interfaces:
        if combined_kinds(name) is not None:
            result.notes.append(
                f"joint '{joint.name}': {name.strip()} (ros_control's combined command "
                f"handle) is declared as the command interfaces "
                f"{', '.join(combined_kinds(name) or ())}")
    if unknown:
        # ros_control loads no provider for such a name: it skips it, and refuses the
        # transmission when no valid one remains (transmission_interface_loader.cpp,
        # TransmissionInterfaceLoader::load: "It contains no valid hardware interfaces").
        # Nothing that loads is lost, but a misspelt name (TX204) deserves a look.
        refused = " (ros_control refuses this transmission)" if not commands else ""
        result.warnings.append(
            f"joint '{joint.name}': hardware interface(s) {', '.join(unknown)} are not ones "
            f"ros_control knows{refused}; no ros2_control command interface for them"
        )


def _ros2_actuator(actuator: Member, result: Translation, **changes: Any) -> Member:
    if actuator.interfaces and not result.interfaces_taken:
        result.notes.append(
            f"actuator '{actuator.name}': <hardwareInterface> is not used by ros_control's "
            "loaders and has no place in ROS 2; dropped"
        )
    if "mechanical_reduction" not in changes:
        changes["mechanical_reduction"] = _retext(actuator.mechanical_reduction, parse_ros2)
    return replace(actuator, interfaces=(), **changes)


def _to_ros1(t: Transmission) -> Translation:
    result = Translation(t)
    if t.kind == "simple":
        joints, actuators = _simple_to_ros1(t, result)
    else:
        joints, actuators = _order_coupled(t, result)
        joints = tuple([_ros1_joint(j, result) for j in joints])
        actuators = tuple([_ros1_actuator(a, result, required=True) for a in actuators])
    for name, value in t.parameters:
        result.losses.append(f"transmission '{t.name}': <param name=\"{name}\"> {value} has no "
                             "place in ROS 1")
    result.transmission = replace(
        t,
        type=standard_type(t.kind),
        joints=joints,
        actuators=actuators,
        dialect="ros1",
        parameters=(),
        ros2_control=None,
    )
    return result


def _simple_to_ros1(t: Transmission, result: Translation) -> tuple[tuple[Member, ...], ...]:
    first = t.joints[0] if t.joints else None
    reduction = first.mechanical_reduction if first is not None else None
    if (reduction is None or reduction.value is None) and not is_expression(reduction):
        reduction = Number(value=1.0, text="1")  # ros2_control's default, required in ROS 1
    actuators = []
    for index, actuator in enumerate(t.actuators):
        if actuator.mechanical_reduction is not None:
            result.losses.append(
                f"actuator '{actuator.name}': <mechanical_reduction> "
                f"{actuator.mechanical_reduction.text} is ignored by ros2_control for simple "
                "transmissions"
            )
        actuators.append(_ros1_actuator(
            actuator, result,
            mechanical_reduction=_retext(reduction, parse_ros1) if index == 0 else None,
            role=_unless(actuator.role, "actuator1"),
        ))
    if not actuators:
        result.notes.append(
            f"transmission '{t.name}': no actuator; wrote 'actuator1' as ros2_control names it"
        )
        actuators.append(Member(name="actuator1", mechanical_reduction=reduction))
    joints = tuple([_ros1_joint(j, result, mechanical_reduction=None,
                                role=_unless(j.role, "joint1")) for j in t.joints])
    return joints, tuple(actuators)


def _unless(role: str | None, default: str) -> str | None:
    # ros_control ignores roles of simple transmissions; the ROS 2 default is not carried back.
    return None if role == default else role


def _ros1_joint(joint: Member, result: Translation, **changes: Any) -> Member:
    """``joint`` as ros_control reads it (``changes``: fields the caller sets itself)."""
    names = [ROS1_INTERFACE[c] for c in joint.interfaces if c in ROS1_INTERFACE]
    dropped = [c for c in joint.interfaces if c not in ROS1_INTERFACE]
    if dropped:
        result.notes.append(
            f"joint '{joint.name}': command interface(s) {', '.join(dropped)} have no ROS 1 "
            "hardware interface; dropped"
        )
    if not names and joint.state_interfaces:
        names = [ROS1_STATE_ONLY]
    if joint.read_only:
        result.losses.append(f"joint '{joint.name}': read_only has no place in ROS 1")
    if "mechanical_reduction" not in changes:
        changes["mechanical_reduction"] = _retext(_as_loaded(joint.mechanical_reduction, 1.0),
                                                  parse_ros1)
    return replace(joint, offset=_retext(_as_loaded(joint.offset, 0.0), parse_ros1),
                   interfaces=tuple(names), state_interfaces=(), read_only=False, **changes)


def _as_loaded(number: Number | None, default: float) -> Number | None:
    """ros2_control reads unparsable text as the default: carry that value, not the text."""
    if number is not None and number.value is None and not is_expression(number):
        return Number(value=default, text=format_float(default))
    return number


def _ros1_actuator(actuator: Member, result: Translation, *, required: bool = False,
                   **changes: Any) -> Member:
    """``actuator`` as ros_control reads it (``changes``: fields the caller sets itself).
    ``required``: ROS 1 refuses a coupled actuator without a reduction; ROS 2 meant 1.0."""
    if actuator.offset is not None:
        result.losses.append(
            f"actuator '{actuator.name}': <offset> {actuator.offset.text} is ignored by "
            "ros2_control and has no place in ROS 1"
        )
    if actuator.read_only:
        result.losses.append(f"actuator '{actuator.name}': read_only has no place in ROS 1")
    if "mechanical_reduction" not in changes:
        reduction = _retext(actuator.mechanical_reduction, parse_ros1)
        if required and (reduction is None or reduction.value is None) and not is_expression(
                reduction):
            reduction = Number(value=1.0, text="1")
        changes["mechanical_reduction"] = reduction
    return replace(actuator, offset=None, interfaces=(), state_interfaces=(), read_only=False,
                   **changes)
