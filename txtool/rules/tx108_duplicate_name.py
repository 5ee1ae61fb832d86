"""Two transmissions with the same name, for the same loader: both load, a warning.

ros_control loads both and registers the transmission handles by name, so the later one
overwrites the earlier with a warning; its own loader test allows this on purpose
(ros-controls/ros_control transmission_interface/test/transmission_interface_loader_test.cpp
:230-243 @3e1dd9d, "We allow to overwrite an existing transmission in the same way a hardware
interface can be overwritten"). ros2_control's parser appends every ``<transmission>`` to the
component's list without comparing names (hardware_interface/src/component_parser.cpp:611-614
@157446a), so both load too; it bites only where something looks a transmission up by name
(a hardware plugin, logs) and finds one of them. Names are compared per loader: ROS 1
transmissions with each other, ROS 2 transmissions within one ``<ros2_control>`` component.
In a literal xacro file, transmissions in different macros or under
``xacro:if``/``xacro:unless`` are not compared, nor names containing ``${...}``.

Failing example::

    <transmission name="t">...</transmission>
    <transmission name="t">...</transmission>

Passing example::

    <transmission name="t1">...</transmission>
    <transmission name="t2">...</transmission>
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator

from txtool.dialects.read import Found
from txtool.lint.context import LintContext
from txtool.lint.problem import Problem
from txtool.lint.rule_helpers import scope

CODE = "TX108"
NAME = "duplicate-name"
SEVERITY = "warning"
FIXABLE = False


def check(ctx: LintContext) -> Iterable[Problem]:
    names = [tx.name for tx in ctx.facts]
    if len(set(names)) == len(names):
        return ()  # every name differs (the keys below hold the name): nothing is repeated
    return _repeated(ctx)


def _repeated(ctx: LintContext) -> Iterator[Problem]:
    first: dict[tuple[object, ...], Found] = {}
    for tx in ctx.facts:
        name = tx.name
        if not name.strip() or not tx.parsed or ("$" in name and ctx.unknown(name)):
            continue
        where = scope(ctx, tx.element) if ctx.literal else ()  # one scope after expansion
        if where is None:
            continue
        found = tx.found
        key = (tx.group, where, name)
        if key not in first:
            first[key] = found
            continue
        line = ctx.position(first[key].element).line
        effect = (
            "ros_control loads both and the later one overwrites the handles of the earlier"
            if tx.ros1
            else "ros2_control loads both; a plugin that looks transmissions up by name finds "
            "only one of them"
        )
        yield ctx.problem(
            CODE, found.element, f"transmission name '{name}' is already used on line {line}: "
            f"{effect}"
        )
