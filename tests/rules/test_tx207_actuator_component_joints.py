"""TX207: ros2_control's parser and an actuator component's transmissions
(hardware_interface/src/component_parser.cpp auto_fill_transmission_interfaces :670-685
@53b9999; tests/oracle/test_validate_reference.py compares the verdicts with the compiled
parser)."""

from __future__ import annotations

import pytest
from click.testing import CliRunner

from tests.rules.helpers import check, problems
from txtool.cli import cli

ROBOT = """
<robot name="r">
  <ros2_control name="hw" type="{component}">
    <joint name="a"><command_interface name="position"/></joint>
    <joint name="b"><command_interface name="position"/></joint>
    <transmission name="t">
      <plugin>transmission_interface/{plugin}</plugin>
      {members}
    </transmission>
  </ros2_control>
</robot>
"""
ONE = '<joint name="a" role="joint1"/>'
TWO = ONE + '<joint name="b" role="joint2"/>'
ACTUATORS = '<actuator name="m1" role="actuator1"/><actuator name="m2" role="actuator2"/>'


def robot(members: str, component: str = "actuator", plugin: str = "SimpleTransmission") -> str:
    return ROBOT.format(members=members, component=component, plugin=plugin)


@pytest.mark.parametrize("plugin", ["DifferentialTransmission", "FourBarLinkageTransmission",
                                    "SimpleTransmission", "my_pkg/CoupledTransmission"])
def test_two_joints_in_an_actuator_component_make_the_parser_throw(plugin):
    found = problems(robot(TWO + ACTUATORS, plugin=plugin), select=["TX207"])
    assert [(p.line, p.column, p.code, p.severity) for p in found] == [(5, 5, "TX207", "error")]
    assert found[0].message == (
        "transmission 't' of actuator component 'hw' names 2 joints: ros2_control's parser "
        "throws \"There should be exactly one joint defined in this component but found 2.\" "
        "and no hardware of the robot loads")


def test_no_joint_makes_it_throw_too():
    found = problems(robot('<actuator name="m1" role="actuator1"/>'), select=["TX207"])
    assert [(p.line, p.code) for p in found] == [(5, "TX207")]
    assert "names 0 joints" in found[0].message


@pytest.mark.parametrize("component", ["system", "sensor"])
def test_other_components_take_coupled_transmissions(component):
    assert check(robot(TWO + ACTUATORS, component=component,
                       plugin="DifferentialTransmission"), select=["TX207"]) == []


def test_the_component_type_is_stripped_as_the_parser_strips_it():
    assert check(robot(TWO, component=" actuator "), select=["TX207"]) == [
        (5, 5, "TX207", "error")]


def test_one_joint_without_actuator_passes():
    assert check(robot(ONE), select=["TX207"]) == []


def test_a_simple_actuator_of_another_name_is_refused_by_configure():
    # the parser appends 'actuator1' (component_parser.cpp:682-684); SimpleTransmission's
    # configure() wants identical actuator names (simple_transmission.hpp:197-219)
    found = problems(robot(ONE + '<actuator name="motor" role="actuator1"/>'), select=["TX207"])
    assert [(p.line, p.column, p.severity) for p in found] == [(7, 38, "error")]
    assert "configure() refuses two actuator names" in found[0].message
    named = robot(ONE + '<actuator name=" actuator1 " role="actuator1"/>')
    assert check(named, select=["TX207"]) == []


def test_a_transmission_nested_deeper_is_not_the_parsers():
    nested = ROBOT.format(members=TWO, component="actuator", plugin="SimpleTransmission")
    nested = nested.replace('<transmission name="t">', '<group><transmission name="t">').replace(
        "</transmission>", "</transmission></group>")
    assert check(nested, select=["TX207"]) == []


def test_a_ros1_transmission_is_not_counted_here():
    xml = """
    <robot name="r">
      <transmission name="t">
        <type>transmission_interface/SimpleTransmission</type>
        <joint name="a"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>
        <actuator name="m"><mechanicalReduction>1</mechanicalReduction></actuator>
      </transmission>
    </robot>
    """
    assert check(xml, select=["TX207"]) == []


def test_validate_exits_1_and_names_the_parsers_words(tmp_path):
    path = tmp_path / "wrist.urdf"
    path.write_text(robot(TWO + ACTUATORS, plugin="DifferentialTransmission").lstrip("\n"))
    result = CliRunner().invoke(cli, ["validate", str(path)])
    assert (result.exit_code, result.stdout) == (1, (
        f"{path}:5:5: error TX207 actuator-component-joints: transmission 't' of actuator "
        "component 'hw' names 2 joints: ros2_control's parser throws \"There should be exactly "
        "one joint defined in this component but found 2.\" and no hardware of the robot "
        "loads\nFound 1 error in 1 file.\n"))
