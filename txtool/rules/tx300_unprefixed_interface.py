"""A ROS 1 hardware interface without ``hardware_interface/``.

What it does: reports a ``<hardwareInterface>`` of a ROS 1 joint written as a registered
interface name without its namespace: ``PositionJointInterface`` instead of
``hardware_interface/PositionJointInterface`` (likewise Velocity, Effort, JointState and the
BiDirectional ones). An actuator's ``<hardwareInterface>`` is never read by ros_control, so it
is not reported. Transmission families with loaders of their own (``pr2_mechanism_model/``,
``sr_mechanism_model/``) are neither reported nor fixed.

Why it matters: ros_control looks the name up as a pluginlib class, and only the prefixed
names are registered: it warns "Failed to process the 'PositionJointInterface' hardware
interface for transmission 'T'" and loads the transmission with its other interfaces; with no
valid interface left it refuses the transmission: then this finding says so, at TX205's severity
(an error; a warning where gazebo_ros_control's DefaultRobotHWSim loads the robot), in place of
TX205's (one mistake, one finding, with its fix).
gazebo_ros_control accepts both spellings but warns "Deprecated syntax, please prepend
'hardware_interface/'" (gazebo_ros_pkgs#550), so a robot can work in simulation and fail on
the real hardware.

Loader: ros_control (ros-controls/ros_control
transmission_interface/src/transmission_interface_loader.cpp:169-183 @0a09467).

Failing example::

    <robot name="r">
      <transmission name="t">
        <type>transmission_interface/SimpleTransmission</type>
        <joint name="j">
          <hardwareInterface>PositionJointInterface</hardwareInterface>
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
        </joint>
        <actuator name="m"><mechanicalReduction>50</mechanicalReduction></actuator>
      </transmission>
    </robot>

Expected finding: ``5:7 warning TX300 hardware interface 'PositionJointInterface' of joint 'j'
in transmission 't' lacks the 'hardware_interface/' prefix: ros_control does not find it
('Failed to process the hardware interface') and drops it; write
'hardware_interface/PositionJointInterface'``

Passing example::

    <robot name="r">
      <transmission name="t">
        <type>transmission_interface/SimpleTransmission</type>
        <joint name="j">
          <hardwareInterface>hardware_interface/PositionJointInterface</hardwareInterface>
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
        </joint>
        <actuator name="m"><mechanicalReduction>50</mechanicalReduction></actuator>
      </transmission>
    </robot>

Fix: ``txtool migrate --write`` prepends ``hardware_interface/``, keeping the whitespace
around the name, in the joints and in the actuators too, so the two spellings stay alike
(older gazebo_ros_control falls back to the actuator's). Names holding xacro expressions are
left as written.
"""

from __future__ import annotations

from collections.abc import Iterator

from lxml import etree

from txtool.dialects.read import detect_dialect, ros1_type, text_of, transmission_elements
from txtool.io.xmlio import local
from txtool.lint.context import LintContext
from txtool.lint.problem import Problem
from txtool.lint.rule_helpers import OWN_LOADER_FAMILIES, children, label, per_transmission
from txtool.rules.tx204_unknown_interface import PREFIX, UNPREFIXED, unprefixed_registered
from txtool.rules.tx205_no_valid_interface import consequence, covered_by_tx300, refusal

CODE = "TX300"
NAME = "unprefixed-interface"
SEVERITY = "warning"
FIXABLE = True


def _unprefixed(
    transmission: etree._Element, nouns: tuple[str, ...] = ("joint",)
) -> Iterator[tuple[etree._Element, etree._Element, str]]:
    """(member, hardwareInterface element, name) for each unprefixed registered name."""
    for member in [m for noun in nouns for m in children(transmission, noun)]:
        for element in children(member, "hardwareInterface"):
            text = (text_of(element) or "").strip()
            if text and unprefixed_registered(text):
                yield member, element, text


@per_transmission
def check(ctx: LintContext) -> Iterator[Problem]:
    for tx in ctx.facts:
        if not tx.ros1 or tx.own_loader:
            continue
        if UNPREFIXED.isdisjoint(tx.joint_interfaces):
            continue  # the common case (the joints' interface names are the texts below)
        found = tx.found
        # Left without a registered interface, the transmission is refused: TX205's finding,
        # said here once, with the fix (see TX205's covered_by_tx300).
        refused = refusal(ctx, tx)
        said, severity = (consequence(ctx, refused[1]) if refused is not None
                          and covered_by_tx300(ctx, refused[1]) else ("drops it", None))
        for member, element, text in _unprefixed(found.element):
            yield ctx.problem(
                CODE,
                element,
                f"hardware interface '{text}' of {local(member)} '{member.get('name', '')}' in "
                f"{label(found)} lacks the '{PREFIX}' prefix: "
                "ros_control does not find it ('Failed to process the hardware interface') and "
                f"{said}; write '{PREFIX}{text}'",
                loader_severity=severity,
            )


def fix(root: etree._Element) -> int:
    fixed = 0
    for transmission in transmission_elements(root):
        if detect_dialect(transmission) != "ros1":
            continue
        if ros1_type(transmission).startswith(OWN_LOADER_FAMILIES):
            continue
        for _, element, text in list(_unprefixed(transmission, ("joint", "actuator"))):
            element.text = (element.text or "").replace(text, PREFIX + text, 1)
            fixed += 1
    return fixed
