"""A transmission drives a joint of type ``fixed``.

What it does: reports a transmission ``<joint>`` that names a URDF ``<joint type="fixed">`` of
the robot (only when the document is a robot with joints). Custom transmission types are not
checked: some name a fixed joint on purpose (franka_hw/FrankaModelInterface uses the flange as
its ``tip``).

Why it matters: a fixed joint has no degree of freedom: there is no position to read and
nothing to command. Simulators merge fixed joints away (gazebo_ros_control then reports the
joint as "not in the gazebo model" and stops), and a hardware plugin would command a joint that
cannot move. ros2_control (master) refuses a fixed joint declared in a ``<ros2_control>`` block
outright: "Joint 'J' is of type 'fixed'. Fixed joints do not make sense in ros2_control."
Usually the joint type or the transmission's joint name is wrong.

Loader: gazebo_ros_pkgs gazebo_ros_control/src/default_robot_hw_sim.cpp ``initSim``
@01c3a2c; ros-controls/ros2_control hardware_interface/src/component_parser.cpp
``parse_control_resources_from_urdf`` (master).

Failing example::

    <robot name="r">
      <link name="a"/>
      <link name="b"/>
      <joint name="tool_mount" type="fixed">
        <parent link="a"/><child link="b"/>
      </joint>
      <transmission name="t">
        <type>transmission_interface/SimpleTransmission</type>
        <joint name="tool_mount">
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
        </joint>
        <actuator name="m"><mechanicalReduction>1</mechanicalReduction></actuator>
      </transmission>
    </robot>

Expected finding: ``9:5 error TX201 joint 'tool_mount' of transmission 't' is a fixed joint: it
cannot move, so the transmission has nothing to read or command``

Passing example::

    <robot name="r">
      <link name="a"/>
      <link name="b"/>
      <joint name="tool_mount" type="revolute">
        <parent link="a"/><child link="b"/><axis xyz="0 0 1"/>
        <limit lower="-1" upper="1" effort="10" velocity="1"/>
      </joint>
      <transmission name="t">
        <type>transmission_interface/SimpleTransmission</type>
        <joint name="tool_mount">
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
        </joint>
        <actuator name="m"><mechanicalReduction>1</mechanicalReduction></actuator>
      </transmission>
    </robot>

Fix: give the joint its real type (``revolute``, ``prismatic``, ``continuous``), or name the
joint the actuator moves.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator

from lxml import etree

from txtool.dialects.read import enclosing_component
from txtool.lint.context import LintContext
from txtool.lint.problem import Problem
from txtool.lint.rule_helpers import children, label, robot_joints_of_transmissions

CODE = "TX201"
NAME = "fixed-joint"
SEVERITY = "error"
FIXABLE = False


def check(ctx: LintContext) -> Iterable[Problem]:
    if not _any_fixed(ctx.joint_elements):
        return ()  # the common case: no joint of the robot is fixed
    return _fixed(ctx)


def _fixed(ctx: LintContext) -> Iterator[Problem]:
    for found, joint, robot in robot_joints_of_transmissions(ctx):
        if robot.get("type") != "fixed":  # JointInfo.is_fixed, without reading the joint
            continue
        info = ctx.joints[joint.get("name", "")]
        throws = _declared_by_component(found.element, info.name)
        effect = (
            "ros2_control throws \"Fixed joints do not make sense in ros2_control\""
            if throws
            else "it cannot move, so the transmission has nothing to read or command"
        )
        yield ctx.problem(
            CODE, joint, f"joint '{info.name}' of {label(found)} is a fixed joint: {effect}",
            refuses_whole=throws,
        )


def _any_fixed(joints: dict[str, etree._Element]) -> bool:
    for element in joints.values():  # noqa: SIM110 (a loop costs less than a generator)
        if element.get("type") == "fixed":
            return True
    return False


def _declared_by_component(transmission: etree._Element, joint: str) -> bool:
    component = enclosing_component(transmission)
    return component is not None and any(
        j.get("name") == joint for j in children(component, "joint")
    )
