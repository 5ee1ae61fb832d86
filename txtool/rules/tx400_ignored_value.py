"""A value the ROS loader never reads.

What it does: reports values written in a standard transmission that its loader does not use:
in a ROS 2 SimpleTransmission, the actuator's ``<mechanical_reduction>`` and ``<offset>``
(ros2_control takes both from the joint; ROS 1 took the reduction from the actuator); in a
ROS 2 Differential / FourBarLinkage, actuator ``<offset>`` elements, and joints or actuators
past the second; in a ROS 1 SimpleTransmission, the joint's ``<mechanicalReduction>``
(ros_control reads the actuator's); in ROS 1, any standard type, an actuator ``<offset>`` (only
joint offsets exist), and a ``<mechanicalReduction>`` directly under ``<transmission>`` (with a
``type=`` attribute this is TX302's case).

Why it matters: a value that is never read looks like configuration but changes nothing: the
robot runs with the default (1.0 or 0.0) while the file says otherwise. Usually it was written
on the wrong side during a port between ROS 1 and ROS 2.

Loader: ros2_control (ros-controls/ros2_control
transmission_interface/src/simple_transmission_loader.cpp ``SimpleTransmissionLoader::load``
reads ``joints.at(0)``; differential_transmission_loader.cpp and
four_bar_linkage_transmission_loader.cpp read ``joints.at(0..1)`` and ``actuators.at(0..1)``);
ros_control (ros-controls/ros_control transmission_interface/src/simple_transmission_loader.cpp
``SimpleTransmissionLoader::load`` reads the actuator's reduction and the joint's offset).

Failing example::

    <robot name="r">
      <ros2_control name="HW" type="system">
        <hardware><plugin>mock_components/GenericSystem</plugin></hardware>
        <joint name="j"><command_interface name="position"/></joint>
        <transmission name="t">
          <plugin>transmission_interface/SimpleTransmission</plugin>
          <joint name="j" role="joint1"></joint>
          <actuator name="m" role="actuator1">
            <mechanical_reduction>50</mechanical_reduction>
          </actuator>
        </transmission>
      </ros2_control>
    </robot>

Expected finding: ``9:9 warning TX400 <mechanical_reduction> of actuator 'm' in transmission 't'
is never read: ros2_control's SimpleTransmission takes reduction and offset from the joint``

Passing example::

    <robot name="r">
      <ros2_control name="HW" type="system">
        <hardware><plugin>mock_components/GenericSystem</plugin></hardware>
        <joint name="j"><command_interface name="position"/></joint>
        <transmission name="t">
          <plugin>transmission_interface/SimpleTransmission</plugin>
          <joint name="j" role="joint1">
            <mechanical_reduction>50</mechanical_reduction>
          </joint>
          <actuator name="m" role="actuator1"></actuator>
        </transmission>
      </ros2_control>
    </robot>

Fix: write the value where the loader reads it (on the ``<joint>`` in ROS 2, on the
``<actuator>`` in ROS 1), or delete it.
"""

from __future__ import annotations

from collections.abc import Iterator

from lxml import etree

from txtool.lint.context import LintContext
from txtool.lint.facts import Facts
from txtool.lint.problem import Problem
from txtool.lint.rule_helpers import per_transmission

CODE = "TX400"
NAME = "ignored-value"
SEVERITY = "warning"
FIXABLE = False

Finding = tuple[etree._Element, str]


@per_transmission
def check(ctx: LintContext) -> Iterator[Problem]:
    for tx in ctx.facts:
        if tx.kind == "other" or (tx.ros1 and _quiet_ros1(tx)):
            continue
        findings = _ros1(tx) if tx.ros1 else _ros2(tx)
        for element, message in findings:
            yield ctx.problem(CODE, element, message)


def _ros2(tx: Facts) -> Iterator[Finding]:
    simple = tx.kind == "simple"
    fields = ("mechanical_reduction", "offset") if simple else ("offset",)
    reason = (
        "ros2_control's SimpleTransmission takes reduction and offset from the joint"
        if simple
        else "ros2_control's coupled transmissions have joint offsets only"
    )
    for refs in (tx.joints, tx.actuators):
        for seen, ref in enumerate(refs, 1):
            if ref.noun == "actuator":
                for field in fields:
                    for element in ref.tagged(field):
                        yield element, _never_read(tx, ref.noun, ref.name, field, reason)
            if not simple and seen > 2:
                yield ref.element, (
                    f"{ref.noun} '{ref.name}' of {tx.label} comes after the second: "
                    "ros2_control's loader reads only the first two and ignores it"
                )


def _quiet_ros1(tx: Facts) -> bool:
    """Nothing for :func:`_ros1` to report (the common case), found without a generator."""
    if "mechanicalReduction" in tx.kids:
        return False
    if tx.kind == "simple":
        for ref in tx.joints:
            if "mechanicalReduction" in ref.kids:
                return False
    for ref in tx.actuators:  # noqa: SIM110 (a loop costs less than a generator, per transmission)
        if "offset" in ref.kids:
            return False
    return True


def _ros1(tx: Facts) -> Iterator[Finding]:
    simple = tx.kind == "simple"
    if simple:
        for ref in tx.joints:
            for element in ref.tagged("mechanicalReduction"):
                yield element, _never_read(
                    tx, ref.noun, ref.name, "mechanicalReduction",
                    "ros_control's SimpleTransmission takes the reduction from the actuator",
                )
    for ref in tx.actuators:
        for element in ref.tagged("offset"):
            yield element, _never_read(
                tx, ref.noun, ref.name, "offset",
                "ros_control reads offsets from joints only",
            )
    if "mechanicalReduction" in tx.kids and tx.element.get("type") is None:
        for element in tx.tagged("mechanicalReduction"):
            yield element, (
                f"<mechanicalReduction> directly under {tx.label} is never read: "
                "ros_control reads the reductions of its <actuator> and <joint> elements"
            )


def _never_read(tx: Facts, noun: str, name: str, field: str, reason: str) -> str:
    return f"<{field}> of {noun} '{name}' in {tx.label} is never read: {reason}"
