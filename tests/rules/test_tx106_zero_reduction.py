from __future__ import annotations

import pytest

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


SIMPLE = """
<robot name="r">
  <ros2_control name="hw" type="system">
    <joint name="j"/>
    <transmission name="t">
      <plugin>transmission_interface/SimpleTransmission</plugin>
      <joint name="j" role="joint1"><mechanical_reduction>{value}</mechanical_reduction></joint>
    </transmission>
  </ros2_control>
</robot>
"""


@pytest.mark.parametrize("value", ["1e-400", "-1e-400", "2e-324", "1e-99999999999999999999"])
def test_humble_reads_a_number_too_small_for_a_double_as_zero_and_refuses_it(value):
    # lexical_casts.cpp impl::stod below C++20: istringstream gives 0 for an underflow; the
    # simple loader then throws "Transmission reduction ratio cannot be zero." (parser17)
    found = problems(SIMPLE.format(value=value), select=["TX106"], **{"ros-distro": "humble"})
    assert [(p.line, p.column, p.severity) for p in found] == [(6, 37, "error")]
    assert found[0].message == (
        f"reduction of joint 'j' of transmission 't' is '{value}', which Humble's ros2_control "
        "reads as 0 (too small for a double): its loader fails (\"Failed to construct "
        "transmission\")")


def test_where_any_ros2_distribution_may_read_it_the_underflow_is_a_warning_naming_both():
    found = problems(SIMPLE.format(value="1e-400"), select=["TX106"])
    assert [(p.line, p.severity) for p in found] == [(6, "warning")]
    assert found[0].message.endswith("; Jazzy's and later silently use 1.0")


@pytest.mark.parametrize("distro", ["jazzy", "rolling", "noetic"])
def test_distributions_that_do_not_read_it_as_zero_say_nothing_here(distro):
    assert check(SIMPLE.format(value="1e-400"), select=["TX106"],
                 **{"ros-distro": distro}) == []


def test_a_tiny_number_that_is_not_zero_is_no_finding():
    assert check(SIMPLE.format(value="1e-310"), select=["TX106"],
                 **{"ros-distro": "humble"}) == []
