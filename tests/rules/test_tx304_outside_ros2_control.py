from __future__ import annotations

from tests.rules.helpers import check, problems

ROS1_TRANSMISSION = """
  <transmission name="wheel_trans">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="wheel">
      <hardwareInterface>hardware_interface/VelocityJointInterface</hardwareInterface>
    </joint>
    <actuator name="wheel_motor"><mechanicalReduction>1</mechanicalReduction></actuator>
  </transmission>"""

COMPONENT = """
  <ros2_control name="DiffBot" type="system">
    <hardware><plugin>mock_components/GenericSystem</plugin></hardware>
    <joint name="wheel"><command_interface name="velocity"/></joint>
  </ros2_control>"""

LINKS = """
  <link name="base"/>
  <link name="wheel_link"/>
  <joint name="wheel" type="continuous"><parent link="base"/><child link="wheel_link"/></joint>"""


def test_top_level_ros1_transmission_beside_a_component_warns():
    xml = "<robot name=\"r\">" + LINKS + ROS1_TRANSMISSION + COMPONENT + "\n</robot>\n"
    found = problems(xml, select=["TX304"])
    assert [(p.line, p.column, p.code, p.severity) for p in found] == [(5, 3, "TX304", "warning")]
    assert "ROS 1 transmission 'wheel_trans' stands outside every <ros2_control>" in (
        found[0].message
    )
    assert found[0].severity == "warning"


def test_without_components_there_is_nothing_to_ignore_it():
    xml = "<robot name=\"r\">" + LINKS + ROS1_TRANSMISSION + "\n</robot>\n"
    assert check(xml, select=["TX304"]) == []


def test_transmissions_inside_the_component_pass():
    inside = COMPONENT.replace(
        "  </ros2_control>",
        "    <transmission name=\"t\">\n"
        "      <plugin>transmission_interface/SimpleTransmission</plugin>\n"
        "      <joint name=\"wheel\" role=\"joint1\"/>\n"
        "    </transmission>\n"
        "  </ros2_control>",
    )
    xml = "<robot name=\"r\">" + LINKS + inside + "\n</robot>\n"
    assert check(xml, select=["TX304"]) == []


def test_macro_bodies_of_a_xacro_library_are_not_reported():
    xml = (
        "<robot xmlns:xacro=\"http://www.ros.org/wiki/xacro\">\n"
        "  <xacro:macro name=\"trans\" params=\"\">" + ROS1_TRANSMISSION + "\n"
        "  </xacro:macro>\n"
        "  <xacro:macro name=\"hw\" params=\"\">" + COMPONENT + "\n"
        "  </xacro:macro>\n"
        "</robot>\n"
    )
    assert check(xml, select=["TX304"], filename="lib.xacro") == []


def test_only_ros1_readers_read_it_there_is_nothing_to_report():
    """--ros-distro noetic: ros_control reads the top-level transmission; no ROS 2 program
    reads this file, so "ros2_control ignores it" would name a reader the run ruled out."""
    xml = "<robot name=\"r\">" + LINKS + ROS1_TRANSMISSION + COMPONENT + "\n</robot>\n"
    assert check(xml, select=["TX304"], **{"ros-distro": "noetic"}) == []


def test_decided_ros2_readers_are_named_with_why():
    xml = "<robot name=\"r\">" + LINKS + ROS1_TRANSMISSION + COMPONENT + "\n</robot>\n"
    (found,) = problems(xml, select=["TX304"], readers=["ros_control", "ros2_control"])
    assert found.message.endswith("stands outside every <ros2_control> block of this document: "
                                  "ros2_control (readers in the test options) ignores it")
