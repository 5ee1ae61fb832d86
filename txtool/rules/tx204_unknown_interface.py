"""An interface name the transmission loader does not know, beside ones it does: a warning.

What it does: reports, in ROS 1, a ``<hardwareInterface>`` of a ``<joint>`` of a standard
transmission that is not one of the names ros_control registers with pluginlib:
``hardware_interface/JointStateInterface``,
``hardware_interface/{Position,Velocity,Effort}JointInterface`` and
``hardware_interface/BiDirectional{Position,Velocity,Effort}JointInterface``, with the nearest
registered name. A registered name written without the prefix is TX300's business.
``<hardwareInterface>`` in an ``<actuator>`` is optional for the parser and never looked up by
the loader, which takes the first joint's list, so it is not checked. In ROS 2, it reports an
interface the enclosing ``<ros2_control>`` component declares for a transmission joint that is
close to one transmissions map (``position``, ``velocity``, ``effort``; Simple and Differential
also ``torque``, ``force`` and ``absolute_position`` on ros2_control master): ``Position``,
``efort``, ``hardware_interface/EffortJointInterface``. Other extra interfaces
(``acceleration``, ``max_velocity``) are fine: the transmission just skips them. Custom
transmission types and names holding xacro expressions are not checked. When no usable
interface is left, the loader refuses the transmission: TX205 reports that as an error.

Why it matters: ros_control follows a best-effort policy: it looks each interface of the first
joint up as a pluginlib class, warns "Failed to process the 'X' hardware interface for
transmission 'T'" for an unknown name and goes on with the others. The transmission loads, but
without that interface. ros2_control's transmissions silently skip every handle whose
interface name they do not map, so a misspelt name means that interface is never transmitted.

Loader: ros_control registers the names (ros-controls/ros_control
transmission_interface/ros_control_plugins.xml:30-92 @23284e8) and looks them up
(transmission_interface/src/transmission_interface_loader.cpp:152, :169-183 @0a09467;
transmission_interface/src/transmission_parser.cpp:221-241 @14e64ea; the loader test
``UnsupportedHwInterfaceType``, transmission_interface/test/transmission_interface_loader_test.cpp
:153-160 @3e1dd9d).

Failing example::

    <robot name="r">
      <transmission name="t">
        <type>transmission_interface/SimpleTransmission</type>
        <joint name="j1">
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
          <hardwareInterface>hardware_interface/PositionJointInterfaces</hardwareInterface>
        </joint>
        <actuator name="m"><mechanicalReduction>50</mechanicalReduction></actuator>
      </transmission>
    </robot>

Expected finding: ``6:7 warning TX204 hardware interface
'hardware_interface/PositionJointInterfaces' of joint 'j1' in transmission 't' is not a
ros_control interface: ros_control warns and loads the transmission without it; did you mean
'hardware_interface/PositionJointInterface'?``

Passing example::

    <robot name="r">
      <transmission name="t">
        <type>transmission_interface/SimpleTransmission</type>
        <joint name="j1">
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
          <hardwareInterface>hardware_interface/PositionJointInterface</hardwareInterface>
        </joint>
        <actuator name="m"><mechanicalReduction>50</mechanicalReduction></actuator>
      </transmission>
    </robot>

Fix: write the registered name the message suggests (ROS 1), or the lower-case interface name
ros2_control maps (ROS 2).
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator

from lxml import etree

from txtool.dialects.read import Found
from txtool.lint.context import LintContext
from txtool.lint.problem import Problem
from txtool.lint.rule_helpers import (
    PREFIX,
    REGISTERED,
    ROS1_INTERFACES,
    MemberRef,
    children,
    label,
    members,
    per_transmission,
)
from txtool.rules.tx203_interface_mismatch import component_joint, declared_interfaces

CODE = "TX204"
NAME = "unknown-interface"
SEVERITY = "warning"
FIXABLE = False

UNPREFIXED = frozenset(name.removeprefix(PREFIX) for name in ROS1_INTERFACES)
ROS2_INTERFACES: dict[str, tuple[str, ...]] = {
    "simple": ("position", "velocity", "effort", "torque", "force", "absolute_position"),
    "differential": ("position", "velocity", "effort", "torque", "force", "absolute_position"),
    "four_bar": ("position", "velocity", "effort"),
}
# ROS 1 names that people carry over into ROS 2 components.
_ROS1_TO_ROS2 = {
    "positionjointinterface": "position",
    "velocityjointinterface": "velocity",
    "effortjointinterface": "effort",
}


@per_transmission
def check(ctx: LintContext) -> Iterator[Problem]:
    for tx in ctx.facts:
        if tx.kind == "other":
            continue
        if tx.ros1:
            if not REGISTERED.issuperset(tx.joint_interfaces):
                yield from _check_ros1(ctx, tx.found)  # else every name is registered
        elif tx.component is not None:  # else no component declares its joints' interfaces
            yield from _check_ros2(ctx, tx.found, tx.kind)


def unprefixed_registered(text: str) -> bool:
    """A registered ROS 1 interface name written without ``hardware_interface/``."""
    return PREFIX + text in ROS1_INTERFACES


def registered(text: str) -> bool:
    """A name ros_control's pluginlib lookup finds (exactly as written, after stripping)."""
    return text in ROS1_INTERFACES


def _check_ros1(ctx: LintContext, found: Found) -> Iterator[Problem]:
    for ref in members(found):
        if ref.noun != "joint":
            continue  # ros_control never reads an actuator's <hardwareInterface>
        elements = children(ref.element, "hardwareInterface")
        texts = [(element.text or "").strip() for element in elements]
        effect = (
            "ros_control warns and loads the transmission without it"
            if any(registered(text) for text in texts)
            else "ros_control warns and drops it (with no valid interface left it refuses the "
            "transmission: TX205)"
        )
        for element, text in zip(elements, texts, strict=True):
            if not text or ctx.unknown(text):
                continue
            if text in ROS1_INTERFACES or unprefixed_registered(text):
                continue
            yield ctx.problem(
                CODE,
                element,
                f"hardware interface '{text}' of {ref.noun} '{ref.name}' in "
                f"{label(found)} is not a ros_control interface: {effect}{ros1_hint(text)}",
            )


def ros1_hint(text: str) -> str:
    """``; did you mean 'X'?`` with the nearest registered ROS 1 interface, or ``""``."""
    guess = _close_matches(text, ROS1_INTERFACES, n=1, cutoff=0.5)
    if not guess:
        guess = _close_matches(PREFIX + text, ROS1_INTERFACES, n=1, cutoff=0.5)
    return f"; did you mean '{guess[0]}'?" if guess else ""


def _check_ros2(ctx: LintContext, found: Found, kind: str) -> Iterator[Problem]:
    mapped = ROS2_INTERFACES[kind]
    for ref, _component, names in ros2_joint_interfaces(ctx, found):
        where = f"joint '{ref.name}' of {label(found)}"
        for name in names:
            guess = _suggest(name, mapped) if name not in mapped else None
            if guess is not None:
                yield ctx.problem(
                    CODE,
                    ref.element,
                    f"interface '{name}' of {where} is not one a transmission maps: "
                    f"ros2_control silently skips it; did you mean '{guess}'?",
                )


def ros2_joint_interfaces(
    ctx: LintContext, found: Found
) -> Iterator[tuple[MemberRef, etree._Element, list[str]]]:
    """(joint, its ``<ros2_control>``, the interface names it declares there), when knowable."""
    for ref in members(found):
        pair = component_joint(ctx, found, ref.name) if ref.noun == "joint" else None
        names = declared_interfaces(pair[1]) if pair is not None else []
        if pair is None or not names or any(ctx.unknown(name) for name in names):
            continue
        yield ref, pair[0], names


def _suggest(name: str, mapped: tuple[str, ...]) -> str | None:
    key = name.strip().lower().removeprefix(PREFIX.lower())
    if key in mapped:
        return key
    if _ROS1_TO_ROS2.get(key) in mapped:
        return _ROS1_TO_ROS2[key]
    guess = _close_matches(key, mapped, n=1, cutoff=0.85)
    return guess[0] if guess else None


def _close_matches(word: str, candidates: Iterable[str], *, n: int, cutoff: float) -> list[str]:
    import difflib  # only for a misspelt interface

    return difflib.get_close_matches(word, candidates, n=n, cutoff=cutoff)
