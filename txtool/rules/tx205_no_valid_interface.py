"""A transmission left with no interface its loader can use: the loader refuses it.

What it does: reports, in ROS 1, a transmission none of whose joints' ``<hardwareInterface>``
names is one ros_control registers (``hardware_interface/PositionJointInterface`` and the
others listed under TX204; the loader reads the first joint's, the others must list the same
set, TX203). The usual cause is the unprefixed ``PositionJointInterface`` or
``EffortJointInterface`` that gazebo_ros_control accepts with a deprecation warning. In ROS 2,
a transmission joint whose ``<joint>`` in the enclosing ``<ros2_control>`` declares interfaces,
none of which the transmission maps (``position``, ``velocity``, ``effort``; Simple and
Differential also ``torque``, ``force``, ``absolute_position``): ``Position``, say. A
transmission whose names are all registered ones without their ``hardware_interface/`` prefix
(``PositionJointInterface``) is reported by TX300 instead, at this rule's severity and with its
fix, while TX300 runs: one mistake, one finding. Custom
transmission types, families with loaders of their own and names holding xacro expressions are
not checked; nor is a ROS 1 transmission outside every ``<ros2_control>`` block of a document
that has such blocks (the robot's loader is then ros2_control, which never reads it: TX304).
A robot that Gazebo loads through gazebo_ros_control's DefaultRobotHWSim (a
``libgazebo_ros_control.so`` plugin, or one built on it, without another ``<robotSimType>``)
gets a warning instead where that loader accepts the first interface.

Why it matters: ros_control warns for each name its pluginlib lookup does not find and, when no
interface is left, logs "Failed to load transmission 'T'. It contains no valid hardware
interfaces." and returns false; loading stops at that transmission. ros2_control's
transmissions get no handle they can map, and ``configure`` throws "None of the provided joint
handles are valid or from the required interfaces".

Loader: ros_control (ros-controls/ros_control
transmission_interface/src/transmission_interface_loader.cpp:126-129, :169-194 @0a09467; the
loader test ``UnsupportedHwInterfaceType``,
transmission_interface/test/transmission_interface_loader_test.cpp:143-151 @3e1dd9d);
gazebo_ros_pkgs gazebo_ros_control/src/default_robot_hw_sim.cpp ``initSim`` @01c3a2c.

Failing example::

    <robot name="r">
      <transmission name="t">
        <type>transmission_interface/SimpleTransmission</type>
        <joint name="j1">
          <hardwareInterface>PositionInterface</hardwareInterface>
        </joint>
        <actuator name="m"><mechanicalReduction>50</mechanicalReduction></actuator>
      </transmission>
    </robot>

Expected finding: ``4:5 error TX205 transmission 't' names no hardware interface ros_control
knows ('PositionInterface'): ros_control refuses it ("It contains no valid hardware
interfaces"); did you mean 'hardware_interface/PositionJointInterface'?``

Passing example::

    <robot name="r">
      <transmission name="t">
        <type>transmission_interface/SimpleTransmission</type>
        <joint name="j1">
          <hardwareInterface>hardware_interface/PositionJointInterface</hardwareInterface>
        </joint>
        <actuator name="m"><mechanicalReduction>50</mechanicalReduction></actuator>
      </transmission>
    </robot>

Fix: write the registered name (``hardware_interface/PositionJointInterface``; ``txtool
migrate --write`` adds the prefix, TX300), or in ROS 2 the lower-case interface name.
"""

from __future__ import annotations

from collections.abc import Iterator

from txtool.dialects.read import Found
from txtool.lint.context import LintContext
from txtool.lint.facts import Facts
from txtool.lint.problem import Problem, Severity
from txtool.lint.rule_helpers import label, opaque, per_transmission
from txtool.model.readers import accepts
from txtool.rules.tx204_unknown_interface import (
    PREFIX,
    REGISTERED,
    ROS2_INTERFACES,
    registered,
    ros1_hint,
    ros2_joint_interfaces,
    unprefixed_registered,
)

CODE = "TX205"
NAME = "no-valid-interface"
SEVERITY = "error"
FIXABLE = False
DEFERS_TO = ("TX300",)  # see covered_by_tx300


@per_transmission
def check(ctx: LintContext) -> Iterator[Problem]:
    for tx in ctx.facts:
        if tx.kind == "other":
            continue
        if tx.ros1:
            refused = refusal(ctx, tx)
            if refused is not None and not covered_by_tx300(ctx, refused[1]):
                yield from _check_ros1(ctx, tx, *refused)
        elif tx.component is not None:  # else no component declares its joints' interfaces
            yield from _check_ros2(ctx, tx.found, tx.kind)


def refusal(ctx: LintContext, tx: Facts) -> tuple[list, list[str]] | None:
    """The joints naming interfaces, and the names, of a ROS 1 transmission ros_control
    refuses for want of a registered interface; None when it does not (or cannot be told)."""
    if tx.component is None and ctx.components:
        return None  # a ROS 2 robot's leftover: no loader reads it (TX304)
    if not tx.typed_ros1 or tx.own_loader:
        return None
    first = next((ref for ref in tx.joints if ref.interfaces), None)
    if first is None or not REGISTERED.isdisjoint(first.interfaces):
        return None  # the common case: the first joint names a registered interface
    joints = [ref for ref in tx.joints if ref.interfaces]
    if any(opaque(ctx, ref.element) for ref in joints):
        return None
    lists = [ref.interfaces for ref in joints]
    if len({frozenset(names) for names in lists}) > 1:
        return None  # joints with different interfaces: TX203
    names = lists[0]
    if any(ctx.unknown(name) or registered(name) for name in names):
        return None
    return joints, names


def covered_by_tx300(ctx: LintContext, names: list[str]) -> bool:
    """Whether TX300 reports this refusal: each name is a registered one without its
    prefix, and TX300 runs. One mistake, one finding: TX300's, which the fix fixes, at this
    rule's severity (see :func:`consequence`)."""
    return ctx.runs("TX300") and all(unprefixed_registered(name) for name in names)


def consequence(ctx: LintContext, names: list[str]) -> tuple[str, Severity]:
    """What the loader does with a transmission left without a registered interface, as
    TX300 says it when it covers this rule's finding, and the severity that goes with it."""
    sim = ctx.gazebo_sim
    said = ("drops it, which leaves no interface: it refuses the transmission (\"It contains "
            "no valid hardware interfaces\")")
    if sim is not None and sim.default and accepts(names[0]):
        return (f"{said}; {sim.describe()} accepts the name with a deprecation warning",
                "warning")
    if sim is not None and sim.default:
        said += f", and so does {sim.describe()}"
    return said, "error"


def _check_ros1(ctx: LintContext, tx: Facts, joints: list,
                names: list[str]) -> Iterator[Problem]:
    shown = ", ".join(f"'{name}'" for name in names)
    fixes = [PREFIX + name for name in names if unprefixed_registered(name)]
    message = (f"{tx.label} names no hardware interface ros_control knows ({shown}): "
               f"ros_control refuses it (\"It contains no valid hardware interfaces\")")
    sim = ctx.gazebo_sim
    if sim is not None and sim.default and accepts(names[0]):
        yield ctx.problem(
            CODE, joints[0].element,
            f"{message}; {sim.describe()} accepts '{names[0]}' with a deprecation "
            f"warning: write '{PREFIX + names[0]}' for both",
            loader_severity="warning",
        )
        return
    if sim is not None and sim.default:
        message += f"; so does {sim.describe()}: \"No matching hardware interface found\""
    advice = (
        f"; write '{fixes[0]}' (gazebo_ros_control accepts the unprefixed name with a "
        "deprecation warning, ros_control does not)"
        if fixes
        else ros1_hint(names[0])
    )
    yield ctx.problem(CODE, joints[0].element, message + advice)


def _check_ros2(ctx: LintContext, found: Found, kind: str) -> Iterator[Problem]:
    mapped = ROS2_INTERFACES[kind]
    for ref, component, names in ros2_joint_interfaces(ctx, found):
        if any(name in mapped for name in names):
            continue
        yield ctx.problem(
            CODE,
            ref.element,
            f"joint '{ref.name}' of {label(found)} declares only {', '.join(names)} in "
            f"<ros2_control> '{component.get('name', '')}'; a {kind} transmission maps "
            f"{', '.join(mapped)}, so configuring it throws (\"None of the provided joint "
            "handles are valid\")",
        )
