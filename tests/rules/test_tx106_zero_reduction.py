from __future__ import annotations

from tests.rules.helpers import check, problems

ROS1 = """
<robot name="r">
  <transmission name="t">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="j">
      <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
    </joint>
    <actuator name="m"><mechanicalReduction>{value}</mechanicalReduction></actuator>
  </transmission>
</robot>
"""

ROS2 = """
<robot name="r">
  <ros2_control name="hw" type="system">
    <joint name="a"/>
    <joint name="b"/>
    <transmission name="t">
      <plugin>transmission_interface/DifferentialTransmission</plugin>
      <actuator name="m1" role="actuator1">
        <mechanical_reduction>{value}</mechanical_reduction></actuator>
      <actuator name="m2" role="actuator2"/>
      <joint name="a" role="joint1"/>
      <joint name="b" role="joint2"/>
    </transmission>
  </ros2_control>
</robot>
"""


def test_ros1_zero_actuator_reduction_fires_at_the_element():
    assert check(ROS1.format(value="0"), select=["TX106"]) == [(7, 24, "TX106", "error")]


def test_ros1_negative_zero_counts_as_zero():
    found = problems(ROS1.format(value="-0.0"), select=["TX106"])
    assert [(p.line, p.code) for p in found] == [(7, "TX106")]
    assert "ros_control refuses it" in found[0].message


def test_ros2_zero_coupled_actuator_reduction_fires():
    found = problems(ROS2.format(value="0"), select=["TX106"])
    assert [(p.line, p.column, p.code, p.severity) for p in found] == [(8, 9, "TX106", "error")]
    assert "ros2_control's loader fails" in found[0].message


def test_nonzero_reduction_passes():
    assert check(ROS1.format(value="50"), select=["TX106"]) == []
    assert check(ROS2.format(value="-2.5"), select=["TX106"]) == []


def test_zero_joint_reduction_of_ros1_simple_is_not_read():
    xml = ROS1.format(value="50").replace(
        "</joint>", "<mechanicalReduction>0</mechanicalReduction></joint>"
    )
    assert check(xml, select=["TX106"]) == []
