from __future__ import annotations

from tests.rules.helpers import check, problems

ROS1 = """
<transmission name="four_bar_trans">
  <type>transmission_interface/{type}</type>
  <joint name="a"><role>joint1</role></joint>
  <joint name="b"><role>joint2</role></joint>
  <actuator name="m1"><role>actuator1</role><mechanicalReduction>50</mechanicalReduction></actuator>
  <actuator name="m2"><role>actuator2</role><mechanicalReduction>50</mechanicalReduction></actuator>
</transmission>
"""


def test_ros1_four_bar_gets_an_info():
    found = problems(ROS1.format(type="FourBarLinkageTransmission"), select=["TX402"])
    assert [(p.line, p.column, p.code, p.severity) for p in found] == [(1, 1, "TX402", "info")]
    assert found[0].severity == "info"
    assert "ros_control#523" in found[0].message and "PR #1837" in found[0].message


def test_ros1_differential_passes():
    assert check(ROS1.format(type="DifferentialTransmission"), select=["TX402"]) == []


def test_ros2_four_bar_passes():
    xml = """
    <ros2_control name="hw" type="system">
      <joint name="a"><command_interface name="effort"/></joint>
      <joint name="b"><command_interface name="effort"/></joint>
      <transmission name="t">
        <plugin>transmission_interface/FourBarLinkageTransmission</plugin>
        <joint name="a" role="joint1"/>
        <joint name="b" role="joint2"/>
        <actuator name="m1" role="actuator1"/>
        <actuator name="m2" role="actuator2"/>
      </transmission>
    </ros2_control>
    """
    assert check(xml, select=["TX402"]) == []
