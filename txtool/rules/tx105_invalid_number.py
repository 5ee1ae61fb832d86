"""A reduction or offset the loader reads that is not a finite number.

ros_control (ROS 1) parses with ``std::stod``: text without a leading number (``fifty``, an
empty element) makes it refuse the transmission; ``inf`` and ``nan`` are accepted and poison
every value the transmission maps; trailing junk is silently dropped (``50abc`` reads as 50).
ros2_control parses the whole stripped text and, on any failure (junk, ``inf``, ``nan``,
empty), **silently** uses the default: 1.0 for ``<mechanical_reduction>``, 0.0 for
``<offset>``. Only values the loader reads are checked (ROS 1: actuator reductions, joint
offsets, and joint reductions of coupled types; ROS 2: joint reductions and offsets, and
actuator reductions of coupled types). Values containing ``${...}`` in a literal xacro file
are unknown and not checked.

Failing example::

    <joint name="j" role="joint1">
      <mechanical_reduction>fifty</mechanical_reduction>
    </joint>

Passing example::

    <joint name="j" role="joint1">
      <mechanical_reduction>50</mechanical_reduction>
    </joint>
"""

from __future__ import annotations

import math
from collections.abc import Iterator

from txtool.lint.context import LintContext
from txtool.lint.problem import Problem
from txtool.lint.support import label, read_numbers
from txtool.model.numbers import format_float, parse_ros1, parse_ros2, parse_strict

CODE = "TX105"
NAME = "invalid-number"
SEVERITY = "error"
FIXABLE = False


def check(ctx: LintContext) -> Iterator[Problem]:
    for found in ctx.transmissions():
        for number in read_numbers(found):
            text = number.element.text
            if ctx.unknown(text):
                continue
            if found.transmission.dialect == "ros1":
                problem = _ros1(text)
            else:
                problem = _ros2(text, default="0.0" if number.field == "offset" else "1.0")
            if problem:
                message = f"{number.describe()} of {label(found)} {problem}"
                yield ctx.problem(CODE, number.element, message)


def _ros1(text: str | None) -> str | None:
    value = parse_ros1(text)
    if value is None:
        shown = f"'{text}'" if text and text.strip() else "empty"
        return f"is {shown}, not a number: ros_control refuses the transmission"
    if not math.isfinite(value):
        shown = (text or "").strip()
        return f"is '{shown}': ros_control accepts it and maps every value to inf or nan"
    if parse_strict(text) is None:
        return (
            f"is '{(text or '').strip()}', not a plain number: ros_control's std::stod reads "
            f"{format_float(value)} and ignores the rest"
        )
    return None


def _ros2(text: str | None, default: str) -> str | None:
    if parse_ros2(text) is not None:
        return None
    shown = f"'{text.strip()}'" if text and text.strip() else "empty"
    return f"is {shown}, not a finite number: ros2_control silently uses {default}"
