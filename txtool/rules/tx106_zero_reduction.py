"""A reduction of zero, which both loaders refuse.

What it does: reports a reduction the loader reads whose value is zero: ``0``, ``-0`` and
``0.0``, and in ROS 1 ``0abc`` too (``std::stod`` reads 0). In ROS 2 also a number too small
for a double (``1e-400``, ``2e-324``): Humble reads it with ``istringstream``, which gives 0,
while Jazzy and later refuse the text and use the default 1.0. That one is an **error** where
only Humble reads the file (``--ros-distro humble``), a **warning** giving each
distribution's reading where a later one may read it too, and nothing where only Jazzy or
later do (TX105 then reports the silent default). Only reductions the loader reads are checked
(see TX105).

Why it matters: the transmission is not loaded, so its joint is not driven. ros_control's
transmission constructors throw "Transmission reduction ratio cannot be zero."; ros2_control's
loaders catch the same exception, log "Failed to construct transmission" and return no
transmission.

Loader: ros-controls/ros_control transmission_interface/include/transmission_interface/
simple_transmission.h ``SimpleTransmission::SimpleTransmission`` (and the differential and
four-bar constructors); ros-controls/ros2_control
transmission_interface/src/simple_transmission_loader.cpp ``SimpleTransmissionLoader::load``;
Humble's reading: hardware_interface/src/lexical_casts.cpp ``impl::stod`` below C++20
(``std::istringstream``, @53b9999).

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
from txtool.lint.rule_helpers import numbers_of, per_transmission, ros2_readings_of
from txtool.model.distro import NumberReading
from txtool.model.numbers import C_SPACE, format_float, parse_ros1, parse_ros2

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
            if not ros1 and plain is None:
                problem = _underflow(number.text, ros2_readings_of(ctx))
                if problem is not None:
                    message, mixed = problem
                    yield ctx.problem(CODE, number.element,
                                      f"{number.describe()} of {tx.label} {message}",
                                      loader_severity="warning" if mixed else None)
                continue
            value = plain if not ros1 else parse_ros1(number.text)
            if value != 0.0:
                continue
            effect = (
                "ros_control refuses it (\"Transmission reduction ratio cannot be zero\")"
                if ros1
                else _FAILS
            )
            yield ctx.problem(CODE, number.element, f"{number.describe()} of {tx.label} is "
                              f"zero: {effect}")


_FAILS = "ros2_control's loader fails (\"Failed to construct transmission\")"


def _underflow(text: str | None,
               readings: tuple[NumberReading, ...]) -> tuple[str, bool] | None:
    """What the ROS 2 builds reading the file make of a text only Humble's reads as zero (a
    number too small for a double; ``from_chars`` refuses it): (message, whether a later
    build reads it too), or None."""
    if NumberReading.ISTRINGSTREAM not in readings or (
            parse_ros2(text, NumberReading.ISTRINGSTREAM) != 0.0):
        return None
    shown = (text or "").strip(C_SPACE)
    refused = (f"is '{shown}', which Humble's ros2_control reads as 0 (too small for a "
               f"double): its loader fails (\"Failed to construct transmission\")")
    if readings == (NumberReading.ISTRINGSTREAM,):
        return refused, False
    later = parse_ros2(text, NumberReading.FROM_CHARS)
    said = "silently use 1.0" if later is None else f"read {format_float(later)}"
    return f"{refused}; Jazzy's and later {said}", True
