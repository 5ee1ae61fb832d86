from __future__ import annotations

from tests.rules.helpers import check, problems

ROS2_SIMPLE = """
<ros2_control name="hw" type="system">
  <joint name="j"><command_interface name="position"/></joint>
  <transmission name="t">
    <plugin>transmission_interface/SimpleTransmission</plugin>
    <actuator name="m" role="actuator1">
      {actuator}
    </actuator>
    <joint name="j" role="joint1">
      {joint}
    </joint>
  </transmission>
</ros2_control>
"""


def test_ros2_simple_actuator_reduction_and_offset_are_never_read():
    xml = ROS2_SIMPLE.format(
        actuator="<mechanical_reduction>50</mechanical_reduction><offset>1</offset>", joint=""
    )
    found = problems(xml, select=["TX400"])
    assert [(p.line, p.column, p.code, p.severity) for p in found] == [(6, 7, "TX400", "warning"), (6, 54, "TX400", "warning")]
    assert "<mechanical_reduction> of actuator 'm' in transmission 't' is never read" in (
        found[0].message
    )
    assert "takes reduction and offset from the joint" in found[0].message
    assert found[0].severity == "warning"


def test_ros2_simple_joint_values_pass():
    xml = ROS2_SIMPLE.format(
        actuator="", joint="<mechanical_reduction>50</mechanical_reduction><offset>1</offset>"
    )
    assert check(xml, select=["TX400"]) == []


ROS2_COUPLED = """
<ros2_control name="hw" type="system">
  <joint name="a"><command_interface name="position"/></joint>
  <joint name="b"><command_interface name="position"/></joint>
  <joint name="c"><command_interface name="position"/></joint>
  <transmission name="t">
    <plugin>transmission_interface/DifferentialTransmission</plugin>
    <actuator name="m1" role="actuator1"><mechanical_reduction>10</mechanical_reduction></actuator>
    <actuator name="m2" role="actuator2"><offset>0.5</offset></actuator>
    <joint name="a" role="joint1"><offset>0.5</offset></joint>
    <joint name="b" role="joint2"/>
    {third}
  </transmission>
</ros2_control>
"""


def test_ros2_coupled_actuator_offset_and_third_joint_are_ignored():
    found = problems(ROS2_COUPLED.format(third='<joint name="c" role="joint3"/>'),
                     select=["TX400"])
    assert [(p.line, p.column) for p in found] == [(8, 42), (11, 5)]
    assert "coupled transmissions have joint offsets only" in found[0].message
    assert "joint 'c' of transmission 't' comes after the second" in found[1].message


def test_ros2_coupled_with_two_joints_and_joint_offsets_passes():
    xml = ROS2_COUPLED.format(third="").replace("<offset>0.5</offset></actuator>", "</actuator>")
    assert check(xml, select=["TX400"]) == []


ROS1_SIMPLE = """
<transmission name="t">
  <type>transmission_interface/SimpleTransmission</type>
  <joint name="j">
    <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
    {joint}
  </joint>
  <actuator name="m">
    <mechanicalReduction>50</mechanicalReduction>
    {actuator}
  </actuator>
</transmission>
"""


def test_ros1_simple_joint_reduction_and_actuator_offset_are_never_read():
    xml = ROS1_SIMPLE.format(
        joint="<mechanicalReduction>2</mechanicalReduction>", actuator="<offset>0.1</offset>"
    )
    found = problems(xml, select=["TX400"])
    assert [(p.line, p.column) for p in found] == [(5, 5), (9, 5)]
    assert "takes the reduction from the actuator" in found[0].message
    assert "reads offsets from joints only" in found[1].message


def test_ros1_simple_joint_offset_passes():
    assert check(ROS1_SIMPLE.format(joint="<offset>0.1</offset>", actuator=""),
                 select=["TX400"]) == []


def test_ros1_coupled_joint_reduction_is_read():
    xml = """
    <transmission name="t">
      <type>transmission_interface/DifferentialTransmission</type>
      <joint name="a"><role>joint1</role><mechanicalReduction>2</mechanicalReduction></joint>
      <joint name="b"><role>joint2</role><mechanicalReduction>2</mechanicalReduction></joint>
      <actuator name="m1"><role>actuator1</role><mechanicalReduction>1</mechanicalReduction></actuator>
      <actuator name="m2"><role>actuator2</role><mechanicalReduction>1</mechanicalReduction></actuator>
    </transmission>
    """
    assert check(xml, select=["TX400"]) == []


def test_ros1_reduction_directly_under_a_typed_transmission_is_never_read():
    xml = ROS1_SIMPLE.format(joint="", actuator="").replace(
        "</transmission>", "  <mechanicalReduction>3</mechanicalReduction>\n</transmission>"
    )
    found = problems(xml, select=["TX400"])
    assert [(p.line, p.column) for p in found] == [(11, 3)]
    assert "directly under transmission 't' is never read" in found[0].message
