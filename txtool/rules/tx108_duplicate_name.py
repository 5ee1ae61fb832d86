"""Two transmissions with the same name, for the same loader: both load, a warning.

What it does: reports a transmission whose name another transmission of the same loader
already has: ROS 1 transmissions with each other, ROS 2 transmissions within one
``<ros2_control>`` component. In a literal xacro file, transmissions in different macros or
under ``xacro:if``/``xacro:unless`` are not compared, nor names containing ``${...}``.

Why it matters: both load. ros_control registers the transmission handles by name, so the
later one overwrites the earlier with a warning; its own loader test allows this on purpose
("We allow to overwrite an existing transmission in the same way a hardware interface can be
overwritten"). ros2_control appends every ``<transmission>`` without comparing names; it bites
only where something looks a transmission up by name (a hardware plugin, logs) and finds one
of them.

Loader: ros_control (ros-controls/ros_control
transmission_interface/test/transmission_interface_loader_test.cpp:230-243 @3e1dd9d);
ros2_control (ros-controls/ros2_control hardware_interface/src/component_parser.cpp:611-614
@157446a).

Failing example::

    <robot name="r">
      <transmission name="t">
        <type>transmission_interface/SimpleTransmission</type>
        <joint name="a">
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
        </joint>
        <actuator name="ma"><mechanicalReduction>50</mechanicalReduction></actuator>
      </transmission>
      <transmission name="t">
        <type>transmission_interface/SimpleTransmission</type>
        <joint name="b">
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
        </joint>
        <actuator name="mb"><mechanicalReduction>50</mechanicalReduction></actuator>
      </transmission>
    </robot>

Expected finding: ``9:3 warning TX108 transmission name 't' is already used on line 2:
ros_control loads both and the later one overwrites the handles of the earlier``

Passing example::

    <robot name="r">
      <transmission name="ta">
        <type>transmission_interface/SimpleTransmission</type>
        <joint name="a">
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
        </joint>
        <actuator name="ma"><mechanicalReduction>50</mechanicalReduction></actuator>
      </transmission>
      <transmission name="tb">
        <type>transmission_interface/SimpleTransmission</type>
        <joint name="b">
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
        </joint>
        <actuator name="mb"><mechanicalReduction>50</mechanicalReduction></actuator>
      </transmission>
    </robot>

Fix: give each transmission a name of its own (the joint's name with ``_trans``, say).
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
