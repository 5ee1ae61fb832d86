"""TX205: no interface the loader can use is left, so it refuses the transmission.

ros_control: transmission_interface/src/transmission_interface_loader.cpp:169-194 @0a09467
("It contains no valid hardware interfaces"); loader test UnsupportedHwInterfaceType,
transmission_interface/test/transmission_interface_loader_test.cpp:143-151 @3e1dd9d.
"""

from __future__ import annotations

import pytest

from tests.rules.helpers import check, problems
from tests.rules.test_tx204_unknown_interface import ROS1, ROS2, SIMPLE


def test_ros1_only_an_unprefixed_interface_is_refused():
    """One mistake, one finding: TX300's, with its fix, at this rule's severity; TX205's own
    where TX300 does not run."""
    xml = ROS1.format(type=SIMPLE, interface="PositionJointInterface")
    found = problems(xml, select=["TX205", "TX300"])
    assert [(p.line, p.column, p.code, p.severity, p.fixable) for p in found] == [
        (4, 5, "TX300", "error", True)]
    assert found[0].message.endswith(
        "and drops it, which leaves no interface: it refuses the transmission (\"It contains "
        "no valid hardware interfaces\"); write 'hardware_interface/PositionJointInterface'")
    found = problems(xml, select=["TX205"])
    assert [(p.line, p.column, p.code, p.severity) for p in found] == [(3, 3, "TX205", "error")]
    assert "ros_control refuses it (\"It contains no valid hardware interfaces\")" in (
        found[0].message)
    assert "write 'hardware_interface/PositionJointInterface'" in found[0].message
    assert "gazebo_ros_control accepts the unprefixed name" in found[0].message


def test_ros1_only_an_unknown_interface_is_refused():
    xml = ROS1.format(type=SIMPLE, interface="unsupported/hw_interface_type")
    assert check(xml, select=["TX204", "TX205"]) == [
        (3, 3, "TX205", "error"), (4, 5, "TX204", "warning")
    ]


@pytest.mark.parametrize(
    "interface",
    ["hardware_interface/PositionJointInterface", "hardware_interface/JointStateInterface"],
)
def test_ros1_one_registered_interface_is_enough(interface):
    assert check(ROS1.format(type=SIMPLE, interface=interface), select=["TX205"]) == []


def test_ros1_custom_types_and_own_loader_families_are_not_checked():
    for type_ in ("pr2_mechanism_model/SimpleTransmission", "hey5_transmissions/Hey5Reducer"):
        xml = ROS1.format(type=type_, interface="PositionJointInterface")
        assert check(xml, select=["TX205"]) == []


def test_ros1_xacro_interface_is_unknown():
    macro = """
    <robot xmlns:xacro="http://www.ros.org/wiki/xacro">
      <xacro:macro name="m" params="hw">
    """ + ROS1.format(type=SIMPLE, interface="${hw}") + """
      </xacro:macro>
    </robot>
    """
    assert check(macro, select=["TX205"], filename="lib.xacro") == []


def test_ros2_joint_declaring_nothing_the_transmission_maps_is_refused():
    found = problems(ROS2.format(interfaces='<command_interface name="Position"/>',
                                 plugin="SimpleTransmission"), select=["TX205"])
    assert [(p.line, p.column, p.code, p.severity) for p in found] == [(8, 5, "TX205", "error")]
    assert "declares only Position" in found[0].message


def test_ros2_one_mapped_interface_is_enough():
    interfaces = '<command_interface name="position"/><state_interface name="temperature"/>'
    assert check(ROS2.format(interfaces=interfaces, plugin="SimpleTransmission"),
                 select=["TX205"]) == []


def test_ros1_only_a_misspelt_interface_is_refused_with_the_nearest_name():
    # YuMi's grippers (corpus): 'hardware_interface/EffortJoinInterface' is their only interface.
    xml = ROS1.format(type=SIMPLE, interface="hardware_interface/EffortJoinInterface")
    found = problems(xml, select=["TX204", "TX205"])
    assert [(p.code, p.severity) for p in found] == [("TX205", "error"), ("TX204", "warning")]
    assert "did you mean 'hardware_interface/EffortJointInterface'?" in found[0].message
    assert "with no valid interface left it refuses the transmission: TX205" in found[1].message


def test_a_ros1_leftover_beside_ros2_control_is_read_by_no_loader():
    """OMY-F3M keeps ROS 1 transmissions beside its <ros2_control> block: TX304 only."""
    xml = """<robot name="r">
  <joint name="j" type="revolute"><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <transmission name="t">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="j"><hardwareInterface>PositionJointInterface</hardwareInterface></joint>
    <actuator name="m"><mechanicalReduction>1</mechanicalReduction></actuator>
  </transmission>
  <ros2_control name="hw" type="system"><joint name="j"><command_interface name="position"/></joint></ros2_control>
</robot>
"""
    assert sorted((code, severity) for _, _, code, severity in check(xml)) == [
        ("TX300", "warning"), ("TX304", "warning")]
    alone = xml.replace('<ros2_control name="hw" type="system"><joint name="j"><command_interface name="position"/></joint></ros2_control>\n', "")
    assert ("TX300", "error") in [(code, severity) for _, _, code, severity in check(alone)]
