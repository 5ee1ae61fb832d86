"""A reduction of zero, which both loaders refuse.

ros_control's transmission constructors throw "Transmission reduction ratio cannot be zero."
and the transmission is not loaded; ros2_control's loaders catch the same exception, log
"Failed to construct transmission" and return no transmission. Only reductions the loader
reads are checked (see TX105); ``-0`` and ``0.0`` count as zero, and so does ``0abc`` in
ROS 1 (``std::stod`` reads 0).

Failing example::

    <actuator name="m">
      <mechanicalReduction>0</mechanicalReduction>
    </actuator>

Passing example::

    <actuator name="m">
      <mechanicalReduction>50</mechanicalReduction>
    </actuator>
"""

from __future__ import annotations

from collections.abc import Iterator

from txtool.lint.context import LintContext
from txtool.lint.problem import Problem
from txtool.lint.support import label, read_numbers
from txtool.model.numbers import parse_ros1, parse_ros2

CODE = "TX106"
NAME = "zero-reduction"
SEVERITY = "error"
FIXABLE = False


def check(ctx: LintContext) -> Iterator[Problem]:
    for found in ctx.transmissions():
        ros1 = found.transmission.dialect == "ros1"
        for number in read_numbers(found):
            if number.field != "reduction" or ctx.unknown(number.element.text):
                continue
            value = (parse_ros1 if ros1 else parse_ros2)(number.text)
            if value != 0.0:
                continue
            effect = (
                "ros_control refuses it (\"Transmission reduction ratio cannot be zero\")"
                if ros1
                else "ros2_control's loader fails (\"Failed to construct transmission\")"
            )
            yield ctx.problem(CODE, number.element, f"{number.describe()} of {label(found)} is "
                              f"zero: {effect}")
