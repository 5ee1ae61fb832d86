"""A ROS 1 actuator without ``<mechanicalReduction>``: ros_control refuses the transmission.

The SimpleTransmission, DifferentialTransmission and FourBarLinkageTransmission loaders of
ros_control require the element in every ``<actuator>`` ("Actuator 'A' of transmission 'T'
does not specify the required <mechanicalReduction> element.") and load nothing without it.
A ``<mechanicalReduction>`` written directly under ``<transmission>`` (the pre-Hydro form)
is not read. gazebo_ros_control's DefaultRobotHWSim never reads reductions
(gazebo_ros_pkgs gazebo_ros_control/src/default_robot_hw_sim.cpp ``initSim`` @01c3a2c), nor
does franka_gazebo's FrankaHWSim (frankaemika/franka_ros franka_gazebo/src/franka_hw_sim.cpp
``initSim`` @005ff25): in a robot that names either as its ``<gazebo>`` plugin the finding is a
warning, since the simulation
loads while a ros_control ``RobotHW`` on the real robot would refuse the transmission. ROS 2
has no such requirement (the default is 1.0).

Failing example::

    <transmission name="t">
      <type>transmission_interface/SimpleTransmission</type>
      <joint name="j">
        <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
      </joint>
      <actuator name="m"/>
    </transmission>

Passing example::

    <transmission name="t">
      <type>transmission_interface/SimpleTransmission</type>
      <joint name="j">
        <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
      </joint>
      <actuator name="m"><mechanicalReduction>50</mechanicalReduction></actuator>
    </transmission>
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
