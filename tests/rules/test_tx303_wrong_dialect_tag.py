from __future__ import annotations

from tests.rules.helpers import check, problems

ROS2 = """
<ros2_control name="hw" type="system">
  <joint name="joint1"><command_interface name="position"/></joint>
  <transmission name="t">
    <plugin>transmission_interface/SimpleTransmission</plugin>
    <actuator name="m" role="actuator1"/>
    <joint name="joint1" role="joint1">
      {body}
    </joint>
  </transmission>
</ros2_control>
"""


def test_ros2_mechanical_reduction_in_ros1_spelling_fires():
    body = "<mechanicalReduction>50</mechanicalReduction>"
    found = problems(ROS2.format(body=body), select=["TX303"])
    assert [(p.line, p.column, p.code, p.severity) for p in found] == [(7, 7, "TX303", "error")]
    assert "joint 'joint1' of transmission 't' uses the ROS 1 <mechanicalReduction>" in (
        found[0].message
    )
    assert "silently becomes 1.0" in found[0].message


def test_ros2_hardware_interface_elements_fire():
    body = ("<hardwareInterface>hardware_interface/PositionJointInterface</hardwareInterface>"
            "<hardware_interface>position</hardware_interface>")
    assert check(ROS2.format(body=body), select=["TX303"]) == [(7, 7, "TX303", "error"), (7, 87, "TX303", "error")]


def test_ros2_correct_spelling_passes():
    body = "<mechanical_reduction>50</mechanical_reduction><offset>0.1</offset>"
    assert check(ROS2.format(body=body), select=["TX303"]) == []


def test_ros2_type_element_fires():
    xml = ROS2.format(body="").replace(
        "<plugin>transmission_interface/SimpleTransmission</plugin>",
        "<type>transmission_interface/SimpleTransmission</type>",
    )
    found = problems(xml, select=["TX303"])
    assert [(p.line, p.column) for p in found] == [(4, 5)]
    assert "reads the type from <plugin>" in found[0].message


def test_proposal_1_role_elements_say_that_ros2_control_throws():
    xml = """
    <ros2_control name="hw" type="system">
      <joint name="joint1"><command_interface name="position"/></joint>
      <transmission name="t">
        <plugin>transmission_interface/SimpleTransmission</plugin>
        <actuator name="m"><role>actuator1</role></actuator>
        <joint name="joint1"><role>joint1</role></joint>
      </transmission>
    </ros2_control>
    """
    found = problems(xml, select=["TX303"])
    assert [(p.line, p.column) for p in found] == [(5, 24), (6, 26)]
    assert "(the ROS 2 Proposal 1 form)" in found[1].message
    assert "throws \"no attribute 'role' in 'joint' tag\"" in found[1].message


def test_ros1_mechanical_reduction_in_ros2_spelling_fires():
    xml = """
    <transmission name="t">
      <type>transmission_interface/SimpleTransmission</type>
      <joint name="j">
        <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
      </joint>
      <actuator name="m"><mechanical_reduction>50</mechanical_reduction></actuator>
    </transmission>
    """
    found = problems(xml, select=["TX303"])
    assert [(p.line, p.column, p.code, p.severity) for p in found] == [(6, 22, "TX303", "error")]
    assert "ros_control reads only <mechanicalReduction>" in found[0].message


def test_ros1_spellings_in_ros1_pass():
    xml = """
    <transmission name="t">
      <type>transmission_interface/SimpleTransmission</type>
      <joint name="j">
        <role>joint1</role>
        <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
      </joint>
      <actuator name="m"><mechanicalReduction>50</mechanicalReduction></actuator>
    </transmission>
    """
    assert check(xml, select=["TX303"]) == []


def test_the_one_obvious_fix_is_offered():
    """The value respelt as the loader reads it; none for a value that is no plain text."""
    found = problems(ROS2.format(body="<mechanicalReduction> 50 </mechanicalReduction>"),
                     select=["TX303"])
    assert found[0].message.endswith(
        "silently becomes 1.0: write <mechanical_reduction>50</mechanical_reduction>")
    found = problems(ROS2.format(body="<mechanicalReduction>${r}</mechanicalReduction>"),
                     select=["TX303"])
    assert found[0].message.endswith("silently becomes 1.0")
    role = ROS2.replace('<actuator name="m" role="actuator1"/>',
                        '<actuator name="m"><role>actuator1</role></actuator>')
    found = problems(role.format(body=""), select=["TX303"])
    assert found[0].message.endswith(
        "'actuator' tag\": write <actuator name=\"m\" role=\"actuator1\">")
    ros1 = """<transmission name="t">
      <type>transmission_interface/SimpleTransmission</type>
      <joint name="j"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>
      <actuator name="m"><mechanical_reduction>50</mechanical_reduction></actuator>
    </transmission>"""
    found = problems(ros1, select=["TX303"])
    assert found[0].message.endswith(
        "never sees this value: write <mechanicalReduction>50</mechanicalReduction>")
