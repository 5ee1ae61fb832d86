from __future__ import annotations

from tests.rules.helpers import check, problems

ROS1 = """
<transmission name="wrist">
  <type>transmission_interface/DifferentialTransmission</type>
  <joint name="flex">
    <role>joint1</role>
    <hardwareInterface>hardware_interface/PositionJointInterface</hardwareInterface>
    <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
  </joint>
  <joint name="roll">
    <role>joint2</role>
    {second}
  </joint>
  <actuator name="m1"><role>actuator1</role><mechanicalReduction>1</mechanicalReduction></actuator>
  <actuator name="m2"><role>actuator2</role><mechanicalReduction>1</mechanicalReduction></actuator>
</transmission>
"""
POSITION = "<hardwareInterface>hardware_interface/PositionJointInterface</hardwareInterface>"
EFFORT = "<hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>"


def test_ros1_joints_with_different_interfaces_fire_at_the_second():
    found = problems(ROS1.format(second=POSITION), select=["TX203"])
    assert [(p.line, p.column, p.code, p.severity) for p in found] == [(8, 3, "TX203", "error")]
    assert "joint 'roll' of transmission 'wrist' lists hardware interfaces" in found[0].message
    assert "ros_control refuses" in found[0].message


def test_ros1_same_interfaces_in_another_order_pass():
    assert check(ROS1.format(second=EFFORT + POSITION), select=["TX203"]) == []


def test_ros1_joint_without_interfaces_is_left_to_other_rules():
    assert check(ROS1.format(second=""), select=["TX203"]) == []


ROS2 = """
<ros2_control name="hw" type="system">
  <joint name="joint1">{interfaces}</joint>
  <transmission name="t">
    <plugin>transmission_interface/SimpleTransmission</plugin>
    <actuator name="m" role="actuator1"/>
    <joint name="joint1" role="joint1"/>
  </transmission>
</ros2_control>
"""


def test_ros2_component_joint_without_interfaces_fires():
    found = problems(ROS2.format(interfaces=""), select=["TX203"])
    assert [(p.line, p.column, p.code, p.severity) for p in found] == [(6, 5, "TX203", "error")]
    assert "has no command or state interface in <ros2_control> 'hw'" in found[0].message


def test_ros2_component_joint_with_a_state_interface_passes():
    xml = ROS2.format(interfaces='<state_interface name="position"/>')
    assert check(xml, select=["TX203"]) == []
