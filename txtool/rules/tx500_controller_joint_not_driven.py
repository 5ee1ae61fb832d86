"""A controller names a joint the robot does not have, or one nothing drives: its manager
refuses it.

What it does: reports, at the controller's name in its configuration file, each joint a
controller claims (``joint``, ``joints``, ``command_joints``, ``left_wheel_names``, ...) that is
not a joint of the robot, or that no reader gives any interface: in ROS 1 no transmission with a
``<hardwareInterface>`` names it, in ROS 2 no ``<ros2_control>`` joint declares it. The robot is
the one ``txtool validate`` pairs with the file (``--controllers``, or the YAML files of the
robot's package); a robot that declares no interface at all for the file's ROS generation (a ROS
1 robot driven by a ``RobotHW`` written in C++) is not judged.

Why it matters: ROS 1's controller manager fails to load the controller: the joint's handle is
looked up in the hardware interface and not found ("Could not find resource 'JOINT' in
'INTERFACE'"). ROS 2's controller manager refuses to activate it: the claimed interface "is not
available".

Loader: ros_control (ros-controls/ros_control
hardware_interface/include/hardware_interface/internal/resource_manager.h:119 @633c374) and
ros2_control (ros-controls/ros2_control controller_manager/src/controller_manager.cpp:4381
@53b9999); the joints each controller claims: txtool/model/controllers.py.

Robot (urdf/robot.urdf)::

    <robot name="r">
      <link name="base"/><link name="arm"/>
      <joint name="shoulder" type="revolute">
        <parent link="base"/><child link="arm"/>
        <limit lower="-1" upper="1" effort="10" velocity="1"/>
      </joint>
      <transmission name="shoulder_tx">
        <type>transmission_interface/SimpleTransmission</type>
        <joint name="shoulder">
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
        </joint>
        <actuator name="shoulder_motor"><mechanicalReduction>1</mechanicalReduction></actuator>
      </transmission>
    </robot>

Failing example (catkin package, config/controllers.yaml)::

    arm_controller:
      type: effort_controllers/JointGroupEffortController
      joints: [shoulder, elbow]

Expected finding: ``1:1 error TX500 controller 'arm_controller'
(effort_controllers/JointGroupEffortController): joint 'elbow' is not a joint of the robot; the
controller manager refuses the controller: Could not find resource 'elbow' in
'hardware_interface::EffortJointInterface'``

Passing example (catkin package, config/controllers.yaml)::

    arm_controller:
      type: effort_controllers/JointGroupEffortController
      joints: [shoulder]

Fix: name the robot's joints (check the spelling and any prefix the robot's xacro adds), or give
the joint a transmission (ROS 1) or a ``<ros2_control>`` joint (ROS 2).
"""

from __future__ import annotations

from collections.abc import Iterator
from typing import TYPE_CHECKING

from txtool.lint.controller_files import refusal

if TYPE_CHECKING:
    from txtool.lint.controller_files import ControllerContext
    from txtool.lint.problem import Problem

CODE = "TX500"
NAME = "controller-joint-not-driven"
SEVERITY = "error"
FIXABLE = False


def check_controllers(ctx: ControllerContext) -> Iterator[Problem]:
    if not ctx.provision.has(ctx.generation):
        return
    for controller in ctx.controllers:
        reported = set()
        for claim in controller.claims:
            joint = claim.joint
            if joint in reported:
                continue
            if joint not in ctx.provision.joints:
                why = "is not a joint of the robot"
            elif not ctx.provision.driven(ctx.generation, joint):
                why = ("has no transmission with a hardwareInterface" if ctx.generation == "ros1"
                       else "is in no <ros2_control> block")
            else:
                continue
            reported.add(joint)
            yield ctx.problem(
                CODE, controller,
                f"controller '{controller.name}' ({controller.type}): joint '{joint}' {why}; "
                f"the controller manager refuses the controller: {refusal(ctx, claim)}",
            )
