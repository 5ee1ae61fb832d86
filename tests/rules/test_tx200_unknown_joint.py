from __future__ import annotations

from tests.rules.helpers import check, problems

ROS2 = """
<robot name="r">
  <link name="a"/>
  <link name="b"/>
  <joint name="joint1" type="revolute">
    <parent link="a"/><child link="b"/><limit lower="-1" upper="1" effort="1" velocity="1"/>
  </joint>
  <ros2_control name="RRBot" type="system">
    <joint name="joint1"><command_interface name="position"/></joint>
    <transmission name="transmission1">
      <plugin>transmission_interface/SimpleTransmission</plugin>
      <actuator name="motor1" role="actuator1"/>
      <joint name="{joint}" role="joint1"/>
    </transmission>
  </ros2_control>
</robot>
"""

ROS1 = """
<robot name="r">
  <link name="a"/>
  <link name="b"/>
  <joint name="elbow" type="revolute">
    <parent link="a"/><child link="b"/><limit lower="-1" upper="1" effort="1" velocity="1"/>
  </joint>
  <transmission name="t">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="{joint}">
      <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
    </joint>
    <actuator name="m"><mechanicalReduction>10</mechanicalReduction></actuator>
  </transmission>
</robot>
"""


def test_ros2_joint_missing_from_the_component_fires():
    found = problems(ROS2.format(joint="joint31415"), select=["TX200"])
    assert [(p.line, p.column, p.code, p.severity) for p in found] == [(12, 7, "TX200", "error")]
    assert "not a <joint> of <ros2_control> 'RRBot'" in found[0].message
    assert "ros2_control throws" in found[0].message


def test_ros2_joint_of_the_component_passes():
    assert check(ROS2.format(joint="joint1"), select=["TX200"]) == []


def test_ros2_component_check_applies_to_a_bare_fragment():
    xml = """
    <ros2_control name="RRBot" type="system">
      <joint name="joint1"><command_interface name="position"/></joint>
      <transmission name="transmission1">
        <plugin>transmission_interface/SimpleTransmission</plugin>
        <joint name="joint2" role="joint1"/>
      </transmission>
    </ros2_control>
    """
    assert check(xml, select=["TX200"]) == [(5, 5, "TX200", "error")]


def test_ros1_joint_missing_from_the_robot_fires():
    found = problems(ROS1.format(joint="elbw"), select=["TX200"])
    assert [(p.line, p.column, p.code, p.severity) for p in found] == [(9, 5, "TX200", "error")]
    assert "joint 'elbw' of transmission 't' is not a <joint> of the robot" in found[0].message


def test_ros1_joint_of_the_robot_passes():
    assert check(ROS1.format(joint="elbow"), select=["TX200"]) == []


def test_a_fragment_without_robot_joints_is_not_cross_checked():
    xml = """
    <transmission name="t">
      <type>transmission_interface/SimpleTransmission</type>
      <joint name="anything">
        <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
      </joint>
      <actuator name="m"><mechanicalReduction>10</mechanicalReduction></actuator>
    </transmission>
    """
    assert check(xml, select=["TX200"]) == []


MACRO_LIBRARY = """
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="hw" params="prefix">
    <ros2_control name="RRBot" type="system">
      <joint name="${prefix}joint1"><command_interface name="position"/></joint>
      <transmission name="transmission1">
        <plugin>transmission_interface/SimpleTransmission</plugin>
        <joint name="{joint}" role="joint1"/>
      </transmission>
    </ros2_control>
  </xacro:macro>
</robot>
"""


def test_xacro_names_are_matched_as_patterns():
    for joint in ("joint1", "${prefix}joint1", "${prefix}other"):
        xml = MACRO_LIBRARY.replace("{joint}", joint)
        assert check(xml, select=["TX200"], filename="hw.xacro") == []


def test_xacro_pattern_does_not_hide_an_unrelated_literal_name():
    xml = MACRO_LIBRARY.replace("{joint}", "elbow")
    assert check(xml, select=["TX200"], filename="hw.xacro") == [(7, 9, "TX200", "error")]


def test_ros2_names_are_compared_stripped_as_the_parser_strips_them():
    # component_parser.cpp get_attribute_value strips both names (:133 @53b9999)
    assert check(ROS2.format(joint=" joint1\t"), select=["TX200"]) == []
    spaced = ROS2.replace('<joint name="joint1"><command', '<joint name=" joint1 "><command')
    assert check(spaced.format(joint="joint1"), select=["TX200"]) == []
    found = problems(ROS2.format(joint="\u00a0joint1"), select=["TX200"])  # no C space
    assert [(p.code, p.severity) for p in found] == [("TX200", "error")]
    assert "is not a <joint> of <ros2_control> 'RRBot'" in found[0].message
