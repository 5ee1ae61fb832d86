"""TX112: read_only must be true or false in any case; parse_bool throws otherwise.

ros2_control hardware_interface/src/lexical_casts.cpp:64-83 @146eb98.
"""

from __future__ import annotations

import pytest

from tests.rules.helpers import check, problems

ROS2 = """
<ros2_control name="hw" type="system">
  <joint name="joint1"><command_interface name="position"/></joint>
  <transmission name="t">
    <plugin>transmission_interface/SimpleTransmission</plugin>
    <actuator name="m" role="actuator1" {attribute}/>
    <joint name="joint1" role="joint1" {attribute}/>
  </transmission>
</ros2_control>
"""


@pytest.mark.parametrize("value", ["yes", "1", "\u00a0true", "tru", "", "ＴＲＵＥ"])
def test_anything_but_true_or_false_is_an_error_on_each_member(value):
    found = problems(ROS2.format(attribute=f'read_only="{value}"'), select=["TX112"])
    assert [(p.line, p.column, p.code, p.severity) for p in found] == [
        (5, 5, "TX112", "error"), (6, 5, "TX112", "error")
    ]
    assert "parse_bool accepts only true or false" in found[0].message
    assert "actuator 'm' of transmission 't'" in found[0].message


@pytest.mark.parametrize("attribute", ['read_only="true"', 'read_only="False"',
                                       'read_only="TRUE"', 'read_only=" true\t"', ""])
def test_true_or_false_in_any_case_or_no_attribute_passes(attribute):
    assert check(ROS2.format(attribute=attribute), select=["TX112"]) == []


def test_ros1_members_are_not_checked():
    xml = """
    <transmission name="t">
      <type>transmission_interface/SimpleTransmission</type>
      <joint name="j" read_only="maybe">
        <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
      </joint>
      <actuator name="m"><mechanicalReduction>1</mechanicalReduction></actuator>
    </transmission>
    """
    assert check(xml, select=["TX112"]) == []
