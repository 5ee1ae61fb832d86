"""The ROS 1 four-bar effort map does not conserve power.

What it does: reports every ROS 1 ``transmission_interface/FourBarLinkageTransmission``; the
same transmission in a ROS 2 ``<ros2_control>`` block, or any other type, is not reported.

Why it matters: ros_control's four-bar maps efforts with
``e_j1 = jr1 * (e_a1 * ar1 - e_a0 * ar0 * jr0)``, which is not the transpose of its own
velocity map, so joint power differs from actuator power (ros_control#523, still open).
ros2_control fixed the same formulas in PR #1837 (issue #1746) to ``tau_a = J^T tau_j``.
Positions and velocities agree between the two; efforts, and every effort-controlled joint, do
not, so a robot behaves differently after migrating to ROS 2 with the same reductions. This is
informational: nothing in the file is wrong, but effort gains tuned on ROS 1 need re-checking
on ROS 2 (``txtool map`` shows both maps).

Loader: ros_control (ros-controls/ros_control
transmission_interface/include/transmission_interface/four_bar_linkage_transmission.h
``FourBarLinkageTransmission::actuatorToJointEffort``); ros2_control (ros-controls/ros2_control
transmission_interface/include/transmission_interface/four_bar_linkage_transmission.hpp
``actuator_to_joint``).

Failing example::

    <robot name="r">
      <transmission name="wrist">
        <type>transmission_interface/FourBarLinkageTransmission</type>
        <joint name="j1">
          <role>joint1</role><mechanicalReduction>1</mechanicalReduction>
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
        </joint>
        <joint name="j2">
          <role>joint2</role><mechanicalReduction>1</mechanicalReduction>
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

Expected finding: ``2:3 info TX402 four-bar transmission 'wrist': ros_control's effort map does
not conserve power (ros_control#523) and differs from ros2_control's since PR #1837, so efforts
change when the robot moves to ROS 2``

Passing example::

    <robot name="r">
      <transmission name="wrist">
        <type>transmission_interface/DifferentialTransmission</type>
        <joint name="j1">
          <role>joint1</role><mechanicalReduction>1</mechanicalReduction>
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
        </joint>
        <joint name="j2">
          <role>joint2</role><mechanicalReduction>1</mechanicalReduction>
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

Fix: nothing to change in the file; when porting to ROS 2, re-check effort gains and limits
with ``txtool map --effort-convention``.
"""

from __future__ import annotations

from collections.abc import Iterator

from txtool.lint.context import LintContext
from txtool.lint.problem import Problem
from txtool.lint.rule_helpers import per_transmission

CODE = "TX402"
NAME = "four-bar-effort-ros1"
SEVERITY = "info"
FIXABLE = False


@per_transmission
def check(ctx: LintContext) -> Iterator[Problem]:
    for tx in ctx.facts:
        if not tx.ros1 or tx.kind != "four_bar":
            continue
        found = tx.found
        t = found.transmission
        yield ctx.problem(
            CODE,
            found.element,
            f"four-bar transmission '{t.name}': ros_control's effort map does not conserve "
            "power (ros_control#523) and differs from ros2_control's since PR #1837, so "
            "efforts change when the robot moves to ROS 2",
        )
