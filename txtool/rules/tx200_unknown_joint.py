"""A transmission names a joint that does not exist.

What it does: reports a ``<joint name="...">`` of a transmission that is not a ``<joint>`` of
the robot (when the document is a robot with joints; a bare ``<transmission>`` fragment or a
macro library is not cross-checked), or, in ROS 2, not a ``<joint>`` of the enclosing
``<ros2_control>`` component. Names still holding xacro expressions (``${prefix}joint1``) are
matched as patterns, never reported.

Why it matters: ros2_control copies each transmission joint's interfaces from the component; a
joint the component does not declare makes the parser throw ``Error while parsing 'HW'.
Transmission 'T' declared joint 'J' is not available in component 'HW'.`` and nothing of the
robot loads. The parser strips both names of spaces first (``name=" j1 "`` is ``j1``). In ROS 1
a transmission joint that is not in the robot has no joint to drive (gazebo_ros_control refuses
it as "not in the gazebo model").

Loader: ros2_control (ros-controls/ros2_control hardware_interface/src/component_parser.cpp
``get_attribute_value``:133 and ``auto_fill_transmission_interfaces`` @53b9999);
gazebo_ros_pkgs gazebo_ros_control/src/default_robot_hw_sim.cpp ``initSim`` @01c3a2c.

Failing example::

    <robot name="r">
      <ros2_control name="RRBot" type="system">
        <hardware><plugin>mock_components/GenericSystem</plugin></hardware>
        <joint name="joint1"><command_interface name="position"/></joint>
        <transmission name="transmission1">
          <plugin>transmission_interface/SimpleTransmission</plugin>
          <joint name="joint31415" role="joint1"/>
          <actuator name="motor1" role="actuator1"/>
        </transmission>
      </ros2_control>
    </robot>

Expected finding: ``7:7 error TX200 joint 'joint31415' of transmission 'transmission1' is not a
<joint> of <ros2_control> 'RRBot': ros2_control throws "declared joint 'joint31415' is not
available in component"``

Passing example::

    <robot name="r">
      <ros2_control name="RRBot" type="system">
        <hardware><plugin>mock_components/GenericSystem</plugin></hardware>
        <joint name="joint1"><command_interface name="position"/></joint>
        <transmission name="transmission1">
          <plugin>transmission_interface/SimpleTransmission</plugin>
          <joint name="joint1" role="joint1"/>
          <actuator name="motor1" role="actuator1"/>
        </transmission>
      </ros2_control>
    </robot>

Fix: name the URDF joint the transmission drives (and, in ROS 2, declare it in the
``<ros2_control>`` component with its interfaces).
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Iterator

from lxml import etree

from txtool.lint.context import LintContext
from txtool.lint.facts import Facts
from txtool.lint.problem import Problem
from txtool.lint.rule_helpers import children, member_names, opaque
from txtool.model.numbers import C_SPACE

CODE = "TX200"
NAME = "unknown-joint"
SEVERITY = "error"
FIXABLE = False

_EXPRESSION = re.compile(r"\$\{[^}]*\}|\$\([^)]*\)")


class Names:
    """Joint names, some possibly written with xacro expressions (matched as patterns)."""

    def __init__(self, names: Iterable[str]) -> None:
        self.exact = set(names)
        self.patterns = [_as_pattern(n) for n in self.exact if "$" in n and _EXPRESSION.search(n)]

    def __contains__(self, name: object) -> bool:
        if name in self.exact:
            return True
        return isinstance(name, str) and any(p.fullmatch(name) for p in self.patterns)


def _as_pattern(text: str) -> re.Pattern[str]:
    parts = _EXPRESSION.split(text)
    return re.compile(".*".join(re.escape(part) for part in parts), re.DOTALL)


def check(ctx: LintContext) -> Iterable[Problem]:
    if not ctx.hints.components and (not ctx.is_robot or _all_known(ctx)):
        return ()  # the common case: no component, every joint named is the robot's
    return _unknown(ctx)


def _unknown(ctx: LintContext) -> Iterator[Problem]:
    robot_joints = Names(ctx.joint_elements) if ctx.is_robot else None
    components: dict[etree._Element, tuple[str, Names] | None] = {}
    for tx in ctx.facts:
        declared = _component_joints(ctx, tx, components) if tx.component is not None else None
        for ref in tx.joints:
            name = ref.name  # the element's name attribute, or ""
            joint = ref.element
            if not name or ("$" in name and ctx.unknown(name)):
                continue
            # ros2_control's parser strips the names (component_parser.cpp
            # get_attribute_value:133 @53b9999) before comparing them
            stripped = name.strip(C_SPACE) if tx.component is not None else name
            if declared is not None and stripped not in declared[1]:
                yield ctx.problem(
                    CODE,
                    joint,
                    f"joint '{name}' of {tx.label} is not a <joint> of <ros2_control> "
                    f"'{declared[0]}': ros2_control throws \"declared joint '{name}' is not "
                    "available in component\"",
                    refuses_whole=True,
                )
            elif robot_joints is not None and stripped not in robot_joints.exact and (
                stripped not in robot_joints
            ):
                yield ctx.problem(
                    CODE,
                    joint,
                    f"joint '{name}' of {tx.label} is not a <joint> of the robot: the "
                    "loader has no joint to bind it to",
                )


def _all_known(ctx: LintContext) -> bool:
    """Every joint name of every transmission is one of the robot's joints, as written."""
    return ctx.joint_elements.keys() >= set(member_names(ctx)[0])


def _component_joints(
    ctx: LintContext, tx: Facts, seen: dict[etree._Element, tuple[str, Names] | None]
) -> tuple[str, Names] | None:
    """Name and joint names of the enclosing component, None if none or not knowable; ``seen``
    keeps the last component's (a component's transmissions come one after another)."""
    component = tx.component
    if component is None or opaque(ctx, component):
        return None
    if component not in seen:
        seen.clear()
        names = Names(j.get("name", "").strip(C_SPACE) for j in children(component, "joint"))
        seen[component] = (component.get("name", ""), names)
    return seen[component]
