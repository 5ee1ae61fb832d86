"""TX208: two <ros2_control> blocks of one name (ros-controls/ros2_control
hardware_interface/src/resource_manager.cpp: ``check_for_duplicates`` throws on the humble
branch @0941f73; ``load_and_initialize_components`` loads nothing from Jazzy on @53b9999)."""

from __future__ import annotations

import pytest
from click.testing import CliRunner

from tests.rules.helpers import check, problems
from txtool.cli import cli

ROBOT = """
<robot name="r">
  <link name="a"/><link name="b"/><link name="c"/>
  <joint name="j1" type="revolute"><parent link="a"/><child link="b"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="j2" type="revolute"><parent link="b"/><child link="c"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <ros2_control name="{first}" type="system">
    <hardware><plugin>mock_components/GenericSystem</plugin></hardware>
    <joint name="j1"><command_interface name="position"/></joint>
  </ros2_control>
  <ros2_control name="{second}" type="sensor">
    <hardware><plugin>mock_components/GenericSystem</plugin></hardware>
    <joint name="j2"><state_interface name="position"/></joint>
  </ros2_control>
</robot>
"""


def robot(first: str = "arm", second: str = "arm") -> str:
    return ROBOT.format(first=first, second=second)


def test_the_second_block_of_one_name_is_an_error():
    found = problems(robot(), select=["TX208"])
    assert [(p.line, p.column, p.code, p.severity) for p in found] == [(11, 3, "TX208", "error")]
    assert found[0].message.startswith(
        "<ros2_control> name 'arm' is also the name of the block at line 7: ros2_control's "
        "resource manager refuses it (\"Hardware name arm is duplicated\")")


def test_names_of_their_own_pass():
    assert check(robot(second="gripper"), select=["TX208"]) == []


@pytest.mark.parametrize(("distro", "expected"), [
    (None, [(11, 3, "TX208", "error")]),  # Jazzy and later strip the name
    ("jazzy", [(11, 3, "TX208", "error")]),
    ("humble", []),  # Humble's get_attribute_value returns the name as written
    ("noetic", []),  # only ROS 1 reads the file: nothing reads the blocks
])
def test_names_compare_as_each_distribution_reads_them(distro, expected):
    options = {"ros-distro": distro} if distro else {}
    assert check(robot(second=" arm "), select=["TX208"], **options) == expected


def test_a_xacro_macro_called_twice_writes_two_blocks_of_one_name():
    xml = """
    <robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
      <link name="a"/><link name="b"/>
      <joint name="j1" type="revolute"><parent link="a"/><child link="b"/>
        <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
      <xacro:macro name="hw" params="joint">
        <ros2_control name="robot" type="system">
          <hardware><plugin>mock_components/GenericSystem</plugin></hardware>
          <joint name="${joint}"><state_interface name="position"/></joint>
        </ros2_control>
      </xacro:macro>
      <xacro:hw joint="j1"/>
      <xacro:hw joint="j1"/>
    </robot>
    """
    found = problems(xml, filename="robot.urdf.xacro", select=["TX208"])
    assert [(p.code, p.severity) for p in found] == [("TX208", "error")]
    # found in the expansion: said at the block in the macro, with the call that made it
    assert [note.message for note in found[0].related] == [
        "expanded from the call of macro 'hw' at robot.urdf.xacro:12"]


def test_validate_exits_1(tmp_path):
    path = tmp_path / "robot.urdf"
    path.write_text(robot().lstrip("\n"))
    result = CliRunner().invoke(cli, ["validate", "--select", "TX208", str(path)])
    assert (result.exit_code, result.stdout) == (1, (
        f"{path}:11:3: error TX208 duplicate-component-name: <ros2_control> name 'arm' is also "
        "the name of the block at line 7: ros2_control's resource manager refuses it "
        "(\"Hardware name arm is duplicated\"): Humble throws and the controller manager "
        "stops; from Jazzy on no hardware of the robot is loaded\nFound 1 error in 1 file.\n"))
