"""A ROS 2 Gazebo plugin that refuses this robot: it has no ``<ros2_control>`` element.

What it does: reports a robot that names gazebo_ros2_control (``libgazebo_ros2_control.so``)
or gz_ros2_control (``gz_ros2_control-system``, ``ign_ros2_control-system`` before Jazzy) as a
``<gazebo>`` plugin, and has no ``<ros2_control>`` element: its transmissions (typically ROS 1
ones) are read by nothing (TX305).

Why it matters: the plugin loads no hardware at all. Both plugins hand the robot description
to ros2_control's ``parse_control_resources_from_urdf``, which throws "no 'ros2_control' tag
found in the URDF". gazebo_ros2_control on Humble catches it and stops: "Error parsing URDF in
gazebo_ros2_control plugin, plugin not active"; so does ign_ros2_control. From Jazzy on, the
parse happens in the plugins' resource manager, which lets the exception stop the controller
manager's start.

Loader: ros2_control (ros-controls/ros2_control hardware_interface/src/component_parser.cpp
``parse_control_resources_from_urdf`` @53b9999); ros-controls/gazebo_ros2_control
gazebo_ros2_control/src/gazebo_ros2_control_plugin.cpp ``GazeboRosControlPlugin::Load``
@42d875b (Jazzy: ``GazeboResourceManager::load_and_initialize_components`` @3e6d3f4);
ros-controls/gz_ros2_control ign_ros2_control/src/ign_ros2_control_plugin.cpp
``IgnitionROS2ControlPlugin::Configure`` @4cb90a2 (Jazzy:
gz_ros2_control/src/gz_ros2_control_plugin.cpp ``GZResourceManager::load_and_initialize_components``
@fa9ced4).

Failing example::

    <robot name="arm">
      <transmission name="t">
        <type>transmission_interface/SimpleTransmission</type>
        <joint name="j">
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
        </joint>
        <actuator name="m"><mechanicalReduction>50</mechanicalReduction></actuator>
      </transmission>
      <gazebo>
        <plugin filename="libgazebo_ros2_control.so" name="gazebo_ros2_control"/>
      </gazebo>
    </robot>

Expected finding: ``10:5 error TX007 <gazebo> plugin libgazebo_ros2_control.so needs a
<ros2_control> element and this robot has none: ros2_control's parser throws ("no 'ros2_control'
tag found in the URDF") and the plugin loads no hardware; its transmissions are read by
nothing``

Passing example::

    <robot name="arm">
      <ros2_control name="arm" type="system">
        <hardware><plugin>gazebo_ros2_control/GazeboSystem</plugin></hardware>
        <joint name="j"><command_interface name="effort"/></joint>
      </ros2_control>
      <gazebo>
        <plugin filename="libgazebo_ros2_control.so" name="gazebo_ros2_control"/>
      </gazebo>
    </robot>

Fix: describe the hardware in a ``<ros2_control>`` element (``txtool convert --to ros2-p2``
writes the transmissions into one), or name the ROS 1 plugin if the robot is for ROS 1.
"""

from __future__ import annotations

from collections.abc import Iterator

from txtool.lint.context import LintContext
from txtool.lint.problem import Problem
from txtool.lint.rule_helpers import whole_robot

CODE = "TX007"
NAME = "no-ros2-control"
SEVERITY = "error"
FIXABLE = False


@whole_robot
def check(ctx: LintContext) -> Iterator[Problem]:
    plugin = ctx.readers.missing_components
    if plugin is None or ctx.literal:
        return
    filename = (plugin.get("filename") or "").strip()
    yield ctx.problem(
        CODE, plugin,
        f"<gazebo> plugin {filename} needs a <ros2_control> element and this robot has none: "
        "ros2_control's parser throws (\"no 'ros2_control' tag found in the URDF\") and the "
        "plugin loads no hardware; its transmissions are read by nothing",
        refuses_whole=True,
    )
