"""Severity keeps its promise where ros2_control accepts what is written (warnings), and stays
an error where it reads something else.

Each case is checked against ros-controls/ros2_control: hardware_interface/src/
component_parser.cpp (``parse_transmission_from_xml`` reads ``<plugin>``;
``get_parameter_value_or`` skips an element without text and defaults to 1.0 / 0.0),
transmission_interface/src/simple_transmission_loader.cpp (``SimpleTransmissionLoader::load``:
``joints.at(0)``) and transmission_interface/include/transmission_interface/
simple_transmission.hpp (``configure``: handles of one name).
"""

from __future__ import annotations

import pytest

from tests.rules.helpers import check, problems

ROBOT = """
<robot name="r">
  <link name="a"/><link name="b"/>
  <joint name="j" type="revolute"><parent link="a"/><child link="b"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <ros2_control name="hw" type="{component}">
    <hardware><plugin>my/Hardware</plugin></hardware>
    <joint name="j"><command_interface name="position"/></joint>
    <transmission name="t">
      <plugin>transmission_interface/SimpleTransmission</plugin>
      {inner}
    </transmission>
  </ros2_control>
</robot>
"""


def robot(inner: str, component: str = "system") -> str:
    return ROBOT.format(inner=inner, component=component)


@pytest.mark.parametrize(("inner", "severity"), [
    # the same type as <plugin>: what is loaded is what <type> says
    ("<type>transmission_interface/SimpleTransmission</type>"
     '<joint name="j" role="joint1"/>', "warning"),
    # another type: the one written in <type> is not loaded
    ("<type>transmission_interface/DifferentialTransmission</type>"
     '<joint name="j" role="joint1"/>', "error"),
])
def test_a_ros1_type_beside_plugin(inner, severity):
    assert check(robot(inner), select=["TX303"]) == [(10, 7, "TX303", severity)]


@pytest.mark.parametrize(("inner", "severity"), [
    # 1 is the default ros2_control uses without <mechanical_reduction>
    ('<joint name="j" role="joint1"><mechanicalReduction>1.0</mechanicalReduction></joint>',
     "warning"),
    ('<joint name="j" role="joint1"><mechanicalReduction>50</mechanicalReduction></joint>',
     "error"),
    # the same value as the <mechanical_reduction> ros2_control reads
    ('<joint name="j" role="joint1"><mechanical_reduction>50</mechanical_reduction>'
     "<mechanicalReduction>50</mechanicalReduction></joint>", "warning"),
    ('<joint name="j" role="joint1"><mechanical_reduction>50</mechanical_reduction>'
     "<mechanicalReduction>40</mechanicalReduction></joint>", "error"),
])
def test_a_ros1_reduction_spelling_loses_only_a_different_value(inner, severity):
    found = check(robot(inner), select=["TX303"])
    assert [(code, level) for _, _, code, level in found] == [("TX303", severity)]


@pytest.mark.parametrize(("number", "severity"), [
    ("<offset></offset>", "warning"),
    ("<offset>  </offset>", "warning"),
    ("<mechanical_reduction/>", "warning"),
    ("<mechanical_reduction><!-- later --></mechanical_reduction>", "warning"),
    ("<mechanical_reduction>fifty</mechanical_reduction>", "error"),
    # tinyxml2 >= 9's GetText() skips a leading comment: 0.5 is read (the loaders' compiled
    # parser agrees, tests/oracle), so nothing is lost and nothing is reported
    ("<offset><!-- c -->0.5</offset>", None),
])
def test_an_empty_number_is_read_as_absent(number, severity):
    found = problems(robot(f'<joint name="j" role="joint1">{number}</joint>'), select=["TX105"])
    assert [p.severity for p in found] == ([severity] if severity else [])
    if severity == "warning":
        assert "nothing written is lost" in found[0].message


def test_a_joint_listed_twice_by_one_name_loads():
    inner = '<joint name="j" role="joint1"/><joint name="j" role="joint1"/>'
    found = problems(robot(inner), select=["TX103"])
    assert [(p.line, p.column, p.severity) for p in found] == [(8, 5, "warning")]
    assert "joint 'j' is listed 2 times" in found[0].message


def test_two_joints_or_an_actuator_component_stay_errors():
    two = '<joint name="j" role="joint1"/><joint name="k" role="joint1"/>'
    assert check(robot(two), select=["TX103"]) == [(8, 5, "TX103", "error")]
    twice = '<joint name="j" role="joint1"/><joint name="j" role="joint1"/>'
    # in an actuator component the parser throws first (TX207)
    assert check(robot(twice, component="actuator"), select=["TX103", "TX207"]) == [
        (8, 5, "TX207", "error")]
