"""A ROS 1 spelling in a ROS 2 transmission, or the reverse.

What it does: reports, in a ROS 2 transmission (inside ``<ros2_control>`` or carrying
``<plugin>``), a ``<type>`` element (ros2_control reads ``<plugin>``), ``<mechanicalReduction>``
(it reads ``<mechanical_reduction>``), ``<hardwareInterface>`` or ``<hardware_interface>``
(interfaces come from the component's ``<joint>``), and a ``<role>`` element on a joint or
actuator (ros2_control reads the ``role=`` attribute; a transmission written that way is
Proposal 1 of the ROS 2 format, which ros2_control never adopted); in a ROS 1 transmission,
``<mechanical_reduction>`` and ``<hardware_interface>`` (ros_control reads
``<mechanicalReduction>`` and ``<hardwareInterface>``).

Why it matters: both loaders ignore elements they do not know, without a word
(dynamixel_hardware#67: "Everything loads smoothly, but the system is simply ignoring the
mechanical reduction"). A reduction in the other dialect's spelling silently becomes 1.0 in
ROS 2 and is "missing" (the transmission fails) or 1.0 in ROS 1; a ``<role>`` element without
the attribute makes ros2_control throw "no attribute 'role' in 'joint' tag with name 'J'". An
error where the loader reads something other than written; a **warning** where ros2_control
ends up with the written value anyway: a ``<type>`` beside a ``<plugin>`` of the same text, a
``<mechanicalReduction>`` equal to the ``<mechanical_reduction>`` beside it or, without one,
equal to 1.

Loader: ros2_control (ros-controls/ros2_control hardware_interface/src/component_parser.cpp
``parse_transmission_from_xml`` reads ``<plugin>``, ``get_parameter_value_or`` reads
``<mechanical_reduction>`` or defaults to 1.0); ros_control (ros-controls/ros_control
transmission_interface/src/transmission_loader.cpp ``getActuatorReduction``).

Failing example::

    <robot name="r">
      <ros2_control name="HW" type="system">
        <hardware><plugin>mock_components/GenericSystem</plugin></hardware>
        <joint name="joint1"><command_interface name="position"/></joint>
        <transmission name="t">
          <plugin>transmission_interface/SimpleTransmission</plugin>
          <joint name="joint1" role="joint1">
            <mechanicalReduction>50</mechanicalReduction>
          </joint>
          <actuator name="m" role="actuator1"/>
        </transmission>
      </ros2_control>
    </robot>

Expected finding: ``8:9 error TX303 joint 'joint1' of transmission 't' uses the ROS 1
<mechanicalReduction>: ros2_control reads only <mechanical_reduction>, so the reduction silently
becomes 1.0: write <mechanical_reduction>50</mechanical_reduction>``

Passing example::

    <robot name="r">
      <ros2_control name="HW" type="system">
        <hardware><plugin>mock_components/GenericSystem</plugin></hardware>
        <joint name="joint1"><command_interface name="position"/></joint>
        <transmission name="t">
          <plugin>transmission_interface/SimpleTransmission</plugin>
          <joint name="joint1" role="joint1">
            <mechanical_reduction>50</mechanical_reduction>
          </joint>
          <actuator name="m" role="actuator1"/>
        </transmission>
      </ros2_control>
    </robot>

Fix: write the element as the dialect spells it, as the message says where the value is
plain text (``<mechanical_reduction>50</mechanical_reduction>``, ``role="joint1"``);
``txtool migrate --write --to ros2-p2`` converts a whole transmission.
"""

from __future__ import annotations

from collections.abc import Iterator

from lxml import etree

from txtool.dialects.read import Found, text_of
from txtool.io.xmlio import local
from txtool.lint.context import LintContext
from txtool.lint.problem import Problem
from txtool.lint.rule_helpers import (
    ROS2_SPELLINGS,
    children,
    label,
    loader_text,
    per_transmission,
)
from txtool.model.numbers import parse_ros2
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
    plugins = children(found.element, "plugin")
    loaded = (text_of(plugins[0]) or "").strip() if plugins else None
    for element in children(found.element, "type"):
        same = loaded is not None and (text_of(element) or "").strip() == loaded
        yield ctx.problem(
            CODE,
            element,
            f"{_whose(found, found.element)} uses the ROS 1 <type> element: ros2_control "
            "ignores it and reads the type from <plugin>"
            + (", which names the same type" if same else ""),
            loader_severity="warning" if same else None,
        )
    for owner in [found.element, *_members(found)]:
        kids = child_index(owner)
        if not _ROS1_SPELLINGS.intersection(kids):
            continue
        where = _whose(found, owner)
        used = _used_reduction(kids)
        for element in kids.get("mechanicalReduction", ()):
            written = parse_ros2(loader_text(element))
            if written is not None and written == used:
                yield ctx.problem(
                    CODE, element,
                    f"{where} uses the ROS 1 <mechanicalReduction>: ros2_control reads only "
                    f"<mechanical_reduction> and uses {used:g}, the value written here anyway",
                    loader_severity="warning",
                )
                continue
            alone = "mechanical_reduction" not in kids
            yield ctx.problem(
                CODE,
                element,
                f"{where} uses the ROS 1 <mechanicalReduction>: ros2_control reads only "
                + ("<mechanical_reduction>, so the reduction silently becomes 1.0"
                   if alone else "the <mechanical_reduction> beside it, which says otherwise")
                + (_respelt(element, "mechanical_reduction") if alone else ""),
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
            yield ctx.problem(CODE, element, _role_message(found, member, element))


def _used_reduction(kids: dict[str, list[etree._Element]]) -> float | None:
    """The reduction ros2_control takes from a member: its first ``<mechanical_reduction>``
    with text, or 1.0 (component_parser.cpp ``get_parameter_value_or``); None when that text is
    no number (TX105's business)."""
    for element in kids.get("mechanical_reduction", ()):
        text = loader_text(element)
        if text is not None:
            return parse_ros2(text)
    return 1.0


def _role_message(found: Found, member: etree._Element, element: etree._Element) -> str:
    where = _whose(found, member)
    if member.get("role") is not None:
        return f"{where} has a <role> element beside its role attribute: ros2_control ignores it"
    role = (text_of(element) or "").strip()
    fix = (f": write <{local(member)} name=\"{member.get('name', '')}\" role=\"{role}\">"
           if role and '"' not in role else "")
    return (
        f"{where} gives its role as a <role> element (the ROS 2 Proposal 1 form): "
        f"ros2_control reads only the role attribute and throws \"no attribute 'role' in "
        f"'{local(member)}' tag\"{fix}"
    )


def _respelt(element: etree._Element, spelling: str) -> str:
    """``: write <spelling>TEXT</spelling>``, the one obvious fix, when the value is plain text
    (one that holds markup or an expression is for the author to carry over)."""
    text = (text_of(element) or "").strip()
    if not text or len(element) or any(c in text for c in "<&$"):
        return ""
    return f": write <{spelling}>{text}</{spelling}>"


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
                "<mechanicalReduction> and never sees this value"
                + ("" if "mechanicalReduction" in kids
                   else _respelt(element, "mechanicalReduction")),
            )
        for element in kids.get("hardware_interface", ()):
            yield ctx.problem(
                CODE,
                element,
                f"{where} has a <hardware_interface> element: ros_control reads only "
                "<hardwareInterface> and ignores it",
            )
