"""Readers: the programs that read a file's transmissions decide its verdicts.

Each case is a package laid out in tmp_path as a user has it (package.xml beside urdf/), with
the findings `txtool validate` gives and the readers its JSON report names. Layouts are modelled
on real packages (source noted at each); no third-party file is copied.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest

ROS_VARIABLES = ("AMENT_PREFIX_PATH", "ROS_PACKAGE_PATH", "CMAKE_PREFIX_PATH")

MANIFEST = """<?xml version="1.0"?>
<package format="{format}">
  <name>{name}</name>
  <version>1.0.0</version>
  <description>robot</description>
  <maintainer email="m@example.com">m</maintainer>
  <license>BSD</license>
  <buildtool_depend>{tool}</buildtool_depend>
  <export>{export}</export>
</package>
"""
# A ROS 1 transmission ros_control refuses (no <mechanicalReduction>, unprefixed interface).
ROS1_BAD = """  <transmission name="trans1">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="joint1"><hardwareInterface>PositionJointInterface</hardwareInterface></joint>
    <actuator name="actuator1"/>
  </transmission>
"""
COMPONENT = """  <ros2_control name="arm" type="system">
    <hardware><plugin>{hardware}</plugin></hardware>
    <joint name="joint1"><command_interface name="position"/><state_interface name="position"/>
    </joint>
{inner}  </ros2_control>
"""
ROBOT = """<robot name="arm">
  <link name="base"/><link name="link1"/>
  <joint name="joint1" type="revolute"><parent link="base"/><child link="link1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
{body}</robot>
"""
GAZEBO = '  <gazebo><plugin filename="{filename}" name="control"/></gazebo>\n'


@pytest.fixture(autouse=True)
def no_ros_environment(monkeypatch):
    for variable in ROS_VARIABLES:
        monkeypatch.delenv(variable, raising=False)


def package(root: Path, name: str, tool: str, *, export: str = "", fmt: int = 3) -> Path:
    folder = root / name
    (folder / "urdf").mkdir(parents=True)
    if tool.startswith("ament"):
        export = f"<build_type>{tool}</build_type>{export}"
    (folder / "package.xml").write_text(
        MANIFEST.format(format=fmt, name=name, tool=tool, export=export))
    return folder


def robot_file(folder: Path, body: str, name: str = "arm.urdf") -> Path:
    path = folder / "urdf" / name
    path.write_text(ROBOT.format(body=body))
    return path


def findings(validate, *args: str) -> tuple[int, list[tuple[int, int, str, str]], dict]:
    code, out, err = validate("--format", "json", *args)
    assert err == ""
    report = json.loads(out)
    found = [(p["line"], p["column"], p["code"], p["severity"]) for p in report["problems"]]
    return code, found, report


def test_ros1_transmissions_in_an_ament_package_with_ros2_control_get_one_info_each(
        validate, tmp_path):
    # Modelled on ROBOTIS-GIT/turtlebot3_manipulation @91492d7
    # turtlebot3_manipulation_description (ament_cmake; stale ROS 1 transmissions beside the
    # ros2_control block): no ROS 1 verdict about their contents, one TX305 each.
    folder = package(tmp_path, "arm_description", "ament_cmake")
    body = ROS1_BAD + COMPONENT.format(hardware="mock_components/GenericSystem", inner="")
    path = robot_file(folder, body)
    code, found, report = findings(validate, str(path))
    assert (code, found) == (0, [(5, 3, "TX305", "info")])
    assert report["readers"] == [{"path": str(path), "readers": ["ros2_control"],
                                  "because": ["package.xml: ament_cmake"], "decided": True}]


def test_the_same_robot_in_a_catkin_package_is_judged_by_ros_control(validate, tmp_path):
    folder = package(tmp_path, "arm_description", "catkin", fmt=2)
    path = robot_file(folder, ROS1_BAD)
    code, found, report = findings(validate, str(path))
    assert code == 1
    assert {c for _, _, c, _ in found} == {"TX104", "TX300"}  # TX300 says TX205's refusal
    assert report["readers"][0]["readers"] == ["ros_control"]
    assert report["readers"][0]["because"] == ["package.xml: catkin"]


def test_a_bare_file_keeps_the_dialect_verdicts(validate, tmp_path):
    body = ROS1_BAD + COMPONENT.format(hardware="mock_components/GenericSystem", inner="")
    path = tmp_path / "arm.urdf"
    path.write_text(ROBOT.format(body=body))
    code, found, report = findings(validate, str(path))
    assert code == 1
    # as before readers: TX304 beside the verdicts of ros_control (TX205 stays silent then)
    assert {c for _, _, c, _ in found} == {"TX104", "TX300", "TX304"}
    assert report["readers"][0]["decided"] is False
    assert report["readers"][0]["because"] == ["<ros2_control> blocks"]


@pytest.mark.parametrize("filename", ["libgazebo_ros2_control.so", "gz_ros2_control-system",
                                      "ign_ros2_control-system"])
def test_a_ros2_gazebo_plugin_without_ros2_control_is_refused(validate, tmp_path, filename):
    # The field case: the robot's only Gazebo plugin is gazebo_ros2_control, no <ros2_control>
    # (gazebo_ros2_control_plugin.cpp Load: "plugin not active").
    path = tmp_path / "arm.urdf"
    path.write_text(ROBOT.format(body=ROS1_BAD + GAZEBO.format(filename=filename)))
    code, found, report = findings(validate, str(path))
    assert (code, found) == (1, [(5, 3, "TX305", "info"), (10, 11, "TX007", "error")])
    assert report["readers"][0]["because"][0] == f"<gazebo> plugin {filename}"


def test_a_ros2_form_outside_ros2_control_in_a_ros2_robot_is_a_warning(validate, tmp_path):
    folder = package(tmp_path, "arm_description", "ament_python")
    top = ('  <transmission name="t"><plugin>transmission_interface/SimpleTransmission</plugin>'
           '<joint name="joint1" role="joint1"/><actuator name="m" role="actuator1"/>'
           "</transmission>\n")
    body = top + COMPONENT.format(hardware="mock_components/GenericSystem", inner="")
    code, found, _ = findings(validate, str(robot_file(folder, body)))
    assert (code, found) == (0, [(5, 3, "TX305", "warning")])


def test_ros2_control_blocks_in_a_catkin_package_are_read_by_nothing(validate, tmp_path):
    folder = package(tmp_path, "arm_description", "catkin")
    inner = ('    <transmission name="t"><plugin>transmission_interface/SimpleTransmission'
             '</plugin><joint name="joint1" role="joint1"><mechanical_reduction>abc'
             "</mechanical_reduction></joint></transmission>\n")
    body = COMPONENT.format(hardware="mock_components/GenericSystem", inner=inner)
    code, found, _ = findings(validate, str(robot_file(folder, body)))
    assert (code, found) == (0, [(9, 5, "TX305", "info")])  # no TX105 about 'abc'


def test_the_document_plugin_wins_over_the_package(validate, tmp_path):
    # A catkin package whose robot runs gazebo_ros_control: ros_control's refusals that
    # DefaultRobotHWSim accepts are warnings (as without a package).
    folder = package(tmp_path, "arm_description", "catkin")
    body = ROS1_BAD + GAZEBO.format(filename="libgazebo_ros_control.so")
    code, found, report = findings(validate, str(robot_file(folder, body)))
    assert code == 0 and {s for *_, s in found} == {"warning"}
    assert report["readers"][0]["readers"] == ["gazebo_ros_control", "ros_control"]


def test_ros_distro_states_the_readers(validate, tmp_path):
    path = tmp_path / "arm.urdf"
    path.write_text(ROBOT.format(body=ROS1_BAD))
    code, found, report = findings(validate, "--ros-distro", "jazzy", str(path))
    assert (code, found) == (0, [(5, 3, "TX305", "info")])
    assert report["readers"][0]["readers"] == ["ros2_control (jazzy)"]
    assert report["readers"][0]["because"] == ["--ros-distro jazzy"]
    code, found, report = findings(validate, "--ros-distro", "noetic", str(path))
    assert code == 1 and "TX104" in {c for _, _, c, _ in found}
    code, out, err = validate("--ros-distro", "indigo", str(path))
    assert code == 2 and "'indigo' is not one of" in err


def test_readers_and_ros_distro_in_the_configuration(validate, tmp_path):
    path = tmp_path / "arm.urdf"
    path.write_text(ROBOT.format(body=ROS1_BAD))
    config = tmp_path / ".txtool.toml"
    config.write_text('readers = ["ros2_control", "gz_ros2_control"]\nros-distro = "humble"\n')
    code, found, report = findings(validate, str(path))
    assert (code, found) == (0, [(5, 3, "TX305", "info")])
    assert report["readers"][0]["readers"] == ["ros2_control (humble)", "gz_ros2_control (humble)"]
    assert report["readers"][0]["because"] == [f"readers in the {config}"] * 2
    config.write_text('ros-distro = "humble"\n')
    _, _, report = findings(validate, str(path))
    assert report["readers"][0]["because"] == [f"ros-distro humble in {config}"]
    _, _, report = findings(validate, "--ros-distro", "noetic", str(path))
    assert report["readers"][0]["because"] == ["--ros-distro noetic"]


@pytest.mark.parametrize(("text", "reason"), [
    ('readers = ["ros3_control"]\n', "key 'readers': unknown reader 'ros3_control'"),
    ('readers = []\n', "key 'readers': name at least one reader"),
    ('ros-distro = "indigo"\n', "key 'ros-distro': unknown ROS distribution 'indigo'"),
])
def test_a_bad_readers_configuration_is_one_line_and_exit_2(validate, tmp_path, text, reason):
    path = tmp_path / "arm.urdf"
    path.write_text(ROBOT.format(body=ROS1_BAD))
    (tmp_path / ".txtool.toml").write_text(text)
    code, out, err = validate(str(path))
    assert code == 2 and out == ""
    assert err.count("\n") == 1 and reason in err and str(tmp_path / ".txtool.toml") in err


VENDOR_PLUGINS = """<library path="lib/libvendor_transmissions">
  <class name="transmission_interface/HalfDifferentialTransmission"
         type="transmission_interface::HalfDifferentialTransmissionLoader"
         base_class_type="transmission_interface::TransmissionLoader">
    <description>half differential</description>
  </class>
</library>
"""
HALF = ROS1_BAD.replace("SimpleTransmission", "HalfDifferentialTransmission").replace(
    "PositionJointInterface", "hardware_interface/PositionJointInterface").replace(
    '<actuator name="actuator1"/>',
    '<actuator name="actuator1"><mechanicalReduction>2</mechanicalReduction></actuator>')


def test_a_type_a_workspace_package_exports_with_pluginlib_is_known(validate, tmp_path):
    # Modelled on pal-robotics/pal_transmissions @ba07389 (package.xml exports
    # ros_control_plugins.xml registering transmission_interface/HalfDifferentialTransmission)
    # and pal-robotics/talos_robot @221f916 talos_description (a catkin package using it).
    src = tmp_path / "ws" / "src"
    vendor = package(src, "vendor_transmissions", "catkin",
                     export='<transmission_interface plugin="${prefix}/plugins.xml"/>')
    (vendor / "plugins.xml").write_text(VENDOR_PLUGINS)
    robot = robot_file(package(src, "talos_like_description", "catkin"), HALF)
    assert findings(validate, str(robot))[:2] == (0, [])
    (vendor / "package.xml").unlink()  # the vendor package is not in this workspace
    other = robot_file(package(tmp_path / "ws2" / "src", "other_description", "catkin"), HALF)
    code, found, _ = findings(validate, str(other))
    assert (code, found) == (0, [(6, 5, "TX113", "warning")])


def test_a_type_exported_on_ament_prefix_path_is_known(validate, tmp_path, monkeypatch):
    prefix = tmp_path / "install"
    vendor = package(prefix / "share", "vendor_transmissions", "ament_cmake",
                     export='<transmission_interface plugin="${prefix}/plugins.xml"/>')
    (vendor / "plugins.xml").write_text(VENDOR_PLUGINS)
    monkeypatch.setenv("AMENT_PREFIX_PATH", str(prefix))
    inner = ('    <transmission name="t"><plugin>transmission_interface/'
             'HalfDifferentialTransmission</plugin><joint name="joint1" role="joint1"/>'
             '<actuator name="m" role="actuator1"/></transmission>\n')
    path = tmp_path / "arm.urdf"
    path.write_text(ROBOT.format(body=COMPONENT.format(hardware="my/Hw", inner=inner)))
    assert findings(validate, str(path))[:2] == (0, [])
    monkeypatch.delenv("AMENT_PREFIX_PATH")
    assert findings(validate, str(path))[1] == [(9, 28, "TX113", "warning")]


def test_a_ros1_macro_library_in_a_ros2_package_is_read_by_nothing(validate, tmp_path):
    # Modelled on turtlebot3_manipulation_description/gazebo/open_manipulator_x.gazebo.xacro
    # (ROBOTIS-GIT/turtlebot3_manipulation @91492d7): a macro of ROS 1 transmissions with
    # unprefixed interfaces, in an ament_cmake package.
    folder = package(tmp_path, "arm_description", "ament_cmake")
    macro = ('<robot xmlns:xacro="http://ros.org/wiki/xacro">\n'
             '  <xacro:macro name="SimpleTransmission" params="trans joint actuator">\n'
             + ROS1_BAD.replace('"trans1"', '"${trans}"') +
             "  </xacro:macro>\n</robot>\n")
    path = folder / "urdf" / "arm.gazebo.xacro"
    path.write_text(macro)
    code, found, report = findings(validate, str(path))
    assert (code, found) == (0, [(3, 3, "TX305", "info")])
    assert "'${trans}' is written in the ROS 1 form in a macro" in report["problems"][0]["message"]


def test_show_effective_names_the_readers(tmp_path):
    from click.testing import CliRunner

    from txtool.cli import cli

    folder = package(tmp_path, "arm_description", "ament_cmake")
    body = ROS1_BAD + COMPONENT.format(hardware="mock_components/GenericSystem", inner="")
    path = robot_file(folder, body)
    result = CliRunner().invoke(cli, ["show", "--effective", str(path)])
    assert result.exit_code == 0
    assert result.stdout.endswith("\nReaders:\n  ros2_control (package.xml: ament_cmake)\n"
                                  "Read by none of them: 'trans1'\n")
    # the transmission itself says it too, not "read by ros_control"
    assert ("trans1 (line 5): SimpleTransmission\n  read by none of this file's readers "
            "(written for ros_control; below, what it would bind)") in result.stdout
    result = CliRunner().invoke(cli, ["show", "--effective", "--format", "json",
                                      "--ros-distro", "humble", str(path)])
    assert json.loads(result.stdout)["readers"] == {
        "readers": ["ros2_control (humble)"], "because": ["--ros-distro humble"],
        "decided": True, "unread": ["trans1"]}


def test_a_fragment_is_read_by_the_gazebo_plugin_its_package_names(validate, tmp_path):
    # Modelled on RobotnikAutomation/summit_xl_common @bb11a00 summit_xl_description: a macro
    # file of transmissions with an unprefixed interface (urdf/bases/summit_x_base.urdf.xacro)
    # whose robots load them through libgazebo_ros_control.so, named in another file of the
    # package (urdf/bases/summit_xl_base.gazebo.xacro), which accepts the unprefixed name.
    folder = package(tmp_path, "base_description", "catkin", fmt=2)
    (folder / "urdf" / "base.gazebo.xacro").write_text(
        '<robot xmlns:xacro="http://ros.org/wiki/xacro"><xacro:macro name="ros_control">'
        '<gazebo><plugin name="ros_control" filename="libgazebo_ros_control.so">'
        "<robotSimType>gazebo_ros_control/DefaultRobotHWSim</robotSimType></plugin></gazebo>"
        "</xacro:macro></robot>\n")
    wheel = ROS1_BAD.replace('"trans1"', '"${name}_trans"').replace(
        '<actuator name="actuator1"/>',
        '<actuator name="m"><mechanicalReduction>1</mechanicalReduction></actuator>').replace(
        "PositionJointInterface", "EffortJointInterface")
    path = folder / "urdf" / "base.urdf.xacro"
    path.write_text('<robot xmlns:xacro="http://ros.org/wiki/xacro">\n'
                    '  <xacro:macro name="wheel" params="name">\n' + wheel +
                    "  </xacro:macro>\n</robot>\n")
    code, found, report = findings(validate, str(path))
    assert code == 0 and {(c, s) for *_, c, s in found} == {("TX300", "warning")}
    assert report["readers"][0]["because"][0] == (
        "<gazebo> plugin libgazebo_ros_control.so in urdf/base.gazebo.xacro")
    (folder / "urdf" / "base.gazebo.xacro").unlink()
    other = package(tmp_path / "other", "base_description", "catkin", fmt=2)
    (other / "urdf" / "base.urdf.xacro").write_text(path.read_text())
    code, found, _ = findings(validate, str(other / "urdf" / "base.urdf.xacro"))
    assert code == 1 and ("TX300", "error") in {(c, s) for *_, c, s in found}


def test_a_vendor_build_of_a_ros2_gazebo_plugin_is_recognised(validate, tmp_path):
    # frankaemika/franka_description (robots/common/franka_arm.ros2_control.xacro) names
    # franka_ign_ros2_control-system, a build of ign_ros2_control.
    body = COMPONENT.format(hardware="franka_ign_ros2_control/IgnitionSystem", inner="") + \
        GAZEBO.format(filename="franka_ign_ros2_control-system") + ROS1_BAD
    path = tmp_path / "arm.urdf"
    path.write_text(ROBOT.format(body=body))
    code, found, report = findings(validate, str(path))
    assert (code, found) == (0, [(11, 3, "TX305", "info")])
    assert report["readers"][0]["readers"] == ["gz_ros2_control", "ros2_control"]


@pytest.mark.parametrize(("distro", "offset"), [("humble", "0 (default)"), ("jazzy", "-1")])
def test_show_effective_shows_the_stated_distributions_values(tmp_path, distro, offset):
    from click.testing import CliRunner

    from txtool.cli import cli

    folder = package(tmp_path, "arm_description", "ament_cmake")
    inner = ('    <transmission name="t"><plugin>transmission_interface/SimpleTransmission'
             '</plugin><actuator name="m" role="actuator1"/><joint name="joint1" role="joint1">'
             "<offset>+-1</offset></joint></transmission>\n")
    body = COMPONENT.format(hardware="mock_components/GenericSystem", inner=inner)
    path = robot_file(folder, body)
    result = CliRunner().invoke(cli, ["show", "--effective", "--ros-distro", distro, str(path)])
    assert result.exit_code == 0
    row = next(line for line in result.stdout.splitlines() if line.strip().startswith("0 "))
    assert offset in row, result.stdout
