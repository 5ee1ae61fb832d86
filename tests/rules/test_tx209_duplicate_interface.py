"""TX209: an interface two <ros2_control> blocks export (ros-controls/ros2_control
hardware_interface/src/resource_manager.cpp: ``std::map::emplace`` keeps the first handle on
the humble branch @0941f73; ``add_state_interface`` and ``insert_command_interface`` throw
"Tried to insert ... with already existing key" @53b9999)."""

from __future__ import annotations

from click.testing import CliRunner

from tests.rules.helpers import check, problems
from txtool.cli import cli

ROBOT = """
<robot name="r">
  <link name="a"/><link name="b"/>
  <joint name="j1" type="revolute"><parent link="a"/><child link="b"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <ros2_control name="arm" type="system">
    <hardware><plugin>my_hardware/Arm</plugin></hardware>
    <joint name="j1"><command_interface name="position"/><state_interface name="position"/>
    </joint>
    <gpio name="io"><command_interface name="out"/></gpio>
  </ros2_control>
  <ros2_control name="other" type="{kind}">
    <hardware><plugin>mock_components/GenericSystem</plugin></hardware>
    {second}
  </ros2_control>
</robot>
"""


def robot(second: str, kind: str = "system") -> str:
    return ROBOT.format(second=second, kind=kind)


def test_a_joint_claimed_by_two_blocks_is_one_finding_naming_every_clash():
    xml = robot('<joint name="j1"><command_interface name="position"/>'
                '<state_interface name="position"/></joint>')
    found = problems(xml, select=["TX209"])
    assert [(p.line, p.column, p.code, p.severity) for p in found] == [(13, 5, "TX209", "error")]
    assert found[0].message == (
        "joint 'j1' of <ros2_control> 'other' exports command interface 'j1/position' and state "
        "interface 'j1/position', which <ros2_control> 'arm' (line 5) exports too: "
        "ros2_control's resource manager keeps one handle per name (Humble drops this block's "
        "without a word; from Jazzy on it logs \"Tried to insert CommandInterface / "
        "StateInterface with already existing key\"), so this block's hardware never gets them")


def test_a_joint_shared_with_other_interfaces_passes():
    # ros2_control's modular robot examples: an actuator commands, a sensor reads the position
    xml = robot('<joint name="j1"><state_interface name="velocity"/></joint>', kind="sensor")
    assert check(xml, select=["TX209"]) == []


def test_command_and_state_names_are_separate_maps():
    xml = robot('<gpio name="io"><state_interface name="out"/></gpio>')
    assert check(xml, select=["TX209"]) == []


def test_gpios_and_sensors_clash_by_their_full_names():
    xml = robot('<gpio name="io"><command_interface name="out"/></gpio>')
    assert check(xml, select=["TX209"]) == [(13, 5, "TX209", "error")]
    sensor = robot('<sensor name="j1"><state_interface name="position"/></sensor>',
                   kind="sensor")
    assert check(sensor, select=["TX209"]) == [(13, 5, "TX209", "error")]


def test_names_are_stripped_from_jazzy_on_and_compared_as_written_on_humble():
    xml = robot('<joint name=" j1"><state_interface name="position "/></joint>')
    assert check(xml, select=["TX209"]) == [(13, 5, "TX209", "error")]
    assert check(xml, select=["TX209"], **{"ros-distro": "humble"}) == []


def test_one_block_alone_is_not_judged_here():
    xml = robot("").replace('<ros2_control name="other"', '<other name="other"').replace(
        "</ros2_control>\n</robot>", "</other>\n</robot>")
    assert check(xml, select=["TX209"]) == []


def test_validate_exits_1_where_a_second_block_claims_a_joint(tmp_path):
    path = tmp_path / "robot.urdf"
    path.write_text(robot('<joint name="j1"><command_interface name="position"/></joint>')
                    .lstrip("\n"))
    result = CliRunner().invoke(cli, ["validate", "--select", "TX209", str(path)])
    assert result.exit_code == 1
    assert result.stdout.startswith(
        f"{path}:13:5: error TX209 duplicate-interface: joint 'j1' of <ros2_control> 'other' "
        "exports command interface 'j1/position', which <ros2_control> 'arm' (line 5) exports "
        "too")
    assert result.stdout.endswith("never gets it\nFound 1 error in 1 file.\n")
