"""A ROS 1 actuator without ``<mechanicalReduction>``: ros_control refuses the transmission.

What it does: reports each ``<actuator>`` of a ROS 1 simple, differential or four-bar
transmission that has no ``<mechanicalReduction>`` of its own. A ``<mechanicalReduction>``
written directly under ``<transmission>`` (the pre-Hydro form) is not read, and is named in
the message.

Why it matters: ros_control loads nothing of such a transmission ("Actuator 'A' of transmission
'T' does not specify the required <mechanicalReduction> element."): the joint is not driven.
gazebo_ros_control's DefaultRobotHWSim and franka_gazebo's FrankaHWSim never read reductions:
in a robot that names either as its ``<gazebo>`` plugin the finding is a warning, since the
simulation loads while a ros_control ``RobotHW`` on the real robot would refuse it. ROS 2 has
no such requirement (the default is 1.0).

Loader: ros_control's SimpleTransmission, DifferentialTransmission and
FourBarLinkageTransmission loaders (ros-controls/ros_control
transmission_interface/src/simple_transmission_loader.cpp ``SimpleTransmissionLoader::load``,
and the differential and four-bar loaders alike); gazebo_ros_pkgs
gazebo_ros_control/src/default_robot_hw_sim.cpp ``initSim`` @01c3a2c and frankaemika/franka_ros
franka_gazebo/src/franka_hw_sim.cpp ``initSim`` @005ff25 read none.

Failing example::

    <robot name="r">
      <transmission name="t">
        <type>transmission_interface/SimpleTransmission</type>
        <joint name="j">
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
        </joint>
        <actuator name="m"/>
      </transmission>
    </robot>

Expected finding: ``7:5 error TX104 actuator 'm' of transmission 't' has no
<mechanicalReduction>: ros_control refuses the transmission``

Passing example::

    <robot name="r">
      <transmission name="t">
        <type>transmission_interface/SimpleTransmission</type>
        <joint name="j">
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
        </joint>
        <actuator name="m"><mechanicalReduction>50</mechanicalReduction></actuator>
      </transmission>
    </robot>

Fix: write ``<mechanicalReduction>`` inside every ``<actuator>`` (``1`` for a direct drive).
"""

from __future__ import annotations

from collections.abc import Iterator

from txtool.lint.context import LintContext
from txtool.lint.problem import Problem
from txtool.lint.rule_helpers import opaque, per_transmission

CODE = "TX104"
NAME = "missing-reduction"
SEVERITY = "error"
FIXABLE = False


@per_transmission
def check(ctx: LintContext) -> Iterator[Problem]:
    for tx in ctx.facts:
        if not tx.typed_ros1 or tx.kind == "other":
            continue
        for ref in tx.actuators:
            if "mechanicalReduction" in ref.kids or opaque(ctx, ref.element):
                continue
            legacy = "mechanicalReduction" in tx.kids
            message = (
                f"actuator '{ref.name}' of {tx.label} has no <mechanicalReduction>: "
                "ros_control refuses the transmission"
            )
            if legacy:
                message += " (it does not read the one under <transmission>)"
            sim = ctx.gazebo_sim
            if sim is not None:
                yield ctx.problem(CODE, ref.element,
                                  f"{message}; {sim.describe()} never reads reductions and "
                                  "loads it", loader_severity="warning")
                continue
            yield ctx.problem(CODE, ref.element, message)
