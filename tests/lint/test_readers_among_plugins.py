"""Which readers a robot's plugins make, where the package and the configuration say more:
a ROS 2 package's file is judged by its package whatever another file's ROS 1 plugin says, a
ROS 2 Gazebo plugin refuses a robot only where it is a reader, and the ROS 1 plugin is
reported as unloadable only where ROS 2 programs alone read the robot."""

from __future__ import annotations

from tests.lint.test_readers import (  # noqa: F401 - no_ros_environment: autouse
    COMPONENT,
    GAZEBO,
    ROBOT,
    findings,
    no_ros_environment,
    package,
    robot_file,
)

BLOCK = COMPONENT.format(hardware="mock_components/GenericSystem", inner="")
TRANSMISSION = ('    <transmission name="t"><plugin>transmission_interface/SimpleTransmission'
                '</plugin><joint name="joint1" role="joint1"/></transmission>\n')


def test_a_ros2_packages_file_is_not_read_by_another_files_ros1_plugin(validate, tmp_path):
    folder = package(tmp_path, "arm_description", "ament_cmake")
    (folder / "urdf" / "arm.gazebo.xacro").write_text(
        '<robot xmlns:xacro="http://ros.org/wiki/xacro"><xacro:macro name="sim">'
        + GAZEBO.format(filename="libgazebo_ros_control.so") + "</xacro:macro></robot>\n")
    path = robot_file(folder, COMPONENT.format(hardware="mock_components/GenericSystem",
                                               inner=TRANSMISSION))
    code, found, report = findings(validate, str(path))
    assert (code, found) == (0, [])
    assert report["readers"][0]["readers"] == ["ros2_control"]
    assert report["readers"][0]["because"] == ["package.xml: ament_cmake"]


def test_a_ros2_gazebo_plugin_refuses_the_robot_only_where_it_is_a_reader(validate, tmp_path):
    path = tmp_path / "arm.urdf"
    path.write_text(ROBOT.format(body=GAZEBO.format(filename="libgazebo_ros2_control.so")))
    code, found, _ = findings(validate, str(path))
    assert (code, found) == (1, [(5, 11, "TX007", "error")])
    (tmp_path / ".txtool.toml").write_text('readers = ["ros2_control"]\n')
    code, found, _ = findings(validate, str(path))
    assert (code, found) == (0, [(1, 1, "TX006", "info")])  # (no transmission in it)


def test_a_ros1_plugin_beside_a_ros2_one_is_no_unloadable_plugin(validate, tmp_path):
    """ROS 1 programs read the robot too (its gazebo_ros_control plugin is one): TX306 is for
    a robot that only ROS 2 programs read."""
    body = BLOCK + GAZEBO.format(filename="libgazebo_ros_control.so") + GAZEBO.format(
        filename="libgazebo_ros2_control.so")
    path = tmp_path / "arm.urdf"
    path.write_text(ROBOT.format(body=body))
    code, found, _ = findings(validate, str(path))
    assert (code, found) == (0, [(1, 1, "TX006", "info")])


def test_a_xacro_file_read_as_written_says_nothing_of_its_ros1_plugin(tmp_path):
    """Read without expansion, the plugin may sit in a macro or branch that never writes it:
    TX306 waits for the expanded robot."""
    from tests.rules.test_tx306_ros1_gazebo_plugin import AMENT, robot_in, validate

    path = robot_in(tmp_path, AMENT)
    xacro = path.with_name("arm.urdf.xacro")
    xacro.write_text(path.read_text().replace(
        '<robot name="arm">', '<robot name="arm" xmlns:xacro="http://www.ros.org/wiki/xacro">'))
    path.unlink()
    assert ("TX306", "warning") in {(c, s) for *_, c, s in validate(xacro)[1]}
    assert "TX306" not in {c for *_, c, _ in validate(xacro, "--no-xacro")[1]}
