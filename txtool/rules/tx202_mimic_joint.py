"""A transmission drives a joint that mimics another joint.

What it checks
    A transmission ``<joint>`` of a standard transmission type that names a URDF joint with a
    ``<mimic joint="..."/>`` child (only when the document is a robot with joints). Custom
    types, such as gripper transmissions that model passive joints, are not checked.

Why
    A mimic joint follows its leader (``q = multiplier * q_leader + offset``); it is not an
    independent degree of freedom. Commanding it through its own transmission and actuator
    fights that constraint, and simulators either ignore the command or let the two joints
    drift apart. Drive the leader instead, or drop the ``<mimic>`` if the joint really has its
    own actuator.

Failing example::

    <robot name="r">
      <joint name="finger_left" type="prismatic">...</joint>
      <joint name="finger_right" type="prismatic">
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

Passing example: the transmission names ``finger_left``.
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
