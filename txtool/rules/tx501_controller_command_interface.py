"""A controller claims a command interface the robot does not provide for that joint: its
manager refuses it.

What it does: reports, at the controller's name in its configuration file, each joint that the
robot drives but not through the interface the controller commands. ROS 1: the controller's type
fixes a hardware interface class (``effort_controllers/...`` an ``EffortJointInterface``, the
trajectory controller's adapters likewise); the joint's transmission must name it in
``<hardwareInterface>``. ROS 2: the controller's ``JOINT/INTERFACE`` command interfaces (from
``command_interfaces``, ``interface_name``, or the controller's default) must be
``<command_interface>`` elements of the joint's ``<ros2_control>`` block.

Why it matters: ROS 1's controller manager fails to load the controller ("This controller
requires a hardware interface of type 'INTERFACE'" when no joint has it, "Could not find
resource 'JOINT' in 'INTERFACE'" when others do). ROS 2's controller manager refuses to
activate it ("Unable to activate controller ... since the command interface ... is not
available"). One finding per controller and interface names every joint concerned. It is a
warning where the robot as expanded may not be the robot launched: a ROS 1
``<hardwareInterface>`` of the robot's xacro files is an expression (a launch file's arguments
set it), or another controller of the file drives the joint as the robot is (a file of
alternatives, of which a launch file spawns some): the manager refuses the controller only if
it is loaded with this robot.

Loader: ros_control (ros-controls/ros_control
controller_interface/include/controller_interface/controller.h:111 and
hardware_interface/include/hardware_interface/internal/resource_manager.h:119 @633c374) and
ros2_control (ros-controls/ros2_control controller_manager/src/controller_manager.cpp:4381
@53b9999); each controller's interfaces: txtool/model/controllers.py.

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
          <state_interface name="velocity"/>
        </joint>
      </ros2_control>
    </robot>

Failing example (ament_cmake package, config/controllers.yaml)::

    controller_manager:
      ros__parameters:
        arm_controller:
          type: velocity_controllers/JointGroupVelocityController
    arm_controller:
      ros__parameters:
        joints: [shoulder]

Expected finding: ``3:5 error TX501 controller 'arm_controller'
(velocity_controllers/JointGroupVelocityController): joint 'shoulder' has no command interface
'velocity' (it has: position); the controller manager refuses the controller: command
interface 'shoulder/velocity' is not available``

Passing example (ament_cmake package, config/controllers.yaml)::

    controller_manager:
      ros__parameters:
        arm_controller:
          type: position_controllers/JointGroupPositionController
    arm_controller:
      ros__parameters:
        joints: [shoulder]

Fix: pick the controller that commands what the joint provides, or give the joint that interface
(a ``<hardwareInterface>`` in ROS 1, a ``<command_interface>`` in ROS 2).
"""

from __future__ import annotations

from collections.abc import Iterator
from typing import TYPE_CHECKING

from txtool.lint.controller_files import controller_interface_problems

if TYPE_CHECKING:
    from txtool.lint.controller_files import ControllerContext
    from txtool.lint.problem import Problem

CODE = "TX501"
NAME = "controller-command-interface"
SEVERITY = "error"
FIXABLE = False


def check_controllers(ctx: ControllerContext) -> Iterator[Problem]:
    return controller_interface_problems(ctx, CODE, command=True)
