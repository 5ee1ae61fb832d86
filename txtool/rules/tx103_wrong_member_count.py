"""A standard transmission with the wrong number of joints or actuators.

What it does: reports a SimpleTransmission without 1 joint and 1 actuator, and a
DifferentialTransmission or FourBarLinkageTransmission without 2 of each; in ros2_control also
a coupled one whose 2 joints (or actuators) are one name listed twice. In ros2_control a
simple transmission needs no ``<actuator>``, since the parser or the hardware plugin supplies
it; a SimpleTransmission listing one joint (or actuator) several times, by the same name, is a
**warning** there: the loader reads the first listing and the later ones are read by nothing.
A transmission of a component of ``type="actuator"`` that does not name exactly one joint is
TX207's (the parser throws before any loader runs). Custom types are not counted, nor literal
xacro transmissions whose members are produced by ``xacro:if`` or macro calls.

Why it matters: ros_control (ROS 1) refuses any other count ("Expected 1 actuators, got 2.").
ros2_control's simple loader reads only the first joint (it fails with none); the coupled
loaders fail with fewer than 2 joints or actuators, and ``configure`` throws unless it gets
two names with one handle each ("There should be exactly two unique joint names"; a name
listed again as a third member gives it three handles: "Not enough valid or required ...
handles were present").

Loader: ros_control (ros-controls/ros_control
transmission_interface/src/simple_transmission_loader.cpp ``SimpleTransmissionLoader::load``,
``checkJointDimension``/``checkActuatorDimension``); ros2_control (ros-controls/ros2_control
transmission_interface/src/simple_transmission_loader.cpp ``SimpleTransmissionLoader::load``:
``joints.at(0)``; transmission_interface/include/transmission_interface/simple_transmission.hpp
``configure``: ``are_names_identical``; differential_transmission.hpp and
four_bar_linkage_transmission.hpp ``configure``: ``get_names``, ``get_ordered_handles``).

Failing example::

    <robot name="r">
      <transmission name="t">
        <type>transmission_interface/SimpleTransmission</type>
        <joint name="a">
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
        </joint>
        <joint name="b">
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
        </joint>
        <actuator name="m"><mechanicalReduction>50</mechanicalReduction></actuator>
      </transmission>
    </robot>

Expected finding: ``2:3 error TX103 transmission 't' (SimpleTransmission) has 2 joints and 1
actuator: ros_control needs exactly 1 joint and 1 actuator and refuses it``

Passing example::

    <robot name="r">
      <transmission name="t">
        <type>transmission_interface/SimpleTransmission</type>
        <joint name="a">
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
        </joint>
        <actuator name="m"><mechanicalReduction>50</mechanicalReduction></actuator>
      </transmission>
    </robot>

Fix: one transmission per joint for simple ones; a coupled pair of joints is one
DifferentialTransmission (or FourBarLinkageTransmission) with two actuators.
"""

from __future__ import annotations

from collections.abc import Iterator

from txtool.dialects.read import Found
from txtool.lint.context import LintContext
from txtool.lint.facts import Facts
from txtool.lint.problem import Problem
from txtool.lint.rule_helpers import in_actuator_component, label, opaque, per_transmission
from txtool.model.numbers import C_SPACE

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
        if len(tx.joints) != 1 and in_actuator_component(tx):
            continue  # the parser throws first (TX207)
        message = _ros1(tx.found) if tx.ros1 else _ros2(tx.found)
        if message and not opaque(ctx, tx.element):
            lower = None if tx.ros1 else _repeated(tx.found)
            yield ctx.problem(CODE, tx.element, lower or message,
                              loader_severity="warning" if lower else None)


def _repeated(found: Found) -> str | None:
    """For a ROS 2 SimpleTransmission that lists one joint (and at most one actuator) several
    times by the same name, outside an actuator component: what the loader does, else None."""
    t = found.transmission
    if t.kind != "simple" or len(t.joints) < 1:
        return None
    for members in (t.joints, t.actuators):
        if len({m.name for m in members}) > 1:
            return None
    repeated = [(noun, ms) for noun, ms in (("joint", t.joints), ("actuator", t.actuators))
                if len(ms) > 1]
    listed = "; ".join(f"{noun} '{ms[0].name}' is listed {len(ms)} times" for noun, ms in repeated)
    return (
        f"{label(found)} (SimpleTransmission): {listed}: ros2_control's loader reads the first "
        "listing and configure() accepts handles of one name, so it loads; the later listings "
        "are read by nothing"
    )


def _counts_fine(tx: Facts) -> bool:
    """The counts the loader wants (the common case, decided without reading the model)."""
    joints, actuators = len(tx.joints), len(tx.actuators)
    if tx.kind != "simple":
        return joints == 2 and actuators == 2 and (tx.ros1 or (
            _distinct(tx.joints[0].name, tx.joints[1].name)
            and _distinct(tx.actuators[0].name, tx.actuators[1].name)))
    return joints == 1 and (actuators == 1 if tx.ros1 else actuators <= 1)


def _distinct(first: str, second: str) -> bool:
    """Two member names ros2_control's parser reads as two (it strips them)."""
    return first.strip(C_SPACE) != second.strip(C_SPACE)


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
            return _one_name_twice(found)
        return f"{has}: ros2_control needs exactly 2 joints and 2 actuators and fails to load it"
    if not t.joints:
        return f"{has}: ros2_control's loader reads the first joint and fails"
    if len(t.joints) > 1:
        return f"{has}: ros2_control uses only joint '{t.joints[0].name}' and ignores the others"
    if len(t.actuators) > 1:
        return f"{has}: ros2_control uses one actuator and ignores the others"
    return None


def _one_name_twice(found: Found) -> str | None:
    """A coupled ROS 2 transmission whose two joints (or actuators) have one name."""
    t = found.transmission
    for noun, members in (("joint", t.joints), ("actuator", t.actuators)):
        if members[0].name == members[1].name:
            return (f"{label(found)} ({_short_type(found)}) lists {noun} '{members[0].name}' "
                    f"twice: ros2_control's configure() throws \"There should be exactly two "
                    f"unique {noun} names\" and the transmission is not configured")
    return None
