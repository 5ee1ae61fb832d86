"""A ROS 2 transmission joint or actuator whose ``read_only`` is not ``true`` or ``false``.

What it does: reports a ``read_only`` attribute of a ROS 2 transmission's ``<joint>`` or
``<actuator>`` that ros2_control does not read as a boolean: ``1``, ``yes``, or a no-break
space around the word. The case does not matter (``True`` is read); a missing attribute is
fine (the default is false).

Why it matters: ros2_control throws "Input string : 'x' is not a valid boolean value.
Expected 'true' or 'false'.", the exception leaves the component parser, and the whole
``robot_description`` fails to load.

Loader: ros2_control strips the attribute of C whitespace and reads it with ``parse_bool``,
which lower-cases the text (ASCII) and accepts exactly ``true`` or ``false``
(ros-controls/ros2_control hardware_interface/src/component_parser.cpp:558-560 and
hardware_interface/src/lexical_casts.cpp:134 @53b9999).

Failing example::

    <robot name="r">
      <ros2_control name="arm" type="system">
        <hardware><plugin>mock_components/GenericSystem</plugin></hardware>
        <joint name="j"><command_interface name="position"/></joint>
        <transmission name="t">
          <plugin>transmission_interface/SimpleTransmission</plugin>
          <joint name="j" role="joint1"/>
          <actuator name="m" role="actuator1" read_only="yes"/>
        </transmission>
      </ros2_control>
    </robot>

Expected finding: ``8:7 error TX112 actuator 'm' of transmission 't' has read_only="yes":
ros2_control's parse_bool accepts only true or false (any case) and throws, so the robot
description fails to load``

Passing example::

    <robot name="r">
      <ros2_control name="arm" type="system">
        <hardware><plugin>mock_components/GenericSystem</plugin></hardware>
        <joint name="j"><command_interface name="position"/></joint>
        <transmission name="t">
          <plugin>transmission_interface/SimpleTransmission</plugin>
          <joint name="j" role="joint1"/>
          <actuator name="m" role="actuator1" read_only="True"/>
        </transmission>
      </ros2_control>
    </robot>

Fix: write ``read_only="true"`` or ``read_only="false"``, or leave the attribute out.
"""

from __future__ import annotations

from collections.abc import Iterator

from txtool.lint.context import LintContext
from txtool.lint.problem import Problem
from txtool.lint.rule_helpers import label, per_transmission
from txtool.model.numbers import C_SPACE

CODE = "TX112"
NAME = "invalid-read-only"
SEVERITY = "error"
FIXABLE = False

_BOOLEANS = ("true", "false")


def valid_bool(text: str) -> bool:
    """What ``hardware_interface::parse_bool`` accepts: true/false in any ASCII case."""
    return text.isascii() and text.lower() in _BOOLEANS


@per_transmission
def check(ctx: LintContext) -> Iterator[Problem]:
    for tx in ctx.facts:
        if tx.ros1:
            continue
        found = tx.found
        for ref in tx.members:
            value = ref.element.get("read_only")
            if value is None or ctx.unknown(value) or valid_bool(value.strip(C_SPACE)):
                continue
            yield ctx.problem(
                CODE,
                ref.element,
                f"{ref.noun} '{ref.name}' of {label(found)} has read_only=\"{value}\": "
                "ros2_control's parse_bool accepts only true or false (any case) and throws, "
                "so the robot description fails to load",
                refuses_whole=True,
            )
