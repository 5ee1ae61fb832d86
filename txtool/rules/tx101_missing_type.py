"""A transmission without a type: no ``<type>`` (ROS 1) or ``<plugin>`` (ROS 2), or an empty one.

What it does: reports a transmission with no ``<type>`` (ROS 1) or ``<plugin>`` (ROS 2), or
an empty one. A ROS 1 transmission that has only the pre-Hydro ``type=`` attribute is left to
TX302.

Why it matters: ros_control logs "No type element found in transmission 'T'." (or "Skipping
empty type element") and skips the transmission. ros2_control throws "Missing <plugin> tag of
<transmission> element for 'T' in your URDF." for a missing ``<plugin>``; an empty one only
prints "text not specified in the plugin tag" and leaves an empty type no loader matches.

Loader: ros_control (ros-controls/ros_control transmission_interface/src/transmission_parser.cpp
``TransmissionParser::parse``); ros2_control (ros-controls/ros2_control
hardware_interface/src/component_parser.cpp ``parse_transmission_from_xml``).

Failing example::

    <robot name="r">
      <ros2_control name="arm" type="system">
        <hardware><plugin>mock_components/GenericSystem</plugin></hardware>
        <joint name="j"><command_interface name="position"/></joint>
        <transmission name="t">
          <joint name="j" role="joint1"/>
          <actuator name="m" role="actuator1"/>
        </transmission>
      </ros2_control>
    </robot>

Expected finding: ``5:5 error TX101 transmission 't' has no <plugin>: ros2_control throws
"Missing <plugin> tag of <transmission> element"``

Passing example::

    <robot name="r">
      <ros2_control name="arm" type="system">
        <hardware><plugin>mock_components/GenericSystem</plugin></hardware>
        <joint name="j"><command_interface name="position"/></joint>
        <transmission name="t">
          <plugin>transmission_interface/SimpleTransmission</plugin>
          <joint name="j" role="joint1"/>
          <actuator name="m" role="actuator1"/>
        </transmission>
      </ros2_control>
    </robot>

Fix: write the type: ``<plugin>transmission_interface/SimpleTransmission</plugin>`` in ROS 2,
``<type>transmission_interface/SimpleTransmission</type>`` in ROS 1.
"""

from __future__ import annotations

from collections.abc import Iterator

from txtool.lint.context import LintContext
from txtool.lint.problem import Problem
from txtool.lint.rule_helpers import per_transmission

CODE = "TX101"
NAME = "missing-type"
SEVERITY = "error"
FIXABLE = False


@per_transmission
def check(ctx: LintContext) -> Iterator[Problem]:
    for tx in ctx.facts:
        element = tx.type_element
        ros1 = tx.ros1
        if element is None:
            if ros1 and tx.element.get("type") is not None:
                continue  # the legacy attribute form: TX302
            if ros1:
                message = f"{tx.label} has no <type>: ros_control skips it"
            else:
                message = (
                    f"{tx.label} has no <plugin>: ros2_control throws "
                    '"Missing <plugin> tag of <transmission> element"'
                )
            yield ctx.problem(CODE, tx.element, message, refuses_whole=not ros1)
        elif not (element.text or "").strip():
            if ros1:
                message = f"{tx.label} has an empty <type>: ros_control skips it"
            else:
                message = f"{tx.label} has an empty <plugin>: no ros2_control loader matches it"
            yield ctx.problem(CODE, element, message)
