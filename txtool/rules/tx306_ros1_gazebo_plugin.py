"""The ROS 1 gazebo_ros_control plugin in a robot only ROS 2 reads: nothing loads it.

What it does: reports a ``<gazebo><plugin filename="libgazebo_ros_control.so">`` (or a build
of it under another name ending so) of a robot whose readers are all ROS 2 programs: the
robot's ``package.xml`` builds with ament only (no catkin, under no condition), or
``--ros-distro`` (``ros-distro``, ``readers``) names ROS 2. In such a package the plugin no
longer decides the readers: the package does, so the ``<ros2_control>`` transmissions are
judged by ros2_control.

Why it matters: gazebo_ros_control is a ROS 1 package (gazebo_ros_pkgs ``noetic-devel``); no
ROS 2 distribution builds it, so Gazebo logs that it cannot load the library and the robot
spawns without a controller manager: nothing in simulation reads its transmissions, and its
ROS 1 ``<robotSimType>`` and parameters do nothing. The robot description itself still
loads, hence a warning. ROS 2 robots in Gazebo run ros2_control through gazebo_ros2_control
(Gazebo Classic, ``libgazebo_ros2_control.so``) or gz_ros2_control (``gz_ros2_control-system``),
both of which read the ``<ros2_control>`` block.

Loader: Gazebo's plugin loader (gazebo ``gazebo::common::SystemPaths``: the library must be on
``GAZEBO_PLUGIN_PATH``); ros-simulation/gazebo_ros_pkgs builds gazebo_ros_control only on its
ROS 1 branches (``noetic-devel``; the ``ros2`` branch has no gazebo_ros_control); the ROS 2
replacements: ros-controls/gazebo_ros2_control gazebo_ros2_control/src/
gazebo_ros2_control_plugin.cpp and ros-controls/gz_ros2_control.

Failing example (ament_cmake package, urdf/robot.urdf)::

    <robot name="r">
      <link name="base"/><link name="arm"/>
      <joint name="shoulder" type="revolute">
        <parent link="base"/><child link="arm"/><axis xyz="0 0 1"/>
        <limit lower="-1" upper="1" effort="10" velocity="1"/>
      </joint>
      <ros2_control name="arm" type="system">
        <hardware><plugin>gazebo_ros2_control/GazeboSystem</plugin></hardware>
        <joint name="shoulder"><command_interface name="position"/></joint>
      </ros2_control>
      <gazebo>
        <plugin name="gazebo_ros_control" filename="libgazebo_ros_control.so"/>
      </gazebo>
    </robot>

Expected finding: ``12:5 warning TX306 <gazebo> plugin libgazebo_ros_control.so is
gazebo_ros_control, a ROS 1 plugin no ROS 2 distribution builds, and only ROS 2 programs read
this robot (gazebo_ros2_control, ros2_control): Gazebo cannot load it and nothing in
simulation reads the transmissions; name gazebo_ros2_control (libgazebo_ros2_control.so) or
gz_ros2_control (gz_ros2_control-system)``

Passing example (ament_cmake package, urdf/robot.urdf)::

    <robot name="r">
      <link name="base"/><link name="arm"/>
      <joint name="shoulder" type="revolute">
        <parent link="base"/><child link="arm"/><axis xyz="0 0 1"/>
        <limit lower="-1" upper="1" effort="10" velocity="1"/>
      </joint>
      <ros2_control name="arm" type="system">
        <hardware><plugin>gazebo_ros2_control/GazeboSystem</plugin></hardware>
        <joint name="shoulder"><command_interface name="position"/></joint>
      </ros2_control>
      <gazebo>
        <plugin name="gazebo_ros2_control" filename="libgazebo_ros2_control.so"/>
      </gazebo>
    </robot>

Fix: replace the plugin with gazebo_ros2_control's (Gazebo Classic) or gz_ros2_control's
(Gazebo), whose parameters file names the controllers; keep ``libgazebo_ros_control.so`` only
in a description for ROS 1.
"""

from __future__ import annotations

from collections.abc import Iterator

from txtool.lint.context import LintContext
from txtool.lint.problem import Problem
from txtool.lint.rule_helpers import whole_robot

CODE = "TX306"
NAME = "ros1-gazebo-plugin"
SEVERITY = "warning"
FIXABLE = False


@whole_robot
def check(ctx: LintContext) -> Iterator[Problem]:
    if ctx.literal:
        return
    plugin = ctx.readers.unloaded_plugin
    if plugin is None:
        return
    filename = (plugin.get("filename") or "").strip()
    readers = ", ".join(ctx.readers.names())
    yield ctx.problem(
        CODE, plugin,
        f"<gazebo> plugin {filename} is gazebo_ros_control, a ROS 1 plugin no ROS 2 "
        f"distribution builds, and only ROS 2 programs read this robot ({readers}): Gazebo "
        "cannot load it and nothing in simulation reads the transmissions; name "
        "gazebo_ros2_control (libgazebo_ros2_control.so) or gz_ros2_control "
        "(gz_ros2_control-system)")
