"""simulate reads each file as validate decides its readers do: what no reader reads is not
simulated, numbers are read as the reading distribution reads them, and the report names the
readers."""

from __future__ import annotations

import json

from click.testing import CliRunner

from tests.simulate.robots import arm_both, arm_ros1, arm_ros2, write
from txtool.cli import cli

PACKAGE = """<package format="3"><name>arm_description</name><version>1.0.0</version>
  <description>arm</description><maintainer email="m@example.com">m</maintainer>
  <license>BSD</license><buildtool_depend>{tool}</buildtool_depend>
  <export><build_type>{tool}</build_type></export></package>"""
GAZEBO_ROS_CONTROL = """<gazebo><plugin name="control" filename="libgazebo_ros_control.so"/>
</gazebo>"""


def txtool(*args: str) -> tuple[int, str, str]:
    result = CliRunner().invoke(cli, ["simulate", *args], catch_exceptions=False)
    return result.exit_code, result.stdout, result.stderr


def in_package(folder, tool: str):
    (folder / "package.xml").write_text(PACKAGE.format(tool=tool), encoding="utf-8")
    return folder


def test_a_ros2_robots_stale_ros1_transmissions_are_not_simulated_and_named(tmp_path):
    robot = write(in_package(tmp_path, "ament_cmake"), "arm.urdf", arm_both())
    code, out, err = txtool(robot, "--duration", "1", "--format", "json")
    assert (code, err) == (0, "")
    doc = json.loads(out)["runs"][0]
    assert doc["readers"]["robot"] == {
        "path": robot, "readers": ["ros2_control"], "because": ["package.xml: ament_cmake"],
        "decided": True}
    checked = doc["checked"]
    assert (checked["transmissions"], checked["simulated"]) == (2, ["t_shoulder", "t_wrist"])
    why = ("read by no reader of the file: it stands outside every <ros2_control> block, and "
           "the file's readers read only the transmissions inside one (ros2_control "
           "(package.xml: ament_cmake))")
    assert checked["unread"] == {"t_shoulder": why, "t_wrist": why}
    assert doc["verdict"] == "pass"


def test_the_verdict_counts_every_transmission_of_the_file(tmp_path):
    """4 transmissions in the file, 2 of them ROS 1 ones ros2_control does not read: "2 of 4",
    not "2 of 2" (a file of 5 said "checked 1 of 1")."""
    robot = write(in_package(tmp_path, "ament_cmake"), "arm.urdf", arm_both())
    code, out, err = txtool(robot, "--duration", "1")
    assert (code, err) == (0, "")
    assert out.splitlines()[-1].endswith(
        "no limit exceeded; checked 2 of 4 transmissions (2 read by no reader of the file) and "
        "3 of 3 joints")


def test_a_ros2_package_whose_file_holds_only_ros1_transmissions_checks_nothing(tmp_path):
    robot = write(in_package(tmp_path, "ament_cmake"), "arm.urdf", arm_ros1())
    code, out, err = txtool(robot, "--duration", "1")
    assert (code, err) == (3, "")
    assert "read by: ros2_control (package.xml: ament_cmake)" in out
    assert ("INCONCLUSIVE: nothing checked: no reader of the config reads any of its 2 "
            "transmissions (read by no reader of the file: it stands outside every "
            "<ros2_control> block") in out
    assert "FAIL" not in out


def test_a_ros1_package_simulates_its_top_level_transmissions_not_its_ros2_control_block(
        tmp_path):
    ros2_wrong = arm_both().replace("<mechanical_reduction>50<", "<mechanical_reduction>-50<")
    robot = write(in_package(tmp_path, "catkin"), "arm.urdf", ros2_wrong)
    code, out, err = txtool(robot, "--duration", "1")
    assert (code, err) == (0, "")
    assert "read by: ros_control (package.xml: catkin)\n" in out
    assert ("transmission 't_shoulder' is not simulated: read by no reader of the file: it "
            "stands inside a <ros2_control> block, and the file's readers read only top-level "
            "transmissions (ros_control (package.xml: catkin))") in out
    assert "has both ROS 1 and ROS 2 transmissions" not in out
    assert "PASS" in out


def test_a_file_read_by_gazebo_ros_control_names_it_and_the_robots_own_hardware(tmp_path):
    robot = write(tmp_path, "arm.urdf", arm_both().replace("</robot>",
                                                           GAZEBO_ROS_CONTROL + "</robot>"))
    code, out, err = txtool(robot, "--duration", "1", "--format", "json")
    assert (code, err) == (0, "")
    doc = json.loads(out)["runs"][0]
    assert doc["readers"]["robot"]["readers"] == ["gazebo_ros_control", "ros_control"]
    assert doc["checked"]["simulated"] == ["t_shoulder", "t_wrist"]
    assert set(doc["checked"]["unread"]) == {"t_shoulder", "t_wrist"}  # the ros2_control ones
    assert all("stands inside a <ros2_control> block" in why
               for why in doc["checked"]["unread"].values())


def _distro_pair(tmp_path) -> tuple[str, str]:
    """A robot whose shoulder reduction '+-50' Humble reads as the default 1 and Jazzy as -50
    (lexical_casts.cpp drops one '+' before from_chars), and a config that writes -50."""
    folder = in_package(tmp_path, "ament_cmake")
    robot = write(folder, "robot.urdf", arm_ros2().replace(
        "<mechanical_reduction>50<", "<mechanical_reduction>+-50<"))
    config = write(folder, "config.urdf", arm_ros2().replace(
        "<mechanical_reduction>50<", "<mechanical_reduction>-50<"))
    return robot, config


def test_numbers_are_read_as_the_named_distribution_reads_them(tmp_path):
    robot, config = _distro_pair(tmp_path)
    code, out, err = txtool(robot, "--candidate", config, "--duration", "1",
                            "--ros-distro", "jazzy")
    assert (code, err) == (0, "")
    assert "robot read by: ros2_control (jazzy) (--ros-distro jazzy)" in out
    assert "config read by: ros2_control (jazzy) (--ros-distro jazzy)" in out
    assert "PASS" in out
    code, out, err = txtool(robot, "--candidate", config, "--duration", "1",
                            "--ros-distro", "humble")
    assert (code, err) == (1, "")
    assert "robot read by: ros2_control (humble) (--ros-distro humble)" in out
    assert ("likely cause: joint 'shoulder': direction reversed and reduction off by a factor "
            "50 in the config's transmission 't_shoulder' (reduction -50, the robot's 1)") in out


def test_a_number_distributions_read_differently_is_read_as_jazzy_with_a_note(tmp_path):
    robot, config = _distro_pair(tmp_path)
    code, out, err = txtool(robot, "--candidate", config, "--duration", "1")
    assert (code, err) == (0, "")
    assert ("transmission 't_shoulder': ROS 2 distributions read its numbers differently "
            "(Humble with istringstream, Jazzy and later with from_chars) and nothing says "
            "which one reads the file: it is simulated as Jazzy and later read it "
            "(--ros-distro humble: as Humble reads it)") in out


def test_ros_distro_in_the_configuration_is_taken_as_validate_takes_it(tmp_path):
    robot, config = _distro_pair(tmp_path)
    (tmp_path / ".txtool.toml").write_text('ros-distro = "humble"\n', encoding="utf-8")
    code, out, err = txtool(robot, "--candidate", config, "--duration", "1")
    assert (code, err) == (1, "")
    assert f"robot read by: ros2_control (humble) (ros-distro humble in {tmp_path}" in out


def test_an_unknown_ros_distro_is_a_usage_error():
    code, _, err = txtool("robot.urdf", "--ros-distro", "groovy")
    assert code == 2
    assert "'groovy' is not one of" in err


def test_undecided_readers_are_said_to_be_so(tmp_path):
    ros2 = write(tmp_path, "arm.urdf", arm_ros2())
    code, out, err = txtool(ros2, "--duration", "1")
    assert (code, err) == (0, "")
    assert ("read by: ros2_control (<ros2_control> blocks); nothing rules ROS 1 out: "
            "ros_control may read the top-level transmissions\n") in out
    ros1 = write(tmp_path, "arm1.urdf", arm_ros1())
    code, out, err = txtool(ros1, "--duration", "1")
    assert (code, err) == (0, "")
    assert "read by: not known (each transmission as the loader of its dialect reads it)\n" in out


def test_a_loader_refusal_names_the_loader_that_refuses(tmp_path):
    no_reduction = arm_ros1().replace("<mechanicalReduction>50</mechanicalReduction>", "")
    ros2_two_joints = arm_ros2().replace(
        '<joint name="shoulder" role="joint1">',
        '<joint name="elbow" role="joint1"/><joint name="shoulder" role="joint1">')
    for name, text, why in (
            ("ros1.urdf", no_reduction,
             "ros_control's transmission loader refuses it: 'm_shoulder' reduction is missing"),
            ("ros2.urdf", ros2_two_joints,
             "ros2_control's transmission loader refuses it: a simple transmission takes one "
             "joint, found 'elbow', 'shoulder' (configure: joint names should be identical)")):
        robot = write(tmp_path, name, text)
        code, out, err = txtool(robot, "--duration", "1", "--format", "json")
        assert (code, err) == (0, "")
        assert json.loads(out)["runs"][0]["checked"]["skipped"] == {"t_shoulder": why}
