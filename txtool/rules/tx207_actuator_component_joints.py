"""A transmission of an actuator component without exactly one joint: the parser refuses the robot.

What it does: reports a ``<transmission>`` of a ``<ros2_control type="actuator">`` block that
names no joint or more than one (of any type, coupled ones included: a differential or
four-bar transmission names two), at the transmission; and, at the ``<actuator>``, a
SimpleTransmission of such a block whose actuator is not named ``actuator1``.

Why it matters: for each transmission of an actuator component, ros2_control's parser throws
"There should be exactly one joint defined in this component but found N." unless it names one
joint: no hardware of the robot loads, and the controller manager (or the Gazebo plugin)
stops. It then appends an actuator named ``actuator1`` to the transmission; a SimpleTransmission
that already lists an actuator of another name is handed two actuator names, which its
``configure()`` refuses ("Actuator names given to transmissions should be identical"), so the
hardware plugin that configures it fails. Humble and every later distribution do the same.

Loader: ros2_control (ros-controls/ros2_control hardware_interface/src/component_parser.cpp
``auto_fill_transmission_interfaces``:670-685 @53b9999, :483-496 on the humble branch
@0941f73; transmission_interface/include/transmission_interface/simple_transmission.hpp
``configure``:197-219 @53b9999).

Failing example::

    <robot name="r">
      <ros2_control name="wrist" type="actuator">
        <hardware><plugin>my_hardware/WristActuator</plugin></hardware>
        <joint name="pitch"><command_interface name="position"/></joint>
        <joint name="roll"><command_interface name="position"/></joint>
        <transmission name="wrist_diff">
          <plugin>transmission_interface/DifferentialTransmission</plugin>
          <joint name="pitch" role="joint1"/>
          <joint name="roll" role="joint2"/>
          <actuator name="left" role="actuator1"/>
          <actuator name="right" role="actuator2"/>
        </transmission>
      </ros2_control>
    </robot>

Expected finding: ``6:5 error TX207 transmission 'wrist_diff' of actuator component 'wrist'
names 2 joints: ros2_control's parser throws "There should be exactly one joint defined in
this component but found 2." and no hardware of the robot loads``

Passing example::

    <robot name="r">
      <ros2_control name="wrist" type="system">
        <hardware><plugin>my_hardware/WristSystem</plugin></hardware>
        <joint name="pitch"><command_interface name="position"/></joint>
        <joint name="roll"><command_interface name="position"/></joint>
        <transmission name="wrist_diff">
          <plugin>transmission_interface/DifferentialTransmission</plugin>
          <joint name="pitch" role="joint1"/>
          <joint name="roll" role="joint2"/>
          <actuator name="left" role="actuator1"/>
          <actuator name="right" role="actuator2"/>
        </transmission>
      </ros2_control>
    </robot>

Fix: a transmission that couples joints belongs to a ``type="system"`` component; an
actuator component holds one joint and a SimpleTransmission without ``<actuator>`` (the parser
names it ``actuator1``).
"""

from __future__ import annotations

from collections.abc import Iterator

from txtool.lint.context import LintContext
from txtool.lint.problem import Problem
from txtool.lint.rule_helpers import in_actuator_component, opaque, per_transmission
from txtool.model.numbers import C_SPACE

CODE = "TX207"
NAME = "actuator-component-joints"
SEVERITY = "error"
FIXABLE = False

ADDED = "actuator1"  # the actuator the parser appends (component_parser.cpp:682-684)


@per_transmission
def check(ctx: LintContext) -> Iterator[Problem]:
    if not ctx.hints.components:
        return
    for tx in ctx.facts:
        if not in_actuator_component(tx) or opaque(ctx, tx.element):
            continue
        component = tx.component.get("name") or ""  # type: ignore[union-attr]
        count = len(tx.joints)
        if count != 1:
            yield ctx.problem(
                CODE, tx.element,
                f"{tx.label} of actuator component '{component}' names {count} joints: "
                "ros2_control's parser throws \"There should be exactly one joint defined in "
                f"this component but found {count}.\" and no hardware of the robot loads",
                refuses_whole=True)
            continue
        if tx.kind != "simple":
            continue
        for ref in tx.actuators:
            name = ref.name.strip(C_SPACE)
            if name == ADDED or ("$" in name and ctx.unknown(name)):
                continue
            yield ctx.problem(
                CODE, ref.element,
                f"actuator '{ref.name}' of {tx.label}: ros2_control's parser appends actuator "
                f"'{ADDED}' to a transmission of actuator component '{component}', and "
                "configure() refuses two actuator names (\"Actuator names given to "
                "transmissions should be identical\"); leave the <actuator> out")
            break
