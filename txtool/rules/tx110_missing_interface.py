"""A ROS 1 joint without ``<hardwareInterface>``: ros_control skips the joint.

What it does: reports a ``<joint>`` of a ROS 1 transmission with no non-empty
``<hardwareInterface>``. Since ROS Indigo an interface written only in the ``<actuator>`` does not
count (ros_control#177). Transmissions of families with their own loaders
(``pr2_mechanism_model/``, ``sr_mechanism_model/``) and ones ros_control skips for want of a
``<type>`` are not checked.

Why it matters: ros_control skips the joint ("No valid hardware interface element found in
joint 'J'."), and a transmission left without joints is not loaded ("Failed to load joints for
transmission 'T'."). gazebo_ros_control's DefaultRobotHWSim still takes the first actuator's
interface when the joint names none, with a warning: in a robot that names it as its
``<gazebo>`` plugin, and whose actuator names an interface it accepts, this rule leaves the
joint to TX301 (a warning, with a fix).

Loader: ros_control's transmission parser (ros-controls/ros_control
transmission_interface/src/transmission_parser.cpp:155-175 @14e64ea); gazebo_ros_pkgs
gazebo_ros_control/src/default_robot_hw_sim.cpp ``initSim`` @01c3a2c.

Failing example::

    <robot name="r">
      <transmission name="t">
        <type>transmission_interface/SimpleTransmission</type>
        <joint name="j"/>
        <actuator name="m">
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
          <mechanicalReduction>50</mechanicalReduction>
        </actuator>
      </transmission>
    </robot>

Expected finding: ``4:5 error TX110 joint 'j' of transmission 't' has no <hardwareInterface>
(only its actuator names one): ros_control skips the joint``

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

Fix: write the interface inside the ``<joint>`` (``hardware_interface/EffortJointInterface``,
say).
"""

from __future__ import annotations

from collections.abc import Iterator

from txtool.lint.context import LintContext
from txtool.lint.problem import Problem
from txtool.lint.rule_helpers import opaque, per_transmission
from txtool.model.readers import accepts

CODE = "TX110"
NAME = "missing-interface"
SEVERITY = "error"
FIXABLE = False


@per_transmission
def check(ctx: LintContext) -> Iterator[Problem]:
    for tx in ctx.facts:
        if not tx.typed_ros1 or tx.own_loader:
            continue
        for ref in tx.joints:
            if ref.interfaces or opaque(ctx, ref.element):
                continue
            interfaces = ref.tagged("hardwareInterface")
            what = "an empty <hardwareInterface>" if interfaces else "no <hardwareInterface>"
            actuators = tx.actuators
            named = tx.actuator_interfaces
            where = " (only its actuator names one)" if named else ""
            # gazebo_ros_control's DefaultRobotHWSim falls back on the first actuator's.
            taken = actuators[0].interfaces if actuators else []
            sim = ctx.gazebo_sim
            if sim is not None and sim.default and taken and accepts(taken[0]):
                continue  # the robot's loader takes the actuator's: TX301 warns (and fixes)
            yield ctx.problem(
                CODE,
                ref.element,
                f"joint '{ref.name}' of {tx.label} has {what}{where}: "
                "ros_control skips the joint",
            )
