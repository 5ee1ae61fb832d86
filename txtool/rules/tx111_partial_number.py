"""A number the loader reads only part of: text after it, hexadecimal, or split by a comment.

What it does: reports a reduction or offset the loader reads as a number followed by other
text (``50abc``, ``5_0``), in hexadecimal (``0x10``), or split by a comment or CDATA section
(``5<!-- gear -->0``). Trailing C whitespace is harmless and not reported.

Why it matters: the transmission loads (a warning), but the value is not what the file seems
to say: ``std::stod`` takes the longest valid prefix and ignores the rest, so ``50abc`` and
``5_0`` load as 50 and 5, ``0x10`` as 16. ros2_control reads the same text as no number at
all: after a port it silently uses the default, 1.0 for a reduction and 0.0 for an offset.
Both loaders read the text TinyXML's ``GetText()`` returns, the element's first text node, so
a number split by a comment is read up to the split only: reported for both dialects.

Loader: ros_control (ros-controls/ros_control transmission_interface/src/transmission_loader.cpp
:60, :95, :130 @63b6afd, ``std::stod``); ros2_control (ros-controls/ros2_control
hardware_interface/src/component_parser.cpp:145, :152-155 @157446a).

Failing example::

    <robot name="r">
      <transmission name="t">
        <type>transmission_interface/SimpleTransmission</type>
        <joint name="j">
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
        </joint>
        <actuator name="m"><mechanicalReduction>50abc</mechanicalReduction></actuator>
      </transmission>
    </robot>

Expected finding: ``7:24 warning TX111 reduction of actuator 'm' of transmission 't' is '50abc':
ros_control's std::stod reads 50 and ignores 'abc' after it; ros2_control would not read it and
silently use 1.0``

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

Fix: write the number alone, in decimal, with any comment outside the element.
"""

from __future__ import annotations

import math
from collections.abc import Iterator

from txtool.lint.context import LintContext
from txtool.lint.problem import Problem
from txtool.lint.rule_helpers import NumberRef, numbers_of, per_transmission
from txtool.model.numbers import C_SPACE, format_float, parse_ros1, parse_ros2, stod

CODE = "TX111"
NAME = "partial-number"
SEVERITY = "warning"
FIXABLE = False


@per_transmission
def check(ctx: LintContext) -> Iterator[Problem]:
    for tx in ctx.facts:
        ros1 = tx.ros1
        for number in numbers_of(tx):
            if number.unknown:
                continue
            text = number.text
            message = None if number.single else _split(number, text, ros1)
            if message is None and ros1 and number.strict is None:  # else a plain number
                message = _prefix(text, "0.0" if number.field == "offset" else "1.0")
            if message:
                yield ctx.problem(
                    CODE, number.element, f"{number.describe()} of {tx.label} {message}"
                )


def _split(number: NumberRef, text: str | None, ros1: bool) -> str | None:
    """The loader reads the first text node only; the element holds more text after it."""
    whole = number.all_text().strip(C_SPACE)
    if text is None or whole == text.strip(C_SPACE):
        return None
    value = (parse_ros1 if ros1 else parse_ros2)(text)
    if value is None or not math.isfinite(value):
        return None  # refused or defaulted: TX105
    loader = "ros_control" if ros1 else "ros2_control"
    return (
        f"is split by a comment or CDATA section: {loader} reads only the text before it, "
        f"'{text.strip(C_SPACE)}' ({format_float(value)}), not '{whole}'"
    )


def _prefix(text: str | None, default: str) -> str | None:
    if parse_ros2(text) is not None:
        return None  # a plain number (the common case)
    read = stod(text)
    if read.value is None or read.special:
        return None
    rest = read.rest.strip(C_SPACE)
    how = f"ignores '{rest}' after it" if rest else "reads it as hexadecimal"
    return (
        f"is '{(text or '').strip(C_SPACE)}': ros_control's std::stod reads "
        f"{format_float(read.value)} and {how}; ros2_control would not read it and silently "
        f"use {default}"
    )
