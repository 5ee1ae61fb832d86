"""A controller reads a state interface the robot does not provide for that joint: its manager
refuses it.

What it does: reports, at the controller's name in its configuration file, each joint that the
robot drives but without a state interface the controller reads: a ROS 2 controller's
``JOINT/INTERFACE`` state interfaces (``state_interfaces``, the joint state broadcaster's
``joints`` with ``interfaces``, the gripper's and diff drive's defaults) must be
``<state_interface>`` elements of the joint's ``<ros2_control>`` block. (A ROS 1 controller
reads the joint state through its command interface's handle, and every transmission joint has
a ``JointStateInterface`` handle.)

Why it matters: ROS 2's controller manager refuses to activate the controller ("Unable to
activate controller ... since the state interface ... is not available"). One finding per
controller and interface names every joint concerned. It is a warning where another controller
of the file drives the joint as the robot is (a file of alternatives, of which a launch file
spawns some): the manager refuses the controller only if it is loaded with this robot.

Loader: ros2_control (ros-controls/ros2_control controller_manager/src/controller_manager.cpp:4416
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
        </joint>
      </ros2_control>
    </robot>

Failing example (ament_cmake package, config/controllers.yaml)::

    controller_manager:
      ros__parameters:
        arm_controller:
          type: joint_trajectory_controller/JointTrajectoryController
    arm_controller:
      ros__parameters:
        joints: [shoulder]
        command_interfaces: [position]
        state_interfaces: [position, velocity]

Expected finding: ``3:5 error TX502 controller 'arm_controller'
(joint_trajectory_controller/JointTrajectoryController): joint 'shoulder' has no state interface
'velocity' (it has: position); the controller manager refuses the controller: state
interface 'shoulder/velocity' is not available``

Passing example (ament_cmake package, config/controllers.yaml)::

    controller_manager:
      ros__parameters:
        arm_controller:
          type: joint_trajectory_controller/JointTrajectoryController
    arm_controller:
      ros__parameters:
        joints: [shoulder]
        command_interfaces: [position]
        state_interfaces: [position]

Fix: read only the state interfaces the joint declares, or declare the one the controller reads
(a ``<state_interface>`` of the joint).
"""

from __future__ import annotations

from collections.abc import Iterator
from typing import TYPE_CHECKING

from txtool.lint.controller_files import controller_interface_problems

if TYPE_CHECKING:
    from txtool.lint.controller_files import ControllerContext
    from txtool.lint.problem import Problem

CODE = "TX502"
NAME = "controller-state-interface"
SEVERITY = "error"
FIXABLE = False


def check_controllers(ctx: ControllerContext) -> Iterator[Problem]:
    return controller_interface_problems(ctx, CODE, command=False)
