"""Every name and pattern that decides a file's readers, one row each: the ``<gazebo>`` plugin
file names (Gazebo Classic, Gazebo/gz, Ignition, vendors' renamed builds, with and without
``lib``/``.so`` and a folder), the RobotHWSim types, the ``<ros2_control>`` hardware plugins of
the simulators, the build types of ``package.xml`` and the plugin names another file of the
package may hold. Each row is a small file written here, read by ``txtool validate --format
json``; nothing from ../shared is needed."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from tests.lint.test_readers import GAZEBO, MANIFEST, ROBOT, ROS1_BAD, ROS_VARIABLES

ROS1_PAIR = ["gazebo_ros_control", "ros_control"]


@pytest.fixture(autouse=True)
def no_ros_environment(monkeypatch):
    for variable in ROS_VARIABLES:
        monkeypatch.delenv(variable, raising=False)


def readers_of(validate, path: Path) -> tuple[list[str], bool]:
    code, out, err = validate("--format", "json", str(path))
    assert code in (0, 1) and err == "", err
    (record,) = json.loads(out)["readers"]
    assert record["path"] == str(path)
    return record["readers"], record["decided"]


def gazebo(filename: str, inner: str = "") -> str:
    if not inner:
        return GAZEBO.format(filename=filename)
    return f'  <gazebo><plugin filename="{filename}" name="control">{inner}</plugin></gazebo>\n'


def sim_type(name: str) -> str:
    return f"<robotSimType>{name}</robotSimType>"


PLUGINS = [
    # Gazebo Classic, ROS 1: gazebo_ros_control and the plugins built on it
    ("libgazebo_ros_control.so", "", ROS1_PAIR),
    ("gazebo_ros_control.so", "", ROS1_PAIR),
    ("/opt/ros/noetic/lib/libgazebo_ros_control.so", "", ROS1_PAIR),
    ("  libgazebo_ros_control.so  ", "", ROS1_PAIR),
    ("libbaxter_gazebo_ros_control.so", "", ROS1_PAIR),  # RethinkRobotics/baxter_simulator
    ("libgazebo_ros_control.so", sim_type("gazebo_ros_control/DefaultRobotHWSim"), ROS1_PAIR),
    ("libgazebo_ros_control.so", sim_type(" franka_gazebo/FrankaHWSim "),
     ["franka_gazebo", "ros_control"]),
    # a RobotHWSim whose rules are not known: ros_control's loaders only
    ("libgazebo_ros_control.so", sim_type("acme_gazebo/AcmeHWSim"), ["ros_control"]),
    # Gazebo Classic, ROS 2
    ("libgazebo_ros2_control.so", "", ["gazebo_ros2_control", "ros2_control"]),
    ("gazebo_ros2_control", "", ["gazebo_ros2_control", "ros2_control"]),
    ("/opt/ros/humble/lib/libgazebo_ros2_control.so", "", ["gazebo_ros2_control",
                                                           "ros2_control"]),
    # Gazebo (gz) and Ignition, under both names, and a vendor's build (franka_ros2)
    ("gz_ros2_control-system", "", ["gz_ros2_control", "ros2_control"]),
    ("libgz_ros2_control-system.so", "", ["gz_ros2_control", "ros2_control"]),
    ("ign_ros2_control-system", "", ["gz_ros2_control", "ros2_control"]),
    ("libign_ros2_control-system.so", "", ["gz_ros2_control", "ros2_control"]),
    ("franka_ign_ros2_control-system", "", ["gz_ros2_control", "ros2_control"]),
    # plugins that read no transmission decide nothing
    ("libgazebo_ros_camera.so", "", []),
    ("libgazebo_ros_control_extra.so", "", []),
    ("gz_ros2_control-system-extra", "", []),
]


@pytest.mark.parametrize(("filename", "inner", "expected"), PLUGINS)
def test_each_gazebo_plugin_name_decides_its_readers(validate, tmp_path, filename, inner,
                                                     expected):
    path = tmp_path / "robot.urdf"
    path.write_text(ROBOT.format(body=ROS1_BAD + gazebo(filename, inner)))
    assert readers_of(validate, path) == (expected, bool(expected))


def test_a_plugin_outside_gazebo_decides_nothing(validate, tmp_path):
    path = tmp_path / "robot.urdf"
    plugin = '  <plugin filename="libgazebo_ros_control.so" name="control"/>\n'
    path.write_text(ROBOT.format(body=ROS1_BAD + plugin))
    assert readers_of(validate, path) == ([], False)


HARDWARE = [
    ("gazebo_ros2_control/GazeboSystem", ["ros2_control", "gazebo_ros2_control"]),
    ("gz_ros2_control/GazeboSimSystem", ["ros2_control", "gz_ros2_control"]),
    ("ign_ros2_control/IgnitionSystem", ["ros2_control", "gz_ros2_control"]),
    ("mujoco_ros2_control/MujocoSystem", ["ros2_control", "mujoco_ros2_control"]),
    (" mujoco_ros2_control/MujocoSystem ", ["ros2_control", "mujoco_ros2_control"]),
    ("mock_components/GenericSystem", ["ros2_control"]),
    ("acme/gz_ros2_control/System", ["ros2_control"]),  # a prefix, not a part
]
COMPONENT = """  <ros2_control name="arm" type="system">
    <hardware><plugin>{hardware}</plugin></hardware>
    <joint name="joint1"><command_interface name="position"/></joint>
  </ros2_control>
"""


@pytest.mark.parametrize(("hardware", "expected"), HARDWARE)
def test_each_simulator_hardware_plugin_is_a_reader_without_deciding(validate, tmp_path,
                                                                     hardware, expected):
    path = tmp_path / "robot.urdf"
    path.write_text(ROBOT.format(body=ROS1_BAD + COMPONENT.format(hardware=hardware)))
    assert readers_of(validate, path) == (expected, False)


def manifest(folder: Path, tools: list[str], export: str = "") -> None:
    (folder / "urdf").mkdir(parents=True)
    depends = "".join(f"<buildtool_depend>{tool}</buildtool_depend>" for tool in tools)
    text = MANIFEST.format(format=3, name=folder.name, tool="", export=export)
    (folder / "package.xml").write_text(
        text.replace("<buildtool_depend></buildtool_depend>", depends))


BUILDS = [
    (["catkin"], "", ["ros_control"]),
    (["ament_cmake"], "", ["ros2_control"]),
    (["ament_python"], "", ["ros2_control"]),
    ([], "<build_type>ament_cmake</build_type>", ["ros2_control"]),
    ([], "<build_type>ament_python</build_type>", ["ros2_control"]),
    ([], "<build_type>catkin</build_type>", ["ros_control"]),
    (["catkin"], "<build_type>ament_cmake</build_type>", ["ros2_control"]),  # export first
    (["cmake"], "", []),  # plain CMake: no ROS generation said
    ([], "", []),
]


@pytest.mark.parametrize(("tools", "export", "expected"), BUILDS)
def test_each_build_type_decides_the_readers_of_a_plain_file(validate, tmp_path, tools, export,
                                                             expected):
    folder = tmp_path / "robot_description"
    manifest(folder, tools, export)
    path = folder / "urdf" / "arm.urdf"
    path.write_text(ROBOT.format(body=ROS1_BAD))
    assert readers_of(validate, path) == (expected, bool(expected))


@pytest.mark.parametrize("tools", [["catkin", "ament_cmake"], ["ament_cmake", "catkin"]])
def test_a_package_built_by_both_generations_keeps_the_ros1_gazebo_plugin(validate, tmp_path,
                                                                         tools):
    folder = tmp_path / "robot_description"
    manifest(folder, tools)
    path = folder / "urdf" / "arm.urdf"
    path.write_text(ROBOT.format(body=ROS1_BAD + gazebo("libgazebo_ros_control.so")))
    assert readers_of(validate, path) == (ROS1_PAIR, True)


def test_a_package_only_ros2_builds_ignores_the_ros1_gazebo_plugin(validate, tmp_path):
    folder = tmp_path / "robot_description"
    manifest(folder, ["ament_cmake"])
    path = folder / "urdf" / "arm.urdf"
    path.write_text(ROBOT.format(body=ROS1_BAD + gazebo("libgazebo_ros_control.so")))
    assert readers_of(validate, path) == (["ros2_control"], True)


ELSEWHERE = [
    ("libgazebo_ros_control.so", ROS1_PAIR),
    ("/usr/lib/libbaxter_gazebo_ros_control.so", ROS1_PAIR),
    ("libgazebo_ros2_control.so", ["gazebo_ros2_control", "ros2_control"]),
    ("gz_ros2_control-system", ["gz_ros2_control", "ros2_control"]),
    ("libign_ros2_control-system.so", ["gz_ros2_control", "ros2_control"]),
]


@pytest.mark.parametrize("suffix", [".urdf", ".xacro", ".gazebo"])
@pytest.mark.parametrize(("filename", "expected"), ELSEWHERE)
def test_a_fragment_takes_the_plugin_another_file_of_its_catkin_package_names(
        validate, tmp_path, filename, expected, suffix):
    folder = tmp_path / "robot_description"
    manifest(folder, ["catkin"])
    other = folder / "urdf" / f"sim{suffix}"
    other.write_text(f'<robot name="arm">\n{gazebo(filename)}</robot>\n')
    path = folder / "urdf" / "arm.urdf"
    path.write_text(ROBOT.format(body=ROS1_BAD))
    assert readers_of(validate, path) == (expected, True)


def test_a_file_of_another_kind_names_no_plugin_for_the_package(validate, tmp_path):
    folder = tmp_path / "robot_description"
    manifest(folder, ["catkin"])
    (folder / "urdf" / "sim.txt").write_text(gazebo("libgz_ros2_control-system.so"))
    path = folder / "urdf" / "arm.urdf"
    path.write_text(ROBOT.format(body=ROS1_BAD))
    assert readers_of(validate, path) == (["ros_control"], True)
