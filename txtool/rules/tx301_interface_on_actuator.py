"""The hardware interface sits only on the actuator.

What it does: reports a ROS 1 transmission ``<joint>`` with no (non-empty)
``<hardwareInterface>`` while an ``<actuator>`` of the same transmission has one: the placement
from before ROS Indigo. TX110 (missing-interface) reports the same joints as errors; this rule
adds the cause and the fix. Families with loaders of their own (``pr2_mechanism_model/``,
``sr_mechanism_model/``) are skipped.

Why it matters: since Indigo, ros_control requires the interface on the joint (ros_control#177):
the parser logs "No valid hardware interface element found in joint 'J'" and skips the joint,
and a transmission left without joints fails to load. gazebo_ros_control still falls back to
the actuator's interface with a warning (gazebo_ros_pkgs#184), so such robots often work in
simulation only.

Loader: ros_control (ros-controls/ros_control transmission_interface/src/transmission_parser.cpp
:155-175 @14e64ea); gazebo_ros_pkgs gazebo_ros_control/src/default_robot_hw_sim.cpp
``initSim`` @01c3a2c.

Failing example::

    <robot name="r">
      <transmission name="tran1">
        <type>transmission_interface/SimpleTransmission</type>
        <joint name="joint1"/>
        <actuator name="motor1">
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
          <mechanicalReduction>1</mechanicalReduction>
        </actuator>
      </transmission>
    </robot>

Expected finding: ``4:5 warning TX301 joint 'joint1' of transmission 'tran1' has no
<hardwareInterface>, only actuator 'motor1' has: ros_control (since Indigo) skips the joint ('No
valid hardware interface')``

Passing example::

    <robot name="r">
      <transmission name="tran1">
        <type>transmission_interface/SimpleTransmission</type>
        <joint name="joint1">
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
        </joint>
        <actuator name="motor1">
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
          <mechanicalReduction>1</mechanicalReduction>
        </actuator>
      </transmission>
    </robot>

Fix: ``txtool migrate --write`` *copies* the actuator's ``<hardwareInterface>`` elements into
the joint (as its first children, text kept verbatim, so ``${...}`` survives), as in the
passing example. The actuator keeps its copy: ros_control accepts an actuator interface as
optional, and tools that still read it there (older gazebo_ros_control) keep working. When the
actuators list different interfaces the right choice is ambiguous and the problem is reported
but not fixed.
"""

from __future__ import annotations

import copy
from collections.abc import Iterator

from lxml import etree

from txtool.dialects.read import detect_dialect, ros1_type, text_of, transmission_elements
from txtool.lint.context import LintContext
from txtool.lint.problem import Problem
from txtool.lint.rule_helpers import (
    OWN_LOADER_FAMILIES,
    children,
    is_xacro,
    label,
    per_transmission,
)
from txtool.rules.tx302_legacy_type_attribute import insert_child

CODE = "TX301"
NAME = "interface-on-actuator"
SEVERITY = "warning"
FIXABLE = True


def _interfaces(member: etree._Element) -> list[etree._Element]:
    return [h for h in children(member, "hardwareInterface") if (text_of(h) or "").strip()]


def _bare_joints(transmission: etree._Element) -> list[etree._Element]:
    """Joints without an interface, when some actuator of the transmission has one.

    A joint whose children come partly from xacro (``<xacro:insert_block>``, conditionals)
    may get its interface there, so it does not count as bare.
    """
    if not any(_interfaces(a) for a in children(transmission, "actuator")):
        return []
    return [
        joint
        for joint in children(transmission, "joint")
        if not _interfaces(joint) and not any(is_xacro(child) for child in joint)
    ]


@per_transmission
def check(ctx: LintContext) -> Iterator[Problem]:
    for tx in ctx.facts:
        if not tx.ros1 or tx.own_loader or not tx.actuator_interfaces:
            continue  # no actuator names an interface: no joint is bare (see _bare_joints)
        found = tx.found
        joints = _bare_joints(found.element)
        if not joints:
            continue
        actuator = next(a for a in children(found.element, "actuator") if _interfaces(a))
        sim = ctx.gazebo_sim
        also = (f"; {sim.describe()} takes the actuator's, with a warning"
                if sim is not None and sim.default else "")
        for joint in joints:
            yield ctx.problem(
                CODE,
                joint,
                f"joint '{joint.get('name', '')}' of {label(found)} has no "
                f"<hardwareInterface>, only actuator '{actuator.get('name', '')}' has: "
                f"ros_control (since Indigo) skips the joint ('No valid hardware interface'){also}",
            )


def _shared_interfaces(transmission: etree._Element) -> list[etree._Element] | None:
    """The actuators' interface elements when all actuators that have some agree."""
    lists = [_interfaces(a) for a in children(transmission, "actuator")]
    lists = [found for found in lists if found]
    texts = {frozenset((text_of(h) or "").strip() for h in found) for found in lists}
    return lists[0] if len(texts) == 1 else None


def fix(root: etree._Element) -> int:
    fixed = 0
    for transmission in transmission_elements(root):
        if detect_dialect(transmission) != "ros1":
            continue
        if ros1_type(transmission).startswith(OWN_LOADER_FAMILIES):
            continue
        joints = _bare_joints(transmission)
        source = _shared_interfaces(transmission) if joints else None
        if source is None:
            continue
        for joint in joints:
            for index, interface in enumerate(source):
                duplicate = copy.deepcopy(interface)
                duplicate.tail = None
                insert_child(joint, duplicate, index)
            fixed += 1
    return fixed
