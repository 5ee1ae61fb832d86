"""A transmission, joint or actuator without a ``name`` attribute, or with an empty one.

What it does: reports a ``<transmission>``, or a ``<joint>`` or ``<actuator>`` of one, whose
``name`` attribute is missing or empty, in either dialect.

Why it matters: ros_control (ROS 1) logs "No name attribute specified for transmission." and
skips the transmission; a joint or actuator without ``name`` makes it drop every joint (or
actuator) of the transmission, so the transmission is skipped too; an empty member name skips
that member. ros2_control's parser throws ``no attribute 'name' in '<tag>' tag`` and the
hardware component fails to load; an empty name is accepted but nothing can refer to it.

Loader: ros_control (ros-controls/ros_control transmission_interface/src/transmission_parser.cpp
``TransmissionParser::parse``, ``parseJoints``, ``parseActuators``); ros2_control
(ros-controls/ros2_control hardware_interface/src/component_parser.cpp ``get_attribute_value``,
called by ``parse_transmission_from_xml``).

Failing example::

    <robot name="r">
      <transmission>
        <type>transmission_interface/SimpleTransmission</type>
        <joint name="j">
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
        </joint>
        <actuator name="m"><mechanicalReduction>50</mechanicalReduction></actuator>
      </transmission>
    </robot>

Expected finding: ``2:3 error TX100 unnamed transmission has no name: ros_control skips it``

Passing example::

    <robot name="r">
      <transmission name="shoulder_trans">
        <type>transmission_interface/SimpleTransmission</type>
        <joint name="j">
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
        </joint>
        <actuator name="m"><mechanicalReduction>50</mechanicalReduction></actuator>
      </transmission>
    </robot>

Fix: name the transmission (the joint's name with ``_trans``, say) and each member after the
URDF joint or the actuator it stands for.
"""

from __future__ import annotations

from collections.abc import Iterator

from lxml import etree

from txtool.lint.context import LintContext
from txtool.lint.problem import Problem
from txtool.lint.rule_helpers import per_transmission

CODE = "TX100"
NAME = "missing-name"
SEVERITY = "error"
FIXABLE = False


@per_transmission
def check(ctx: LintContext) -> Iterator[Problem]:
    for tx in ctx.facts:
        if tx.name.strip():
            for ref in tx.members:
                if not ref.name.strip():
                    break
            else:
                continue  # the common case: every name is there
        ros1 = tx.ros1
        what = _consequence(tx.element, "transmission", ros1, member=False)
        if what:
            yield ctx.problem(CODE, tx.element, f"{tx.label} {what}",
                              refuses_whole=_throws(tx.element, ros1))
        for ref in tx.members:
            what = _consequence(ref.element, ref.noun, ros1, member=True)
            if what:
                yield ctx.problem(CODE, ref.element, f"{ref.noun} of {tx.label} {what}",
                                  refuses_whole=_throws(ref.element, ros1))


def _throws(element: etree._Element, ros1: bool) -> bool:
    """ros2_control's parser throws for a missing name: nothing of the robot loads."""
    return not ros1 and element.get("name") is None


def _consequence(element: etree._Element, tag: str, ros1: bool, *, member: bool) -> str | None:
    name = element.get("name")
    if name is None:
        if not ros1:
            return f"has no name: ros2_control throws \"no attribute 'name' in '{tag}' tag\""
        if member:
            return f"has no name: ros_control drops every {tag} of the transmission and skips it"
        return "has no name: ros_control skips it"
    if name.strip():
        return None
    if not ros1:
        return "has an empty name: ros2_control accepts it but nothing can refer to it"
    if member:
        return f"has an empty name: ros_control skips this {tag}"
    return "has an empty name: ros_control skips it"
