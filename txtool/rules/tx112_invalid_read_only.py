"""A ROS 2 transmission joint or actuator whose ``read_only`` is not ``true`` or ``false``.

ros2_control strips the attribute of C whitespace and reads it with ``parse_bool``, which
lower-cases the text (ASCII) and accepts exactly ``true`` or ``false``; anything else, such as
``1``, ``yes`` or a no-break space around the word, throws "Input string : 'x' is not a valid
boolean value. Expected 'true' or 'false'." (ros-controls/ros2_control
hardware_interface/src/component_parser.cpp:558-560 and lexical_casts.cpp:134 @53b9999). The
exception leaves the component parser, so the whole ``robot_description`` fails to load. A
missing attribute is fine (the default is false).

Failing example::

    <actuator name="joint1_motor" role="actuator1" read_only="yes"/>

Passing example::

    <actuator name="joint1_motor" role="actuator1" read_only="True"/>
"""

from __future__ import annotations

from collections.abc import Iterator

from txtool.lint.context import LintContext
from txtool.lint.problem import Problem
from txtool.lint.rule_helpers import label, per_transmission
from txtool.model.numbers import C_SPACE

CODE = "TX112"
NAME = "invalid-read-only"
SEVERITY = "error"
FIXABLE = False

_BOOLEANS = ("true", "false")


def valid_bool(text: str) -> bool:
    """What ``hardware_interface::parse_bool`` accepts: true/false in any ASCII case."""
    return text.isascii() and text.lower() in _BOOLEANS


@per_transmission
def check(ctx: LintContext) -> Iterator[Problem]:
    for tx in ctx.facts:
        if tx.ros1:
            continue
        found = tx.found
        for ref in tx.members:
            value = ref.element.get("read_only")
            if value is None or ctx.unknown(value) or valid_bool(value.strip(C_SPACE)):
                continue
            yield ctx.problem(
                CODE,
                ref.element,
                f"{ref.noun} '{ref.name}' of {label(found)} has read_only=\"{value}\": "
                "ros2_control's parse_bool accepts only true or false (any case) and throws, "
                "so the robot description fails to load",
            )
