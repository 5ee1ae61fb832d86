"""A controller's type is no plugin a known package provides: its manager fails to load it
unless a package outside the workspace exports it.

What it does: reports, at the controller's name in its configuration file, a ``type`` that is
none of the standard controllers of its ROS generation (ros_controllers for ROS 1,
ros2_controllers for ROS 2, those of past releases included) and none that a package beside the
file's package exports with pluginlib (``<export><controller_interface plugin="..."/>`` in its
``package.xml``). A misspelt type, or a ROS 1 type in a ROS 2 file, is the usual cause.

Why it matters: the controller manager looks the type up among the installed plugins and fails
to load the controller when none has it (ROS 1: "Could not load controller 'NAME' because
controller type 'TYPE' does not exist"; ROS 2: "Loader for controller 'NAME' (type 'TYPE') not
found"). txtool cannot see what is installed beside the workspace, so this is a warning.

Loader: ros_control (ros-controls/ros_control controller_manager/src/controller_manager.cpp:313
@633c374) and ros2_control (ros-controls/ros2_control
controller_manager/src/controller_manager.cpp:1253 @53b9999); the known types:
txtool/model/controllers.py.

Robot (urdf/robot.urdf)::

    <robot name="r">
      <link name="base"/><link name="arm"/>
      <joint name="shoulder" type="revolute">
        <parent link="base"/><child link="arm"/>
        <limit lower="-1" upper="1" effort="10" velocity="1"/>
      </joint>
      <ros2_control name="arm" type="system">
        <hardware><plugin>mock_components/GenericSystem</plugin></hardware>
        <joint name="shoulder">
          <command_interface name="position"/>
          <state_interface name="position"/>
        </joint>
      </ros2_control>
    </robot>

Failing example (ament_cmake package, config/controllers.yaml)::

    controller_manager:
      ros__parameters:
        joint_state_broadcaster:
          type: joint_state_controller/JointStateController

Expected finding: ``3:5 warning TX503 controller 'joint_state_broadcaster': no known package
provides type 'joint_state_controller/JointStateController' for ROS 2's controller manager; it
fails to load the controller unless an installed package exports it``

Passing example (ament_cmake package, config/controllers.yaml)::

    controller_manager:
      ros__parameters:
        joint_state_broadcaster:
          type: joint_state_broadcaster/JointStateBroadcaster

Fix: spell the type as its package exports it (``txtool rules TX503`` lists where the known
types come from); for a vendor controller, keep its package in the workspace.
"""

from __future__ import annotations

from collections.abc import Iterator
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from txtool.lint.controller_files import ControllerContext
    from txtool.lint.problem import Problem

CODE = "TX503"
NAME = "unknown-controller-type"
SEVERITY = "warning"
FIXABLE = False


def check_controllers(ctx: ControllerContext) -> Iterator[Problem]:
    generation = "ROS 1" if ctx.generation == "ros1" else "ROS 2"
    for controller in ctx.controllers:
        if not controller.known:
            yield ctx.problem(
                CODE, controller,
                f"controller '{controller.name}': no known package provides type "
                f"'{controller.type}' for {generation}'s controller manager; it fails to load "
                f"the controller unless an installed package exports it",
            )
