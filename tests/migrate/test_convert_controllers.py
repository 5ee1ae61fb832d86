"""``txtool convert ROBOT --to ros2-p2 --controllers ROS1.yaml``: what each ROS 1 controller
is in ROS 2, and whether the converted ``<ros2_control>`` provides what it claims there."""

from __future__ import annotations

from click.testing import CliRunner

from txtool.cli import cli

ROBOT = """<robot name="r">
  <link name="a"/><link name="b"/>
  <joint name="j" type="revolute"><parent link="a"/><child link="b"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <transmission name="t"><type>transmission_interface/SimpleTransmission</type>
    <joint name="j"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
    </joint><actuator name="m"><mechanicalReduction>1</mechanicalReduction></actuator>
  </transmission>
</robot>
"""
CONTROLLERS = """\
joint_state_controller:
  type: joint_state_controller/JointStateController
arm:
  type: effort_controllers/JointTrajectoryController
  joints: [j]
hold:
  type: position_controllers/JointPositionController
  joint: j
vendor:
  type: acme_controllers/MagicController
"""


def convert(tmp_path, *args: str):
    (tmp_path / "robot.urdf").write_text(ROBOT)
    (tmp_path / "controllers.yaml").write_text(CONTROLLERS)
    result = CliRunner().invoke(cli, ["convert", "robot.urdf", *args], catch_exceptions=False)
    return result.exit_code, result.stdout, result.stderr


def test_each_controller_in_ros2_against_the_converted_robot(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    code, out, err = convert(tmp_path, "--to", "ros2-p2", "--hardware-plugin", "my/Hardware",
                             "--controllers", "controllers.yaml", "-o", "robot2.urdf")
    assert (code, out) == (0, "")
    assert err.splitlines() == [
        "note: controllers.yaml:1:1: controller 'joint_state_controller' "
        "(joint_state_controller/JointStateController) is "
        "joint_state_broadcaster/JointStateBroadcaster in ROS 2; the converted <ros2_control> "
        "provides what it claims",
        "note: controllers.yaml:3:1: controller 'arm' (effort_controllers/"
        "JointTrajectoryController) is joint_trajectory_controller/JointTrajectoryController in "
        "ROS 2 (joints: [j], command_interfaces: [effort], state_interfaces: [position, "
        "velocity]); the converted <ros2_control> provides what it claims",
        "note: controllers.yaml:9:1: controller 'vendor' (acme_controllers/MagicController): no "
        "ros2_controllers type does its work; port it",
        "warning: controllers.yaml:6:1: controller 'hold' (position_controllers/"
        "JointPositionController) is forward_command_controller/ForwardCommandController in "
        "ROS 2 (joints: [j], interface_name: position); the converted <ros2_control> lacks "
        "j/position (command)",
    ]
    assert b"<ros2_control" in (tmp_path / "robot2.urdf").read_bytes()


def test_controllers_are_refused_before_anything_is_written(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "ros2.yaml").write_text(
        "controller_manager:\n  ros__parameters:\n    jsb:\n"
        "      type: joint_state_broadcaster/JointStateBroadcaster\n")
    code, out, err = convert(tmp_path, "--to", "ros2-p2", "--controllers", "ros2.yaml",
                             "-o", "robot2.urdf")
    assert (code, out) == (2, "")
    assert err == ("txtool: ros2.yaml: no ROS 1 controller configuration (a controller "
                   "namespace with a type)\n")
    assert not (tmp_path / "robot2.urdf").exists()
    code, _, err = convert(tmp_path, "--to", "ros1", "--controllers", "controllers.yaml")
    assert (code, err) == (2, "txtool: --controllers applies to --to ros2-p1 and ros2-p2\n")
