"""A standard transmission with the wrong number of joints or actuators.

SimpleTransmission takes 1 joint and 1 actuator; DifferentialTransmission and
FourBarLinkageTransmission take 2 of each. ros_control (ROS 1) refuses any other count
("Expected 1 actuators, got 2."). ros2_control's simple loader reads only the first joint (it
fails with none, and a component of ``type="actuator"`` throws for more than one); a simple
transmission needs no ``<actuator>`` there, since the parser or the hardware plugin supplies
it. The coupled loaders fail with fewer than 2 joints or actuators and ``configure`` throws
for more. Custom types are not counted, nor literal xacro transmissions whose members are
produced by ``xacro:if`` or macro calls.

Failing example::

    <transmission name="t">
      <type>transmission_interface/SimpleTransmission</type>
      <joint name="a">...</joint>
      <joint name="b">...</joint>
      <actuator name="m">...</actuator>
    </transmission>

Passing example::

    <transmission name="t">
      <type>transmission_interface/SimpleTransmission</type>
      <joint name="a">...</joint>
      <actuator name="m">...</actuator>
    </transmission>
"""

from __future__ import annotations

from collections.abc import Iterator

from txtool.dialects.read import Found, enclosing_component
from txtool.lint.context import LintContext
from txtool.lint.facts import Facts
from txtool.lint.problem import Problem
from txtool.lint.support import label, opaque, per_transmission

CODE = "TX103"
NAME = "wrong-member-count"
SEVERITY = "error"
FIXABLE = False


@per_transmission
def check(ctx: LintContext) -> Iterator[Problem]:
    for tx in ctx.facts:
        if tx.kind == "other":
            continue
        if (tx.ros1 and not tx.typed_ros1) or _counts_fine(tx):
            continue
        message = _ros1(tx.found) if tx.ros1 else _ros2(tx.found)
        if message and not opaque(ctx, tx.element):
            yield ctx.problem(CODE, tx.element, message)


def _counts_fine(tx: Facts) -> bool:
    """The counts the loader wants (the common case, decided without reading the model)."""
    joints, actuators = len(tx.joints), len(tx.actuators)
    if tx.kind != "simple":
        return joints == 2 and actuators == 2
    return joints == 1 and (actuators == 1 if tx.ros1 else actuators <= 1)


def _counts(joints: int, actuators: int) -> str:
    return f"{_plural(joints, 'joint')} and {_plural(actuators, 'actuator')}"


def _plural(count: int, noun: str) -> str:
    return f"{count} {noun}" if count == 1 else f"{count} {noun}s"


def _short_type(found: Found) -> str:
    return found.transmission.type.rsplit("/", 1)[-1]


def _ros1(found: Found) -> str | None:
    t = found.transmission
    want = 1 if t.kind == "simple" else 2
    if len(t.joints) == want and len(t.actuators) == want:
        return None
    return (
        f"{label(found)} ({_short_type(found)}) has {_counts(len(t.joints), len(t.actuators))}: "
        f"ros_control needs exactly {_counts(want, want)} and refuses it"
    )


def _ros2(found: Found) -> str | None:
    t = found.transmission
    has = f"{label(found)} ({_short_type(found)}) has {_counts(len(t.joints), len(t.actuators))}"
    if t.kind != "simple":
        if len(t.joints) == 2 and len(t.actuators) == 2:
            return None
        return f"{has}: ros2_control needs exactly 2 joints and 2 actuators and fails to load it"
    if not t.joints:
        return f"{has}: ros2_control's loader reads the first joint and fails"
    if len(t.joints) > 1:
        component = enclosing_component(found.element)
        if component is not None and component.get("type") == "actuator":
            return (
                f"{has}: ros2_control throws \"There should be exactly one joint defined in this "
                "component\""
            )
        return f"{has}: ros2_control uses only joint '{t.joints[0].name}' and ignores the others"
    if len(t.actuators) > 1:
        return f"{has}: ros2_control uses one actuator and ignores the others"
    return None
