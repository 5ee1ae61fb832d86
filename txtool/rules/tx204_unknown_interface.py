"""An interface name the transmission loader does not know.

What it checks
    * ROS 1: every ``<hardwareInterface>`` of a joint or actuator of a standard transmission
      must be one of the names ros_control registers with pluginlib:
      ``hardware_interface/JointStateInterface``,
      ``hardware_interface/{Position,Velocity,Effort}JointInterface`` and
      ``hardware_interface/BiDirectional{Position,Velocity,Effort}JointInterface``. A
      registered name written without the prefix is TX300's business; anything else is
      reported here with the nearest registered name.
    * ROS 2: the interfaces the enclosing ``<ros2_control>`` component declares for a
      transmission joint. Transmissions map ``position``, ``velocity`` and ``effort``
      (Simple and Differential also ``torque``, ``force`` and ``absolute_position`` on
      ros2_control master). A declared name that is close to one of those (``Position``,
      ``efort``, ``hardware_interface/EffortJointInterface``) is reported with the
      suggestion; so is a joint none of whose interfaces the transmission can map. Other
      extra interfaces (``acceleration``, ``max_velocity``) are fine: the transmission just
      skips them.

    Custom transmission types and names holding xacro expressions are not checked.

Why
    ros_control looks each joint interface up as a pluginlib class; an unknown name gives
    "Failed to process the 'X' hardware interface for transmission 'T'", and with no valid
    name left the transmission fails to load. ros2_control's transmissions silently skip
    every handle whose interface name they do not map, so a misspelt name means the joint is
    never transmitted, without any error.

Failing example (ROS 1)::

    <joint name="j1">
      <hardwareInterface>hardware_interface/PositionJointInterfaces</hardwareInterface>
    </joint>

Passing example: ``hardware_interface/PositionJointInterface``.

Failing example (ROS 2)::

    <ros2_control name="HW" type="system">
      <joint name="j1"><command_interface name="Position"/></joint>
      <transmission name="t">
        <plugin>transmission_interface/SimpleTransmission</plugin>
        <joint name="j1" role="joint1"/>
      </transmission>
    </ros2_control>

Passing example: ``<command_interface name="position"/>``.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator

from txtool.dialects.read import Found
from txtool.lint.context import LintContext
from txtool.lint.problem import Problem
from txtool.lint.support import children, label, members
from txtool.rules.tx203_interface_mismatch import component_joint, declared_interfaces

CODE = "TX204"
NAME = "unknown-interface"
SEVERITY = "error"
FIXABLE = False

PREFIX = "hardware_interface/"
ROS1_INTERFACES: tuple[str, ...] = tuple(
    PREFIX + name
    for name in (
        "JointStateInterface",
        "PositionJointInterface",
        "VelocityJointInterface",
        "EffortJointInterface",
        "BiDirectionalPositionJointInterface",
        "BiDirectionalVelocityJointInterface",
        "BiDirectionalEffortJointInterface",
    )
)
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


def check(ctx: LintContext) -> Iterator[Problem]:
    for found in ctx.transmissions():
        if found.transmission.kind == "other":
            continue
        if found.transmission.dialect == "ros1":
            yield from _check_ros1(ctx, found)
        else:
            yield from _check_ros2(ctx, found)


def unprefixed_registered(text: str) -> bool:
    """A registered ROS 1 interface name written without ``hardware_interface/``."""
    return PREFIX + text in ROS1_INTERFACES


def _check_ros1(ctx: LintContext, found: Found) -> Iterator[Problem]:
    for ref in members(found):
        for element in children(ref.element, "hardwareInterface"):
            text = (element.text or "").strip()
            if not text or ctx.unknown(text):
                continue
            if text in ROS1_INTERFACES or unprefixed_registered(text):
                continue
            yield ctx.problem(
                CODE,
                element,
                f"hardware interface '{text}' of {ref.noun} '{ref.member.name}' in "
                f"{label(found)} is not a ros_control interface: the pluginlib lookup fails "
                f"and the interface is dropped{_ros1_hint(text)}",
            )


def _ros1_hint(text: str) -> str:
    guess = _close_matches(text, ROS1_INTERFACES, n=1, cutoff=0.5)
    if not guess:
        guess = _close_matches(PREFIX + text, ROS1_INTERFACES, n=1, cutoff=0.5)
    return f"; did you mean '{guess[0]}'?" if guess else ""


def _check_ros2(ctx: LintContext, found: Found) -> Iterator[Problem]:
    t = found.transmission
    mapped = ROS2_INTERFACES[t.kind]
    for ref in members(found):
        pair = component_joint(ctx, found, ref.member.name) if ref.noun == "joint" else None
        names = declared_interfaces(pair[1]) if pair is not None else []
        if pair is None or not names or any(ctx.unknown(name) for name in names):
            continue
        where = f"joint '{ref.member.name}' of {label(found)}"
        near = [(name, _suggest(name, mapped)) for name in names if name not in mapped]
        for name, guess in near:
            if guess is not None:
                yield ctx.problem(
                    CODE,
                    ref.element,
                    f"interface '{name}' of {where} is not one a transmission maps: "
                    f"ros2_control silently skips it; did you mean '{guess}'?",
                )
        if not any(name in mapped for name in names) and all(g is None for _, g in near):
            yield ctx.problem(
                CODE,
                ref.element,
                f"{where} declares only {', '.join(names)} in <ros2_control> "
                f"'{pair[0].get('name', '')}'; a {t.kind} transmission maps "
                f"{', '.join(mapped)}, so ros2_control transmits nothing for it",
            )


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
