"""A ROS 1 joint without ``<hardwareInterface>``: ros_control skips the joint.

ros_control's transmission parser needs at least one non-empty ``<hardwareInterface>`` in
every ``<joint>`` of a transmission ("No valid hardware interface element found in joint
'J'.", ros-controls/ros_control transmission_interface/src/transmission_parser.cpp:155-175
@14e64ea); the joint is skipped, and a transmission left without joints is not loaded ("Failed
to load joints for transmission 'T'."). Since ROS Indigo an interface written only in the
``<actuator>`` does not count (ros_control#177); gazebo_ros_control still tolerated that with
a warning. Transmissions of families with their own loaders (``pr2_mechanism_model/``,
``sr_mechanism_model/``) and ones ros_control skips for want of a ``<type>`` are not checked.

Failing example::

    <joint name="j"/>
    <actuator name="m">
      <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
      <mechanicalReduction>1</mechanicalReduction>
    </actuator>

Passing example::

    <joint name="j">
      <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
    </joint>
"""

from __future__ import annotations

from collections.abc import Iterator

from txtool.dialects.read import Found
from txtool.lint.context import LintContext
from txtool.lint.problem import Problem
from txtool.lint.support import children, label, loaded_by_ros_control, members, opaque, typed_ros1

CODE = "TX110"
NAME = "missing-interface"
SEVERITY = "error"
FIXABLE = False


def check(ctx: LintContext) -> Iterator[Problem]:
    for found in ctx.transmissions():
        if not typed_ros1(found) or not loaded_by_ros_control(found):
            continue
        for ref in members(found):
            if ref.noun != "joint" or opaque(ctx, ref.element):
                continue
            interfaces = children(ref.element, "hardwareInterface")
            if any((h.text or "").strip() for h in interfaces):
                continue
            what = "an empty <hardwareInterface>" if interfaces else "no <hardwareInterface>"
            where = " (only its actuator names one)" if _actuator_has_one(found) else ""
            yield ctx.problem(
                CODE,
                ref.element,
                f"joint '{ref.member.name}' of {label(found)} has {what}{where}: "
                "ros_control skips the joint",
            )


def _actuator_has_one(found: Found) -> bool:
    return any(
        (h.text or "").strip()
        for ref in members(found)
        if ref.noun == "actuator"
        for h in children(ref.element, "hardwareInterface")
    )
