"""Roles a loader refuses: coupled ROS 1 roles missing, empty, duplicated or misspelt; a ROS 2
member without the ``role`` attribute.

ros_control's DifferentialTransmission and FourBarLinkageTransmission loaders require a
``<role>`` on both joints and both actuators, exactly ``joint1``/``joint2`` and
``actuator1``/``actuator2`` (case-sensitive) and all different ("Joint 'J' of transmission 'T'
does not specify a valid <role> element."); they sort the members by role. SimpleTransmission
ignores roles. ros2_control's parser requires a ``role`` attribute on every ``<joint>`` and
``<actuator>`` of a transmission and throws "no attribute 'role' in 'joint' tag" without it
(a ``<role>`` child element instead is TX303's business); the value itself is not used.

Failing example::

    <transmission name="wrist">
      <type>transmission_interface/DifferentialTransmission</type>
      <joint name="a"><role>joint1</role>...</joint>
      <joint name="b"><role>joint1</role>...</joint>
      ...
    </transmission>

Passing example::

    <transmission name="wrist">
      <type>transmission_interface/DifferentialTransmission</type>
      <joint name="a"><role>joint1</role>...</joint>
      <joint name="b"><role>joint2</role>...</joint>
      ...
    </transmission>
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
        )


def _role_element(ref: MemberRef) -> bool:
    return bool(children(ref.element, "role"))
