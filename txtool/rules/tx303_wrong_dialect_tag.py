"""A ROS 1 spelling in a ROS 2 transmission, or the reverse.

What it checks
    * In a ROS 2 transmission (inside ``<ros2_control>`` or carrying ``<plugin>``):
      a ``<type>`` element (ros2_control reads ``<plugin>``), ``<mechanicalReduction>``
      (it reads ``<mechanical_reduction>``), ``<hardwareInterface>`` or
      ``<hardware_interface>`` (interfaces come from the component's ``<joint>``), and a
      ``<role>`` element on a joint or actuator (ros2_control reads the ``role=`` attribute;
      a transmission written that way is Proposal 1 of the ROS 2 format, which ros2_control
      never adopted).
    * In a ROS 1 transmission: ``<mechanical_reduction>`` and ``<hardware_interface>``
      (ros_control reads ``<mechanicalReduction>`` and ``<hardwareInterface>``).

Why
    Both loaders ignore elements they do not know, without a word (dynamixel_hardware#67:
    "Everything loads smoothly, but the system is simply ignoring the mechanical reduction").
    A reduction in the other dialect's spelling silently becomes 1.0 in ROS 2 and is
    "missing" (the transmission fails) or 1.0 in ROS 1; a ``<role>`` element without the
    attribute makes ros2_control throw "no attribute 'role' in 'joint' tag with name 'J'".

Failing example::

    <ros2_control name="HW" type="system">
      <joint name="joint1"><command_interface name="position"/></joint>
      <transmission name="t">
        <plugin>transmission_interface/SimpleTransmission</plugin>
        <joint name="joint1" role="joint1">
          <mechanicalReduction>50</mechanicalReduction>
        </joint>
      </transmission>
    </ros2_control>

Passing example: ``<mechanical_reduction>50</mechanical_reduction>``.
"""

from __future__ import annotations

from collections.abc import Iterator

from lxml import etree

from txtool.dialects.read import Found
from txtool.io.xmlio import local
from txtool.lint.context import LintContext
from txtool.lint.problem import Problem
from txtool.lint.support import ROS2_SPELLINGS, children, label, per_transmission
from txtool.model.robot import child_index

CODE = "TX303"
NAME = "wrong-dialect-tag"
SEVERITY = "error"
FIXABLE = False

_ROS1_SPELLINGS = frozenset({"mechanicalReduction", "hardwareInterface", "hardware_interface"})


@per_transmission
def check(ctx: LintContext) -> Iterator[Problem]:
    for tx in ctx.facts:
        if tx.ros1:
            if ROS2_SPELLINGS.isdisjoint(tx.kids):
                for ref in tx.members:
                    if not ROS2_SPELLINGS.isdisjoint(ref.kids):
                        break
                else:
                    continue  # the common case: say nothing, build no message
            yield from _check_ros1(ctx, tx.found)
        else:
            yield from _check_ros2(ctx, tx.found)


def _members(found: Found) -> list[etree._Element]:
    return children(found.element, "joint") + children(found.element, "actuator")


def _whose(found: Found, owner: etree._Element) -> str:
    if owner is found.element:
        return label(found)
    return f"{local(owner)} '{owner.get('name', '')}' of {label(found)}"


def _check_ros2(ctx: LintContext, found: Found) -> Iterator[Problem]:
    for element in children(found.element, "type"):
        yield ctx.problem(
            CODE,
            element,
            f"{_whose(found, found.element)} uses the ROS 1 <type> element: ros2_control "
            "ignores it and reads the type from <plugin>",
        )
    for owner in [found.element, *_members(found)]:
        kids = child_index(owner)
        if not _ROS1_SPELLINGS.intersection(kids):
            continue
        where = _whose(found, owner)
        for element in kids.get("mechanicalReduction", ()):
            yield ctx.problem(
                CODE,
                element,
                f"{where} uses the ROS 1 <mechanicalReduction>: ros2_control reads only "
                "<mechanical_reduction>, so the reduction silently becomes 1.0",
            )
        for spelling in ("hardwareInterface", "hardware_interface"):
            for element in kids.get(spelling, ()):
                yield ctx.problem(
                    CODE,
                    element,
                    f"{where} has a <{spelling}> element: ros2_control ignores it and takes "
                    "the interfaces from the <joint> of the <ros2_control> component",
                )
    for member in _members(found):
        for element in children(member, "role"):
            yield ctx.problem(CODE, element, _role_message(found, member))


def _role_message(found: Found, member: etree._Element) -> str:
    where = _whose(found, member)
    if member.get("role") is not None:
        return f"{where} has a <role> element beside its role attribute: ros2_control ignores it"
    return (
        f"{where} gives its role as a <role> element (the ROS 2 Proposal 1 form): "
        f"ros2_control reads only the role attribute and throws \"no attribute 'role' in "
        f"'{local(member)}' tag\""
    )


def _check_ros1(ctx: LintContext, found: Found) -> Iterator[Problem]:
    for owner in [found.element, *_members(found)]:
        kids = child_index(owner)
        if "mechanical_reduction" not in kids and "hardware_interface" not in kids:
            continue  # the common case: say nothing, build no message
        where = _whose(found, owner)
        for element in kids.get("mechanical_reduction", ()):
            yield ctx.problem(
                CODE,
                element,
                f"{where} uses the ROS 2 <mechanical_reduction>: ros_control reads only "
                "<mechanicalReduction> and never sees this value",
            )
        for element in kids.get("hardware_interface", ()):
            yield ctx.problem(
                CODE,
                element,
                f"{where} has a <hardware_interface> element: ros_control reads only "
                "<hardwareInterface> and ignores it",
            )
