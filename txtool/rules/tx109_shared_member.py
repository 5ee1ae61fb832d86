"""A joint or actuator in more than one transmission of the same loader: both load, a warning.

What it does: reports a joint or actuator that a transmission names when another transmission
of the same loader already does. Compared as for TX108 (per loader, per ``<ros2_control>``
component, xacro-aware); custom types are skipped, since some (``franka_hw/...``) list joints
on purpose that standard transmissions also drive.

Why it matters: neither loader rejects it, and ros2_control never applies transmissions
itself: the hardware plugin does (its own test robot shares joints between a differential
and a four-bar transmission, ros2_control_test_assets ``minimal_robot_hardware_resources``, in
the corpus). It bites when both transmissions are applied in the same direction: two
transmissions writing one joint (actuator to joint) or one actuator (joint to actuator)
overwrite each other, and the one applied last wins. Reading one shared actuator into several
joints (a motor that drives coupled fingers) is a legitimate design: a warning.

Loader: ros_control resolves each transmission's members on its own
(ros-controls/ros_control transmission_interface/src/transmission_interface_loader.cpp:39-86
@0a09467); ros2_control appends transmissions and their members without comparing them
(ros-controls/ros2_control hardware_interface/src/component_parser.cpp:474-507, :611-614
@157446a).

Failing example::

    <robot name="r">
      <transmission name="a">
        <type>transmission_interface/SimpleTransmission</type>
        <joint name="elbow">
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
        </joint>
        <actuator name="ma"><mechanicalReduction>50</mechanicalReduction></actuator>
      </transmission>
      <transmission name="b">
        <type>transmission_interface/SimpleTransmission</type>
        <joint name="elbow">
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
        </joint>
        <actuator name="mb"><mechanicalReduction>50</mechanicalReduction></actuator>
      </transmission>
    </robot>

Expected finding: ``11:5 warning TX109 joint 'elbow' of transmission 'b' is also in transmission
'a' (line 2): both load, but where both are applied the one applied last overwrites the joint's
state``

Passing example::

    <robot name="r">
      <transmission name="a">
        <type>transmission_interface/SimpleTransmission</type>
        <joint name="elbow">
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
        </joint>
        <actuator name="ma"><mechanicalReduction>50</mechanicalReduction></actuator>
      </transmission>
      <transmission name="b">
        <type>transmission_interface/SimpleTransmission</type>
        <joint name="wrist">
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
        </joint>
        <actuator name="mb"><mechanicalReduction>50</mechanicalReduction></actuator>
      </transmission>
    </robot>

Fix: give each joint and each actuator to one transmission; a coupled pair is one
differential (or four-bar) transmission, not two simple ones.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator

from txtool.dialects.read import Found
from txtool.lint.context import LintContext
from txtool.lint.problem import Problem
from txtool.lint.rule_helpers import label, member_names, scope

CODE = "TX109"
NAME = "shared-member"
SEVERITY = "warning"
FIXABLE = False


def check(ctx: LintContext) -> Iterable[Problem]:
    if _all_distinct(ctx):
        return ()  # the common case: no joint or actuator is named twice in the document
    return _shared(ctx)


def _shared(ctx: LintContext) -> Iterator[Problem]:
    owner: dict[tuple[object, ...], Found] = {}
    names: set[tuple[object, ...]] = set()
    for tx in ctx.facts:
        if tx.kind == "other" or not tx.parsed:
            continue  # ros_control skips unparsed ones before any member is used
        where = scope(ctx, tx.element) if ctx.literal else ()  # one scope after expansion
        if where is None:
            continue
        found = tx.found
        group = tx.group
        named = (group, where, tx.name)
        if tx.name and named in names:
            continue
        names.add(named)
        seen_here: set[tuple[str, str]] = set()
        for ref in tx.members:
            name = ref.name
            noun_name = (ref.noun, name)
            if not name.strip() or noun_name in seen_here or ("$" in name and ctx.unknown(name)):
                continue
            seen_here.add(noun_name)
            key = (group, where, ref.noun, name)
            first = owner.setdefault(key, found)
            if first is found:
                continue
            line = ctx.position(first.element).line
            yield ctx.problem(
                CODE,
                ref.element,
                f"{ref.noun} '{name}' of {label(found)} is also in {label(first)} (line {line}): "
                f"both load, but where both are applied the one applied last overwrites the "
                f"{ref.noun}'s {'state' if ref.noun == 'joint' else 'command'}",
            )


def _all_distinct(ctx: LintContext) -> bool:
    """No (noun, name) repeats across the transmissions: no key below can be met twice."""
    joints, actuators = member_names(ctx)
    return len(set(joints)) == len(joints) and len(set(actuators)) == len(actuators)
