"""TX306: the ROS 1 gazebo_ros_control plugin in a robot only ROS 2 programs read.

gazebo_ros_control is built only on gazebo_ros_pkgs' ROS 1 branches (ros-simulation/
gazebo_ros_pkgs noetic-devel; its ros2 branch has none): under ROS 2 Gazebo cannot load it. In a
package only ROS 2 builds, the package, not that plugin, says who reads the robot
(txtool/model/readers.py ``assume``). Packages are laid out as a user has them."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from click.testing import CliRunner

from tests.rules.test_gazebo_ros_control import PLUGIN
from txtool.cli import cli

MANIFEST = """<?xml version="1.0"?>
<package format="3">
  <name>arm_description</name>
  <version>1.0.0</version>
  <description>arm</description>
  <maintainer email="m@example.com">m</maintainer>
  <license>BSD</license>
  {depends}
</package>
"""
AMENT = "<buildtool_depend>ament_cmake</buildtool_depend><export><build_type>ament_cmake" \
        "</build_type></export>"
CATKIN = "<buildtool_depend>catkin</buildtool_depend>"
BOTH = ('<buildtool_depend condition="$ROS_VERSION == 1">catkin</buildtool_depend>'
        '<buildtool_depend condition="$ROS_VERSION == 2">ament_cmake</buildtool_depend>')
ROBOT = """<robot name="arm">
  <link name="base"/><link name="link1"/>
  <joint name="joint1" type="revolute"><parent link="base"/><child link="link1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  {plugin}
  <ros2_control name="arm" type="system">
    <hardware><plugin>mock_components/GenericSystem</plugin></hardware>
    <joint name="joint1"><command_interface name="position"/></joint>
    <transmission name="t">
      <plugin>transmission_interface/SimpleTransmission</plugin>
      <joint name="joint1" role="joint1"><mechanical_reduction>0</mechanical_reduction></joint>
    </transmission>
  </ros2_control>
</robot>
"""


@pytest.fixture(autouse=True)
def no_ros_environment(monkeypatch):
    for variable in ("AMENT_PREFIX_PATH", "ROS_PACKAGE_PATH", "CMAKE_PREFIX_PATH"):
        monkeypatch.delenv(variable, raising=False)


def robot_in(root: Path, depends: str | None, plugin: str = PLUGIN.format(extra="")) -> Path:
    folder = root / "arm_description"
    (folder / "urdf").mkdir(parents=True)
    if depends is not None:
        (folder / "package.xml").write_text(MANIFEST.format(depends=depends))
    path = folder / "urdf" / "arm.urdf"
    path.write_text(ROBOT.format(plugin=plugin))
    return path


def validate(path: Path, *args: str) -> tuple[int, list[tuple[int, int, str, str]], dict]:
    result = CliRunner().invoke(cli, ["validate", "--format", "json", *args, str(path)])
    report = json.loads(result.stdout)
    found = [(p["line"], p["column"], p["code"], p["severity"]) for p in report["problems"]]
    return result.exit_code, found, report


def test_in_an_ament_package_the_plugin_is_a_warning_and_ros2_control_judges_the_robot(
        tmp_path):
    code, found, report = validate(robot_in(tmp_path, AMENT))
    # the zero reduction ros2_control refuses is judged (it was an unread transmission while
    # the ROS 1 plugin decided the readers), and the plugin is named
    assert (code, found) == (1, [(6, 5, "TX306", "warning"), (13, 42, "TX106", "error")])
    assert report["readers"][0]["readers"] == ["ros2_control"]
    assert report["readers"][0]["because"] == ["package.xml: ament_cmake"]
    message = next(p["message"] for p in report["problems"] if p["code"] == "TX306")
    assert message == (
        "<gazebo> plugin libgazebo_ros_control.so is gazebo_ros_control, a ROS 1 plugin no ROS 2 "
        "distribution builds, and only ROS 2 programs read this robot (ros2_control): Gazebo "
        "cannot load it and nothing in simulation reads the transmissions; name "
        "gazebo_ros2_control (libgazebo_ros2_control.so) or gz_ros2_control "
        "(gz_ros2_control-system)")


@pytest.mark.parametrize("depends", [CATKIN, BOTH, None])
def test_where_ros1_may_build_the_package_the_plugin_decides_as_before(tmp_path, depends):
    code, found, report = validate(robot_in(tmp_path, depends))
    assert "TX306" not in {c for _, _, c, _ in found}
    assert report["readers"][0]["readers"] == ["gazebo_ros_control", "ros_control"]


def test_a_ros2_distribution_said_on_the_command_line_reports_it_too(tmp_path):
    code, found, _ = validate(robot_in(tmp_path, None), "--ros-distro", "jazzy")
    assert (6, 5, "TX306", "warning") in found
    _, found, _ = validate(robot_in(tmp_path / "other", None), "--ros-distro", "noetic")
    assert "TX306" not in {c for _, _, c, _ in found}


def test_the_ros2_plugin_is_no_finding(tmp_path):
    plugin = '<gazebo><plugin filename="libgazebo_ros2_control.so" name="g"/></gazebo>'
    _, found, _ = validate(robot_in(tmp_path, AMENT, plugin=plugin))
    assert "TX306" not in {c for _, _, c, _ in found}


def test_the_text_report_says_it_with_exit_1_for_the_refused_reduction(tmp_path):
    path = robot_in(tmp_path, AMENT)
    result = CliRunner().invoke(cli, ["validate", "--select", "TX306", str(path)])
    assert (result.exit_code, result.stdout.splitlines()[-1]) == (0, "Found 1 warning in 1 file.")
    assert result.stdout.startswith(f"{path}:6:5: warning TX306 ros1-gazebo-plugin: ")
