from __future__ import annotations

import pytest

from tests.rules.helpers import check, problems

ROS1 = """
<robot name="r">
  <transmission name="t">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="j">
      <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
      <offset>{offset}</offset>
    </joint>
    <actuator name="m"><mechanicalReduction>{reduction}</mechanicalReduction></actuator>
  </transmission>
</robot>
"""
ROS2 = """
<robot name="r">
  <ros2_control name="hw" type="system">
    <joint name="j"/>
    <transmission name="t">
      <plugin>transmission_interface/SimpleTransmission</plugin>
      <joint name="j" role="joint1">
        <mechanical_reduction>{reduction}</mechanical_reduction>
        <offset>{offset}</offset>
      </joint>
    </transmission>
  </ros2_control>
</robot>
"""


def test_ros1_word_reduction_fires_at_the_element():
    found = problems(ROS1.format(offset="0", reduction="fifty"), select=["TX105"])
    assert [(p.line, p.column, p.code) for p in found] == [(8, 24, "TX105")]
    assert "'fifty', not a number: ros_control refuses" in found[0].message


def test_ros1_trailing_junk_says_stod_reads_the_leading_number():
    found = problems(ROS1.format(offset="0", reduction="50abc"), select=["TX105"])
    assert [(p.line, p.column) for p in found] == [(8, 24)]
    assert "std::stod reads 50 and ignores the rest" in found[0].message


def test_ros1_inf_offset_fires():
    found = problems(ROS1.format(offset="inf", reduction="50"), select=["TX105"])
    assert [(p.line, p.column) for p in found] == [(6, 7)]
    assert "inf or nan" in found[0].message


@pytest.mark.parametrize(
    ("reduction", "offset", "where", "default"),
    [("fifty", "0", (7, 9), "1.0"), ("2", "nan", (8, 9), "0.0"), ("", "0", (7, 9), "1.0")],
)
def test_ros2_invalid_numbers_say_the_silent_default(reduction, offset, where, default):
    found = problems(ROS2.format(reduction=reduction, offset=offset), select=["TX105"])
    assert [(p.line, p.column) for p in found] == [where]
    assert f"ros2_control silently uses {default}" in found[0].message


def test_ros2_trailing_junk_is_not_accepted():
    assert check(ROS2.format(reduction="50abc", offset="0"), select=["TX105"]) == [(7, 9, "TX105")]


def test_plain_numbers_pass():
    assert check(ROS1.format(offset="-0.5", reduction=" 1e2 "), select=["TX105"]) == []
    assert check(ROS2.format(reduction="+325.949", offset="0.0"), select=["TX105"]) == []


def test_ignored_values_are_not_checked():
    # ros_control's SimpleTransmission never reads a joint reduction.
    xml = ROS1.format(offset="0", reduction="50").replace(
        "<offset>", "<mechanicalReduction>fifty</mechanicalReduction><offset>"
    )
    assert check(xml, select=["TX105"]) == []


def test_literal_xacro_expressions_are_unknown():
    xml = """
    <robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
      <xacro:macro name="tr" params="n">
        <transmission name="${n}_t">
          <type>transmission_interface/SimpleTransmission</type>
          <joint name="${n}"><hardwareInterface>EffortJointInterface</hardwareInterface></joint>
          <actuator name="${n}_m"><mechanicalReduction>${r * 2}</mechanicalReduction></actuator>
        </transmission>
      </xacro:macro>
    </robot>
    """
    assert check(xml, filename="lib.xacro", select=["TX105"]) == []
