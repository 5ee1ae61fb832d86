"""Two transmissions with the same name, for the same loader.

ros_control registers transmission handles by name, so the later transmission replaces the
earlier one; ros2_control keeps both in the component's list but anything that looks a
transmission up by name (hardware plugins, logs) sees only one. Names are compared per
loader: ROS 1 transmissions with each other, ROS 2 transmissions within one
``<ros2_control>`` component. In a literal xacro file, transmissions in different macros or
under ``xacro:if``/``xacro:unless`` are not compared, nor names containing ``${...}``.

Failing example::

    <transmission name="t">...</transmission>
    <transmission name="t">...</transmission>

Passing example::

    <transmission name="t1">...</transmission>
    <transmission name="t2">...</transmission>
"""

from __future__ import annotations

from collections.abc import Iterator

from txtool.dialects.read import Found
from txtool.lint.context import LintContext
from txtool.lint.problem import Problem
from txtool.lint.support import loader_group, parsed, scope

CODE = "TX108"
NAME = "duplicate-name"
SEVERITY = "error"
FIXABLE = False


def check(ctx: LintContext) -> Iterator[Problem]:
    first: dict[tuple[object, ...], Found] = {}
    for found in ctx.transmissions():
        name = found.transmission.name
        where = scope(ctx, found.element)
        if not name.strip() or ctx.unknown(name) or where is None or not parsed(found):
            continue
        key = (loader_group(found), where, name)
        if key not in first:
            first[key] = found
            continue
        line = ctx.position(first[key].element).line
        effect = (
            "ros_control registers transmissions by name and the later one replaces it"
            if found.transmission.dialect == "ros1"
            else "anything that looks transmissions up by name sees only one of them"
        )
        yield ctx.problem(
            CODE, found.element, f"transmission name '{name}' is already used on line {line}: "
            f"{effect}"
        )
