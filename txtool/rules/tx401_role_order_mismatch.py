"""A coupled ROS 2 transmission whose values ros2_control binds to the wrong joint.

What it does: reports a ROS 2 Differential or FourBarLinkage transmission (its first two joints
and first two actuators, separately) whose members are written in an XML order that differs
from the order of their names (``wrist_roll`` before ``wrist_flex``), or whose ``role`` values
(``joint1``/``joint2``, ``actuator1``/``actuator2``) run against the XML order, and therefore
against the name order too.

Why it matters: ros2_control's loaders take ``mechanical_reduction`` and ``offset`` by XML
position (``joints.at(0)``, ``joints.at(1)``; the roles are ignored, ros2_control#3382), while
``configure`` orders the joint and actuator handles by name (a ``std::set``,
ros2_control#1745). When the two orders differ, the values written on one joint are applied to
the other. When the roles run against the XML and name order, each value stays on the joint it
is written on, but ros2_control drives the first joint as ``joint1`` whatever its role says
(in a differential, which joint is the sum and which the difference). ros_control (ROS 1)
takes the values by role and the data in XML order (TX404).

Loader: ros2_control (ros-controls/ros2_control
transmission_interface/src/differential_transmission_loader.cpp
``DifferentialTransmissionLoader::load``;
transmission_interface/include/transmission_interface/differential_transmission.hpp
``configure``).

Failing example::

    <robot name="r">
      <ros2_control name="HW" type="system">
        <hardware><plugin>mock_components/GenericSystem</plugin></hardware>
        <joint name="wrist_flex"><command_interface name="position"/></joint>
        <joint name="wrist_roll"><command_interface name="position"/></joint>
        <transmission name="wrist">
          <plugin>transmission_interface/DifferentialTransmission</plugin>
          <joint name="wrist_roll" role="joint1">
            <mechanical_reduction>2</mechanical_reduction>
          </joint>
          <joint name="wrist_flex" role="joint2">
            <mechanical_reduction>4</mechanical_reduction>
          </joint>
          <actuator name="m1" role="actuator1"/>
          <actuator name="m2" role="actuator2"/>
        </transmission>
      </ros2_control>
    </robot>

Expected finding: ``8:7 error TX401 transmission 'wrist': ros2_control binds the joint
reductions and offsets in XML order (wrist_roll, wrist_flex) but orders the joint handles by
name (wrist_flex, wrist_roll), so the values written on 'wrist_roll' land on 'wrist_flex'``

Passing example::

    <robot name="r">
      <ros2_control name="HW" type="system">
        <hardware><plugin>mock_components/GenericSystem</plugin></hardware>
        <joint name="wrist_flex"><command_interface name="position"/></joint>
        <joint name="wrist_roll"><command_interface name="position"/></joint>
        <transmission name="wrist">
          <plugin>transmission_interface/DifferentialTransmission</plugin>
          <joint name="wrist_flex" role="joint1">
            <mechanical_reduction>4</mechanical_reduction>
          </joint>
          <joint name="wrist_roll" role="joint2">
            <mechanical_reduction>2</mechanical_reduction>
          </joint>
          <actuator name="m1" role="actuator1"/>
          <actuator name="m2" role="actuator2"/>
        </transmission>
      </ros2_control>
    </robot>

Fix: write the members in the order of their names, with the roles in that order too
(``wrist_flex`` as ``joint1`` before ``wrist_roll`` as ``joint2``); ``txtool show --effective``
shows which value lands on which joint.
"""

from __future__ import annotations

from collections.abc import Iterator

from txtool.lint.context import LintContext
from txtool.lint.problem import Problem
from txtool.lint.rule_helpers import coupled_groups, label, per_transmission
from txtool.model.core import Member

CODE = "TX401"
NAME = "role-order-mismatch"
SEVERITY = "error"
FIXABLE = False


@per_transmission
def check(ctx: LintContext) -> Iterator[Problem]:
    for tx in ctx.facts:
        if tx.ros1 or tx.kind not in ("differential", "four_bar"):
            continue
        found = tx.found
        for noun, members, elements, roles in coupled_groups(tx):
            if any(ctx.unknown(m.name) for m in members[:2]):
                continue
            message = _mismatch(noun, members[:2], roles)
            if message is not None:
                yield ctx.problem(CODE, elements[0], f"{label(found)}: {message}")


def _mismatch(noun: str, members: tuple[Member, ...], roles: tuple[str, str]) -> str | None:
    names = [m.name for m in members]
    if len(names) < 2 or names[0] == names[1]:
        return None
    values = "reductions and offsets" if noun == "joint" else "reductions"
    by_name = sorted(names)
    if names != by_name:
        return (
            f"ros2_control binds the {noun} {values} in XML order ({names[0]}, {names[1]}) "
            f"but orders the {noun} handles by name ({by_name[0]}, {by_name[1]}), so the "
            f"values written on '{names[0]}' land on '{names[1]}'"
        )
    written = [m.role for m in members]
    if written == [roles[1], roles[0]]:
        return (
            f"the {noun} roles ({written[0]}, {written[1]}) run against the XML and name "
            f"order ({names[0]}, {names[1]}): ros2_control ignores roles and drives "
            f"'{names[0]}' as {roles[0]}, against its role"
        )
    return None
