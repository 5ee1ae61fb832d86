"""A transmission drives a joint that mimics another joint.

What it does: reports a transmission ``<joint>`` of a standard transmission type that names a
URDF joint with a ``<mimic joint="..."/>`` child (only when the document is a robot with
joints). Custom types, such as gripper transmissions that model passive joints, are not
checked.

Why it matters: a mimic joint follows its leader (``q = multiplier * q_leader + offset``); it
is not an independent degree of freedom. Commanding it through its own transmission and
actuator fights that constraint, and simulators either ignore the command or let the two
joints drift apart. A warning: it loads.

Loader: urdfdom reads the ``<mimic>`` (ros/urdfdom urdf_parser/src/joint.cpp
``parseJointMimic``); gazebo_ros_pkgs gazebo_ros_control/src/default_robot_hw_sim.cpp
``initSim`` @01c3a2c commands the joint as any other.

Failing example::

    <robot name="r">
      <link name="palm"/>
      <link name="left"/>
      <link name="right"/>
      <joint name="finger_left" type="prismatic">
        <parent link="palm"/><child link="left"/><axis xyz="1 0 0"/>
        <limit lower="0" upper="0.04" effort="10" velocity="0.1"/>
      </joint>
      <joint name="finger_right" type="prismatic">
        <parent link="palm"/><child link="right"/><axis xyz="-1 0 0"/>
        <limit lower="0" upper="0.04" effort="10" velocity="0.1"/>
        <mimic joint="finger_left" multiplier="1"/>
      </joint>
      <transmission name="t">
        <type>transmission_interface/SimpleTransmission</type>
        <joint name="finger_right">
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
        </joint>
        <actuator name="m"><mechanicalReduction>1</mechanicalReduction></actuator>
      </transmission>
    </robot>

Expected finding: ``16:5 warning TX202 joint 'finger_right' of transmission 't' mimics
'finger_left': it follows that joint, so driving it through its own transmission fights the
mimic constraint``

Passing example::

    <robot name="r">
      <link name="palm"/>
      <link name="left"/>
      <link name="right"/>
      <joint name="finger_left" type="prismatic">
        <parent link="palm"/><child link="left"/><axis xyz="1 0 0"/>
        <limit lower="0" upper="0.04" effort="10" velocity="0.1"/>
      </joint>
      <joint name="finger_right" type="prismatic">
        <parent link="palm"/><child link="right"/><axis xyz="-1 0 0"/>
        <limit lower="0" upper="0.04" effort="10" velocity="0.1"/>
        <mimic joint="finger_left" multiplier="1"/>
      </joint>
      <transmission name="t">
        <type>transmission_interface/SimpleTransmission</type>
        <joint name="finger_left">
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
        </joint>
        <actuator name="m"><mechanicalReduction>1</mechanicalReduction></actuator>
      </transmission>
    </robot>

Fix: drive the leader instead, or drop the ``<mimic>`` if the joint really has its own
actuator.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator

from txtool.lint.context import LintContext
from txtool.lint.problem import Problem
from txtool.lint.rule_helpers import label, robot_joints_of_transmissions

CODE = "TX202"
NAME = "mimic-joint"
SEVERITY = "warning"
FIXABLE = False


def check(ctx: LintContext) -> Iterable[Problem]:
    if not ctx.hints.mimics:
        return ()  # no <mimic> in the document
    return _mimics(ctx)


def _mimics(ctx: LintContext) -> Iterator[Problem]:
    for found, joint, robot in robot_joints_of_transmissions(ctx):
        if next(robot.iterchildren("{*}mimic"), None) is None:
            continue  # no <mimic>: nothing to read
        info = ctx.joints[joint.get("name", "")]
        if info.mimic is None:
            continue
        yield ctx.problem(
            CODE,
            joint,
            f"joint '{info.name}' of {label(found)} mimics "
            f"'{info.mimic}': it follows that joint, so driving it through its own "
            "transmission fights the mimic constraint",
        )
