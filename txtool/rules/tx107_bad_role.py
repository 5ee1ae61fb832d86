"""Roles a loader refuses: coupled ROS 1 roles missing, empty, duplicated or misspelt; a ROS 2
member without the ``role`` attribute.

What it does: reports, in a ROS 1 DifferentialTransmission or FourBarLinkageTransmission, a
joint or actuator whose ``<role>`` is missing, empty, not exactly ``joint1``/``joint2`` or
``actuator1``/``actuator2`` (case-sensitive), or the same as another member's; and in ROS 2, a
``<joint>`` or ``<actuator>`` of a transmission without the ``role`` attribute (a ``<role>``
child element instead is TX303's business). SimpleTransmission ignores roles.

Why it matters: ros_control's coupled loaders refuse the transmission ("Joint 'J' of
transmission 'T' does not specify a valid <role> element."); they sort the members by role.
ros2_control's parser throws "no attribute 'role' in 'joint' tag" and the hardware component
fails to load; the value itself is not used.

Loader: ros_control (ros-controls/ros_control transmission_interface/src/transmission_loader.cpp
``TransmissionLoader::getJointRole``, ``getActuatorRole``, called by
differential_transmission_loader.cpp and four_bar_linkage_transmission_loader.cpp);
ros2_control (ros-controls/ros2_control hardware_interface/src/component_parser.cpp
``parse_transmission_from_xml``).

Failing example::

    <robot name="r">
      <transmission name="wrist">
        <type>transmission_interface/DifferentialTransmission</type>
        <joint name="a">
          <role>joint1</role>
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
        </joint>
        <joint name="b">
          <role>joint1</role>
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
        </joint>
        <actuator name="ma">
          <role>actuator1</role><mechanicalReduction>50</mechanicalReduction>
        </actuator>
        <actuator name="mb">
          <role>actuator2</role><mechanicalReduction>50</mechanicalReduction>
        </actuator>
      </transmission>
    </robot>

Expected finding: ``9:7 error TX107 joint 'b' of transmission 'wrist' has role 'joint1' like
joint 'a': roles must differ; ros_control refuses the transmission``

Passing example::

    <robot name="r">
      <transmission name="wrist">
        <type>transmission_interface/DifferentialTransmission</type>
        <joint name="a">
          <role>joint1</role>
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
        </joint>
        <joint name="b">
          <role>joint2</role>
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
        </joint>
        <actuator name="ma">
          <role>actuator1</role><mechanicalReduction>50</mechanicalReduction>
        </actuator>
        <actuator name="mb">
          <role>actuator2</role><mechanicalReduction>50</mechanicalReduction>
        </actuator>
      </transmission>
    </robot>

Fix: give the two joints ``joint1`` and ``joint2`` and the two actuators ``actuator1`` and
``actuator2``, in the order of the transmission's maths (see ``txtool map``).
"""

from __future__ import annotations

from collections.abc import Iterator

from txtool.dialects.read import Found
from txtool.lint.context import LintContext
from txtool.lint.problem import Problem
from txtool.lint.rule_helpers import MemberRef, children, label, members, opaque, per_transmission

CODE = "TX107"
NAME = "bad-role"
SEVERITY = "error"
FIXABLE = False


@per_transmission
def check(ctx: LintContext) -> Iterator[Problem]:
    for tx in ctx.facts:
        if not tx.ros1:
            yield from _ros2(ctx, tx.found)
        elif tx.kind in _COUPLED and tx.typed_ros1 and not opaque(ctx, tx.element):
            yield from _ros1_coupled(ctx, tx.found)


_COUPLED = ("differential", "four_bar")


def _ros1_coupled(ctx: LintContext, found: Found) -> Iterator[Problem]:
    taken: dict[tuple[str, str], str] = {}
    for ref in members(found):
        valid = (f"{ref.noun}1", f"{ref.noun}2")
        who = f"{ref.noun} '{ref.name}' of {label(found)}"
        roles = children(ref.element, "role")
        role = (roles[0].text or "").strip() if roles else None
        if ctx.unknown(role):
            continue
        where = roles[0] if roles else ref.element
        refused = "ros_control refuses the transmission"
        if role is None:
            message = f"{who} has no <role>: expected '{valid[0]}' or '{valid[1]}'; {refused}"
        elif role not in valid:
            shown = f"role '{role}'" if role else "an empty <role>"
            message = f"{who} has {shown}, expected '{valid[0]}' or '{valid[1]}': {refused}"
        elif (ref.noun, role) in taken:
            message = (
                f"{who} has role '{role}' like {ref.noun} '{taken[(ref.noun, role)]}': "
                f"roles must differ; {refused}"
            )
        else:
            taken[(ref.noun, role)] = ref.name
            continue
        yield ctx.problem(CODE, where, message)


def _ros2(ctx: LintContext, found: Found) -> Iterator[Problem]:
    for ref in members(found):
        if ref.element.get("role") is not None or _role_element(ref):
            continue
        yield ctx.problem(
            CODE,
            ref.element,
            f"{ref.noun} '{ref.name}' of {label(found)} has no role attribute: "
            f"ros2_control throws \"no attribute 'role' in '{ref.noun}' tag\"",
            refuses_whole=True,
        )


def _role_element(ref: MemberRef) -> bool:
    return bool(children(ref.element, "role"))
