from __future__ import annotations

from tests.rules.helpers import check, problems

IFACE = "<hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>"
ROS1 = f"""
<robot name="r">
  <transmission name="t">
    <type>transmission_interface/{{type}}</type>
    <joint name="a">{IFACE}</joint>
    {{more}}
    <actuator name="m"><mechanicalReduction>1</mechanicalReduction></actuator>
  </transmission>
</robot>
"""


def test_ros1_simple_with_two_joints_fires_at_the_transmission():
    xml = ROS1.format(type="SimpleTransmission", more=f'<joint name="b">{IFACE}</joint>')
    found = problems(xml, select=["TX103"])
    assert [(p.line, p.column, p.code, p.severity) for p in found] == [(2, 3, "TX103", "error")]
    assert "2 joints and 1 actuator" in found[0].message
    assert "ros_control needs exactly 1 joint and 1 actuator" in found[0].message


def test_ros1_differential_with_one_of_each_fires():
    assert check(ROS1.format(type="DifferentialTransmission", more=""), select=["TX103"]) == [
        (2, 3, "TX103", "error")
    ]


def test_ros1_simple_one_and_one_passes():
    assert check(ROS1.format(type="SimpleTransmission", more=""), select=["TX103"]) == []


ROS2 = """
<robot name="r">
  <ros2_control name="hw" type="{component}">
    <joint name="a"/>
    <transmission name="t">
      <plugin>transmission_interface/SimpleTransmission</plugin>
      <joint name="a" role="joint1"/>
      {more}
    </transmission>
  </ros2_control>
</robot>
"""


def test_ros2_simple_without_actuator_passes():
    assert check(ROS2.format(component="actuator", more=""), select=["TX103"]) == []


def test_ros2_simple_with_two_joints_in_an_actuator_component_is_left_to_tx207():
    xml = ROS2.format(component="actuator", more='<joint name="b" role="joint2"/>')
    found = problems(xml, select=["TX103", "TX207"])
    assert [(p.line, p.column, p.code) for p in found] == [(4, 5, "TX207")]
    assert "There should be exactly one joint" in found[0].message


def test_ros2_simple_with_two_joints_in_a_system_ignores_the_second():
    xml = ROS2.format(component="system", more='<joint name="b" role="joint2"/>')
    assert "uses only joint 'a'" in problems(xml, select=["TX103"])[0].message


def test_custom_types_are_not_counted():
    xml = ROS1.format(type="SimpleTransmission", more="").replace(
        "transmission_interface/SimpleTransmission", "franka_hw/FrankaStateInterface"
    )
    assert check(xml.replace('<joint name="a">', '<joint name="a"/><joint name="b">'),
                 select=["TX103"]) == []


def test_literal_xacro_members_under_conditionals_are_not_counted():
    xml = f"""
    <robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
      <xacro:macro name="tr" params="gripper">
        <transmission name="t">
          <type>transmission_interface/SimpleTransmission</type>
          <joint name="a">{IFACE}</joint>
          <xacro:if value="${{gripper}}"><joint name="b">{IFACE}</joint></xacro:if>
          <actuator name="m"><mechanicalReduction>1</mechanicalReduction></actuator>
        </transmission>
      </xacro:macro>
    </robot>
    """
    assert check(xml, filename="lib.urdf.xacro", select=["TX103"]) == []


def test_ros2_simple_with_two_actuators_uses_one():
    xml = ROS2.format(component="system", more='<actuator name="m1" role="actuator1"/>'
                                               '<actuator name="m2" role="actuator2"/>')
    found = problems(xml, select=["TX103"])
    assert [(p.line, p.column, p.code) for p in found] == [(4, 5, "TX103")]
    assert found[0].message == ("transmission 't' (SimpleTransmission) has 1 joint and 2 "
                                "actuators: ros2_control uses one actuator and ignores the others")


def test_ros2_simple_without_joint_fails_to_load():
    xml = ROS2.format(component="system", more="").replace('<joint name="a" role="joint1"/>',
                                                           '<actuator name="m"/>')
    found = problems(xml, select=["TX103"])
    assert [(p.line, p.column, p.code) for p in found] == [(4, 5, "TX103")]
    assert found[0].message.endswith("has 0 joints and 1 actuator: ros2_control's loader reads "
                                     "the first joint and fails")


COUPLED = """
<robot name="r">
  <ros2_control name="hw" type="system">
    <joint name="a"/><joint name="b"/>
    <transmission name="t">
      <plugin>transmission_interface/DifferentialTransmission</plugin>
      <joint name="a" role="joint1"/>
      <joint name="{second_joint}" role="joint2"/>
      <actuator name="m1" role="actuator1"/>
      <actuator name="{second_actuator}" role="actuator2"/>
      {more}
    </transmission>
  </ros2_control>
</robot>
"""


def coupled(second_joint: str = "b", second_actuator: str = "m2", more: str = "") -> str:
    return COUPLED.format(second_joint=second_joint, second_actuator=second_actuator, more=more)


def test_ros2_coupled_with_two_distinct_names_each_passes():
    assert check(coupled(), select=["TX103"]) == []


def test_ros2_coupled_listing_one_actuator_twice_is_refused_by_configure():
    # differential_transmission.hpp configure: get_names (a std::set) must give two names
    found = problems(coupled(second_actuator=" m1 "), select=["TX103"])
    assert [(p.line, p.column, p.code, p.severity) for p in found] == [(4, 5, "TX103", "error")]
    assert found[0].message == (
        "transmission 't' (DifferentialTransmission) lists actuator 'm1' twice: ros2_control's "
        "configure() throws \"There should be exactly two unique actuator names\" and the "
        "transmission is not configured")


def test_ros2_coupled_listing_one_joint_twice_is_refused_by_configure():
    found = problems(coupled(second_joint="a"), select=["TX103"])
    assert [(p.line, p.code) for p in found] == [(4, "TX103")]
    assert "lists joint 'a' twice" in found[0].message


def test_ros2_coupled_with_an_actuator_listed_again_as_a_third_fails_to_load():
    found = problems(coupled(more='<actuator name="m1" role="actuator1"/>'), select=["TX103"])
    assert [(p.line, p.code) for p in found] == [(4, "TX103")]
    assert "2 joints and 3 actuators" in found[0].message
