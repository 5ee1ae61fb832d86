"""The joints of a transmission cannot share its interfaces.

What it does: reports, in ROS 1, a transmission whose joints do not all list the same set of
``<hardwareInterface>`` names (any order; joints without any are left to other rules); in
ROS 2, a transmission joint that the enclosing ``<ros2_control>`` component declares without
any ``<command_interface>`` or ``<state_interface>`` (``<joint name="joint1"/>``).

Why it matters: ros_control's transmission loader refuses a transmission whose joints differ:
"Failed to load transmission 'T'. It has joints with different hardware interfaces. This is
currently unsupported." ros2_control copies the interface names of the component's
``<joint>`` into the transmission; a joint with none gives the transmission no handle, and
configuring it throws "None of the provided joint handles are valid or from the required
interfaces".

Loader: ros_control (ros-controls/ros_control
transmission_interface/src/transmission_interface_loader.cpp ``TransmissionInterfaceLoader::load``
@0a09467); ros2_control (ros-controls/ros2_control
transmission_interface/include/transmission_interface/simple_transmission.hpp and
differential_transmission.hpp ``configure``).

Failing example::

    <robot name="r">
      <transmission name="wrist">
        <type>transmission_interface/DifferentialTransmission</type>
        <joint name="flex">
          <role>joint1</role>
          <hardwareInterface>hardware_interface/PositionJointInterface</hardwareInterface>
        </joint>
        <joint name="roll">
          <role>joint2</role>
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
        </joint>
        <actuator name="m1">
          <role>actuator1</role><mechanicalReduction>50</mechanicalReduction>
        </actuator>
        <actuator name="m2">
          <role>actuator2</role><mechanicalReduction>50</mechanicalReduction>
        </actuator>
      </transmission>
    </robot>

Expected finding: ``8:5 error TX203 joint 'roll' of transmission 'wrist' lists hardware
interfaces [hardware_interface/EffortJointInterface] but joint 'flex' lists
[hardware_interface/PositionJointInterface]: ros_control refuses joints with different hardware
interfaces``

Passing example::

    <robot name="r">
      <transmission name="wrist">
        <type>transmission_interface/DifferentialTransmission</type>
        <joint name="flex">
          <role>joint1</role>
          <hardwareInterface>hardware_interface/PositionJointInterface</hardwareInterface>
        </joint>
        <joint name="roll">
          <role>joint2</role>
          <hardwareInterface>hardware_interface/PositionJointInterface</hardwareInterface>
        </joint>
        <actuator name="m1">
          <role>actuator1</role><mechanicalReduction>50</mechanicalReduction>
        </actuator>
        <actuator name="m2">
          <role>actuator2</role><mechanicalReduction>50</mechanicalReduction>
        </actuator>
      </transmission>
    </robot>

Fix: list the same interfaces in every joint of the transmission (ROS 1), or declare the
joint's interfaces in the ``<ros2_control>`` component (ROS 2).
"""

from __future__ import annotations

from collections.abc import Iterator

from lxml import etree

from txtool.dialects.read import Found, enclosing_component
from txtool.lint.context import LintContext
from txtool.lint.problem import Problem
from txtool.lint.rule_helpers import children, label, members, opaque, per_transmission

CODE = "TX203"
NAME = "interface-mismatch"
SEVERITY = "error"
FIXABLE = False


@per_transmission
def check(ctx: LintContext) -> Iterator[Problem]:
    for tx in ctx.facts:
        if tx.ros1:
            if len(tx.joints) > 1 and not tx.own_loader:  # one joint agrees with itself
                yield from _check_ros1(ctx, tx.found)
        elif tx.component is not None:  # else no component declares its joints
            yield from _check_ros2(ctx, tx.found)


def _check_ros1(ctx: LintContext, found: Found) -> Iterator[Problem]:
    first: tuple[str, frozenset[str]] | None = None
    for ref in members(found):
        interfaces = frozenset(ref.member.interfaces)
        if ref.noun != "joint" or not interfaces or opaque(ctx, ref.element):
            continue
        if any(ctx.unknown(name) for name in interfaces):
            continue
        if first is None:
            first = (ref.name, interfaces)
        elif interfaces != first[1]:
            yield ctx.problem(
                CODE,
                ref.element,
                f"joint '{ref.name}' of {label(found)} lists hardware interfaces "
                f"{_listing(interfaces)} but joint '{first[0]}' lists {_listing(first[1])}: "
                "ros_control refuses joints with different hardware interfaces",
            )


def _listing(interfaces: frozenset[str]) -> str:
    return "[" + ", ".join(sorted(interfaces)) + "]"


def component_joint(
    ctx: LintContext, found: Found, name: str
) -> tuple[etree._Element, etree._Element] | None:
    """The enclosing ``<ros2_control>`` and its ``<joint name=name>``, when both are knowable."""
    component = enclosing_component(found.element)
    if component is None:
        return None
    joint = _joints_of(ctx, component).get(name)
    if joint is None or opaque(ctx, joint):
        return None
    return component, joint


def _joints_of(ctx: LintContext, component: etree._Element) -> dict[str, etree._Element]:
    """A block's ``<joint>`` elements by name (the first of a repeated name), found once per
    block: a block generated for thousands of transmissions is asked about each of them. Only
    the last block's are kept: a block's transmissions come one after another."""
    known = ctx.memo.setdefault("component joints", {})
    joints = known.get(component)
    if joints is None:
        known.clear()
        joints = known[component] = {}
        for joint in children(component, "joint"):
            joints.setdefault(joint.get("name"), joint)
    return joints


def declared_interfaces(joint: etree._Element) -> list[str]:
    """Command then state interface names of a component joint, without repeats."""
    names = [
        child.get("name", "")
        for tag in ("command_interface", "state_interface")
        for child in children(joint, tag)
    ]
    return list(dict.fromkeys(names))


def _check_ros2(ctx: LintContext, found: Found) -> Iterator[Problem]:
    for ref in members(found):
        pair = component_joint(ctx, found, ref.name) if ref.noun == "joint" else None
        if pair is None or declared_interfaces(pair[1]):
            continue
        yield ctx.problem(
            CODE,
            ref.element,
            f"joint '{ref.name}' of {label(found)} has no command or state interface "
            f"in <ros2_control> '{pair[0].get('name', '')}': the transmission gets no handle "
            "for it and ros2_control cannot configure it",
        )
