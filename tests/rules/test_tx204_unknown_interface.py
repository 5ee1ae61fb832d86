from __future__ import annotations

from tests.rules.helpers import check, problems

ROS1 = """
<transmission name="t">
  <type>{type}</type>
  <joint name="j">
    <hardwareInterface>{interface}</hardwareInterface>
  </joint>
  <actuator name="m"><mechanicalReduction>1</mechanicalReduction></actuator>
</transmission>
"""
SIMPLE = "transmission_interface/SimpleTransmission"


def test_ros1_unknown_interface_fires_with_the_nearest_name():
    xml = ROS1.format(type=SIMPLE, interface="hardware_interface/PositionJointInterfaces")
    found = problems(xml, select=["TX204"])
    assert [(p.line, p.column, p.code, p.severity) for p in found] == [(4, 5, "TX204", "warning")]
    assert "did you mean 'hardware_interface/PositionJointInterface'?" in found[0].message


def test_ros1_actuator_interfaces_are_never_read_so_never_reported():
    # transmission_interface_loader.cpp:152 @0a09467 reads the first joint's interfaces only.
    xml = ROS1.format(type=SIMPLE, interface="hardware_interface/EffortJointInterface").replace(
        "<actuator name=\"m\">",
        "<actuator name=\"m\"><hardwareInterface>EffortJoinInterface</hardwareInterface>")
    assert check(xml, select=["TX204", "TX205", "TX300"]) == []


def test_ros1_unknown_beside_a_valid_interface_loads_best_effort_with_a_warning():
    # Best-effort policy: transmission_interface_loader.cpp:169-183 @0a09467 and the loader
    # test UnsupportedHwInterfaceType, transmission_interface_loader_test.cpp:153-160 @3e1dd9d.
    xml = ROS1.format(type=SIMPLE, interface="hardware_interface/EffortJointInterface").replace(
        "</hardwareInterface>",
        "</hardwareInterface>\n    <hardwareInterface>unsupported/hw_interface_type"
        "</hardwareInterface>", 1)
    found = problems(xml, select=["TX204", "TX205"])
    assert [(p.line, p.column, p.code, p.severity) for p in found] == [(5, 5, "TX204", "warning")]
    assert "ros_control warns and loads the transmission without it" in found[0].message


def test_ros1_registered_interfaces_pass():
    for name in ("hardware_interface/EffortJointInterface",
                 "hardware_interface/BiDirectionalVelocityJointInterface",
                 "hardware_interface/JointStateInterface"):
        assert check(ROS1.format(type=SIMPLE, interface=name), select=["TX204"]) == []


def test_ros1_unprefixed_registered_name_is_tx300_not_tx204():
    xml = ROS1.format(type=SIMPLE, interface="PositionJointInterface")
    # alone, the name leaves the transmission refused: TX300 at TX205's severity
    assert check(xml, select=["TX204", "TX300"]) == [(4, 5, "TX300", "error")]


def test_ros1_custom_types_and_xacro_values_are_not_checked():
    custom = ROS1.format(type="franka_hw/FrankaStateInterface",
                         interface="franka_hw/FrankaStateInterface")
    assert check(custom, select=["TX204"]) == []
    macro = """
    <robot xmlns:xacro="http://www.ros.org/wiki/xacro">
      <xacro:macro name="m" params="hw">
    """ + ROS1.format(type=SIMPLE, interface="${hw}") + """
      </xacro:macro>
    </robot>
    """
    assert check(macro, select=["TX204"], filename="lib.xacro") == []


ROS2 = """
<ros2_control name="hw" type="system">
  <joint name="joint1">
    {interfaces}
  </joint>
  <transmission name="t">
    <plugin>transmission_interface/{plugin}</plugin>
    <actuator name="m" role="actuator1"/>
    <joint name="joint1" role="joint1"/>
  </transmission>
</ros2_control>
"""


def test_ros2_misspelt_component_interface_fires():
    xml = ROS2.format(interfaces='<command_interface name="Position"/>', plugin="SimpleTransmission")
    found = problems(xml, select=["TX204"])
    assert [(p.line, p.column, p.code, p.severity) for p in found] == [(8, 5, "TX204", "warning")]
    assert "interface 'Position' of joint 'joint1'" in found[0].message
    assert "did you mean 'position'?" in found[0].message


def test_ros2_ros1_interface_name_in_a_component_gets_the_ros2_name():
    interfaces = '<command_interface name="hardware_interface/EffortJointInterface"/>'
    found = problems(ROS2.format(interfaces=interfaces, plugin="SimpleTransmission"),
                     select=["TX204"])
    assert len(found) == 1 and "did you mean 'effort'?" in found[0].message


def test_ros2_extra_interfaces_beside_a_mapped_one_pass():
    interfaces = ('<command_interface name="position"/><state_interface name="max_velocity"/>'
                  '<state_interface name="acceleration"/>')
    xml = ROS2.format(interfaces=interfaces, plugin="SimpleTransmission")
    assert check(xml, select=["TX204"]) == []


def test_ros2_joint_with_nothing_a_transmission_maps_is_tx205_not_tx204():
    interfaces = '<state_interface name="temperature"/>'
    assert check(ROS2.format(interfaces=interfaces, plugin="SimpleTransmission"),
                 select=["TX204", "TX205"]) == [(8, 5, "TX205", "error")]


def test_ros2_four_bar_does_not_map_torque():
    interfaces = '<command_interface name="torque"/>'
    assert check(ROS2.format(interfaces=interfaces, plugin="SimpleTransmission"),
                 select=["TX204", "TX205"]) == []
    assert check(ROS2.format(interfaces=interfaces, plugin="FourBarLinkageTransmission"),
                 select=["TX204", "TX205"]) == [(8, 5, "TX205", "error")]
