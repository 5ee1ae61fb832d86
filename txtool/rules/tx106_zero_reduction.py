"""A reduction of zero, which both loaders refuse.

What it does: reports a reduction the loader reads whose value is zero: ``0``, ``-0`` and
``0.0``, and in ROS 1 ``0abc`` too (``std::stod`` reads 0). Only reductions the loader reads
are checked (see TX105).

Why it matters: the transmission is not loaded, so its joint is not driven. ros_control's
transmission constructors throw "Transmission reduction ratio cannot be zero."; ros2_control's
loaders catch the same exception, log "Failed to construct transmission" and return no
transmission.

Loader: ros-controls/ros_control transmission_interface/include/transmission_interface/
simple_transmission.h ``SimpleTransmission::SimpleTransmission`` (and the differential and
four-bar constructors); ros-controls/ros2_control
transmission_interface/src/simple_transmission_loader.cpp ``SimpleTransmissionLoader::load``.

Failing example::

    <robot name="r">
      <transmission name="t">
        <type>transmission_interface/SimpleTransmission</type>
        <joint name="j">
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
        </joint>
        <actuator name="m"><mechanicalReduction>0</mechanicalReduction></actuator>
      </transmission>
    </robot>

Expected finding: ``7:24 error TX106 reduction of actuator 'm' of transmission 't' is zero:
ros_control refuses it ("Transmission reduction ratio cannot be zero")``

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

Fix: write the gear ratio (``1`` for a direct drive; a negative value reverses the joint).
"""

from __future__ import annotations

from collections.abc import Iterator

from txtool.lint.context import LintContext
from txtool.lint.problem import Problem
from txtool.lint.rule_helpers import numbers_of, per_transmission
from txtool.model.numbers import parse_ros1

CODE = "TX106"
NAME = "zero-reduction"
SEVERITY = "error"
FIXABLE = False


@per_transmission
def check(ctx: LintContext) -> Iterator[Problem]:
    for tx in ctx.facts:
        ros1 = tx.ros1
        for number in numbers_of(tx):
            if number.field != "reduction" or number.unknown_written:
                continue
            plain = number.strict
            if plain is not None and plain != 0.0:
                continue  # a plain non-zero number: std::stod reads the same, or throws (TX105)
            value = plain if not ros1 else parse_ros1(number.text)
            if value != 0.0:
                continue
            effect = (
                "ros_control refuses it (\"Transmission reduction ratio cannot be zero\")"
                if ros1
                else "ros2_control's loader fails (\"Failed to construct transmission\")"
            )
            yield ctx.problem(CODE, number.element, f"{number.describe()} of {tx.label} is "
                              f"zero: {effect}")
