"""Two controllers that one launch file starts claim the same command interface: the manager
refuses one of them.

What it does: reports, at a controller's name in its configuration file, each other controller
of the file that claims one of the same command interfaces when a launch file of the
configuration's or the robot's package (its ``launch`` folder) starts both: a controller_manager
``spawner`` that runs under no condition names both, without ``--inactive``, ``--load-only`` or
``--stopped`` (see :mod:`txtool.io.launch_spawners`). ROS 2: the same ``JOINT/INTERFACE``
command interface. ROS 1: the same joint through a command interface (a controller claims each
joint's handle exclusively, whatever its interface; the joint state controller claims none).
Only interfaces the robot provides are compared (a missing one is TX501's finding).

Why it matters: ROS 2's controller manager activates the first and refuses the other ("Resource
conflict for controller 'B'. Command interface 'JOINT/INTERFACE' is already claimed"); with one
spawner naming both, the refusal is the second's, with two spawners it is whichever is
activated last. ROS 1's controller manager refuses to start both in one switch ("Could not
switch controllers, due to resource conflict"): the spawner's strict switch starts neither of
its controllers. A launch file's controllers named through an argument (``$(arg ...)``,
``LaunchConfiguration``) are not known and not compared.

Loader: ros2_control (ros-controls/ros2_control controller_manager/src/controller_manager.cpp:2696
@53b9999) and ros_control (ros-controls/ros_control
hardware_interface/include/hardware_interface/robot_hw.h:113-146 checkForConflict and
controller_manager/scripts/spawner:212 @633c374).

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

Launch (launch/bringup.launch.py)::

    from launch import LaunchDescription
    from launch_ros.actions import Node

    def generate_launch_description():
        return LaunchDescription([
            Node(package="controller_manager", executable="spawner",
                 arguments=["arm_controller", "shoulder_controller"]),
        ])

Failing example (ament_cmake package, config/controllers.yaml)::

    controller_manager:
      ros__parameters:
        arm_controller:
          type: joint_trajectory_controller/JointTrajectoryController
        shoulder_controller:
          type: position_controllers/JointGroupPositionController
    arm_controller:
      ros__parameters:
        joints: [shoulder]
        command_interfaces: [position]
        state_interfaces: [position]
    shoulder_controller:
      ros__parameters:
        joints: [shoulder]

Expected finding: ``5:5 error TX504 controller 'shoulder_controller'
(position_controllers/JointGroupPositionController) claims command interface
'shoulder/position', which 'arm_controller' claims too, and launch/bringup.launch.py:6 starts
both: the controller manager refuses the one activated second: Resource conflict for controller
'shoulder_controller'. Command interface 'shoulder/position' is already claimed``

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

Fix: start one of them (spawn the other with ``--inactive``, or ``--stopped`` in ROS 1, and
switch between them at run time), or give each its own joints.
"""

from __future__ import annotations

from collections.abc import Iterator
from typing import TYPE_CHECKING

from txtool.lint.controller_files import shown
from txtool.model.controllers import ROS1

if TYPE_CHECKING:
    from txtool.lint.controller_files import ControllerContext
    from txtool.lint.problem import Problem
    from txtool.model.controllers import Controller

CODE = "TX504"
NAME = "controllers-claim-one-interface"
SEVERITY = "error"
FIXABLE = False


def check_controllers(ctx: ControllerContext) -> Iterator[Problem]:
    by_name = {c.name: c for c in ctx.controllers}
    reported: set[tuple[str, str]] = set()
    for spawn in ctx.spawns:
        where = f"{shown(spawn.path)}:{spawn.line}"
        started = [by_name[name] for name in dict.fromkeys(spawn.started) if name in by_name]
        others = [c for s in ctx.spawns if s.path == spawn.path and s.line < spawn.line
                  for c in (by_name.get(name) for name in s.started) if c is not None]
        for index, controller in enumerate(started):
            for earlier in dict.fromkeys([*others, *started[:index]]):
                shared = _shared(ctx, earlier, controller)
                if shared and (earlier.name, controller.name) not in reported:
                    reported.add((earlier.name, controller.name))
                    yield ctx.problem(CODE, controller, _message(ctx, earlier, controller,
                                                                 shared, where))


def _claimed(ctx: ControllerContext, controller: Controller) -> dict[str, None]:
    """What the controller claims exclusively: ROS 1 joints, ROS 2 ``JOINT/INTERFACE``."""
    return dict.fromkeys(claim.joint if ctx.generation == ROS1 else
                         f"{claim.joint}/{claim.interface}"
                         for claim in controller.claims
                         if claim.command and ctx.provision.provides(ctx.generation, claim))


def _shared(ctx: ControllerContext, first: Controller, second: Controller) -> list[str]:
    if first is second:
        return []
    theirs = _claimed(ctx, first)
    return [key for key in _claimed(ctx, second) if key in theirs]


def _message(ctx: ControllerContext, earlier: Controller, controller: Controller,
             shared: list[str], where: str) -> str:
    names = ", ".join(f"'{key}'" for key in shared)
    if ctx.generation == ROS1:
        return (f"controller '{controller.name}' ({controller.type}) claims joint"
                f"{'s' if len(shared) > 1 else ''} {names}, which '{earlier.name}' claims too, "
                f"and {where} starts both: the controller manager refuses to start them "
                "together: Could not switch controllers, due to resource conflict")
    return (f"controller '{controller.name}' ({controller.type}) claims command interface"
            f"{'s' if len(shared) > 1 else ''} {names}, which '{earlier.name}' claims too, and "
            f"{where} starts both: the controller manager refuses the one activated second: "
            f"Resource conflict for controller '{controller.name}'. Command interface "
            f"'{shared[0]}' is already claimed")
