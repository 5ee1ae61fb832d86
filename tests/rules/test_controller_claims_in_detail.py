"""The interfaces each controller claims, in the cases the controller rules' tables leave out:
defaults a parameter does not override, a type named among a controller's own parameters,
a robot that only reads its joints, several robots that fit a file equally, and what a ROS 1
controller with a PID becomes in ROS 2."""

from __future__ import annotations

import pytest
from click.testing import CliRunner

import txtool
from tests.rules.test_tx5xx_controllers import FULL, findings, manager, ros1_robot, ros2_robot
from txtool.cli import cli


def test_gripper_controllers_state_interfaces_are_fixed_but_for_the_parallel_gripper(tmp_path):
    """gripper_controllers read position and velocity whatever is configured; only the
    parallel gripper takes ``state_interfaces``."""
    params = "g:\n  ros__parameters:\n    joint: j1\n    state_interfaces: [effort]\n"
    robot = ros2_robot(j1=("position", "position,velocity"))
    yaml = manager(("g", "position_controllers/GripperActionController"), params=params)
    assert findings(tmp_path, robot, yaml) == []
    yaml = manager(("g", "parallel_gripper_action_controller/GripperActionController"),
                   params=params)
    assert findings(tmp_path, robot, yaml) == [(4, 5, "TX502")]


def test_diff_drive_reads_wheel_positions_unless_told_otherwise(tmp_path):
    params = ("base:\n  ros__parameters:\n    left_wheel_names: [left]\n"
              "    right_wheel_names: [right]\n")
    yaml = manager(("base", "diff_drive_controller/DiffDriveController"), params=params)
    wheels = ros2_robot(left=("velocity", "position"), right=("velocity", "position"))
    assert findings(tmp_path, wheels, yaml) == []


BROADCASTER = """\
controller_manager:
  ros__parameters:
    update_rate: 100
jsb:
  ros__parameters:
    type: joint_state_broadcaster/JointStateBroadcaster
    joints: [j1, j9]
    interfaces: [position]
"""


def test_a_broadcaster_typed_among_its_own_parameters_is_a_controller(tmp_path):
    assert findings(tmp_path, ros2_robot(j1=FULL), BROADCASTER) == [(4, 1, "TX500")]


def test_a_controller_typed_twice_is_judged_once(tmp_path):
    yaml = manager(("jsb", "joint_state_broadcaster/JointStateBroadcaster"),
                   params=BROADCASTER.split("update_rate: 100\n", 1)[1])
    assert findings(tmp_path, ros2_robot(j1=FULL), yaml) == [(4, 5, "TX500")]


def test_a_robot_that_only_reads_its_joints_provides_state_interfaces(tmp_path):
    """A <ros2_control> block of sensors (state interfaces, no command) still says what the
    robot provides: a broadcaster of a joint it lacks is refused."""
    robot = ros2_robot(j1=("", "position"))
    assert findings(tmp_path, robot, BROADCASTER) == [(4, 1, "TX500")]
    assert findings(tmp_path, robot, BROADCASTER.replace("j1, j9", "j1")) == []


def test_of_robots_that_fit_a_file_equally_the_first_is_judged(tmp_path):
    (tmp_path / "package.xml").write_text('<package format="3"><name>p</name></package>')
    (tmp_path / "a.urdf").write_text(ros1_robot(j1="EffortJointInterface"))
    (tmp_path / "b.urdf").write_text(ros1_robot(j1="PositionJointInterface"))
    (tmp_path / "controllers.yaml").write_text(
        "arm:\n  type: effort_controllers/JointEffortController\n  joint: j1\n")
    assert [p.code for p in txtool.validate([str(tmp_path)]) if p.code >= "TX500"] == []
    (tmp_path / "controllers.yaml").write_text(
        "arm:\n  type: position_controllers/JointPositionController\n  joint: j1\n")
    assert [(p.line, p.code) for p in txtool.validate([str(tmp_path)])
            if p.code >= "TX500"] == [(1, "TX501")]


ROS1_ROBOT = """<robot name="r">
  <link name="a"/><link name="b"/>
  <joint name="j" type="revolute"><parent link="a"/><child link="b"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <transmission name="t"><type>transmission_interface/SimpleTransmission</type>
    <joint name="j"><hardwareInterface>hardware_interface/{interface}JointInterface</hardwareInterface>
    </joint><actuator name="m"><mechanicalReduction>1</mechanicalReduction></actuator>
  </transmission>
</robot>
"""


@pytest.mark.parametrize(("type_", "interface", "command", "state"), [
    ("effort_controllers/JointPositionController", "Effort", "effort", "position"),
    ("effort_controllers/JointGroupPositionController", "Effort", "effort", "position"),
    ("effort_controllers/JointVelocityController", "Effort", "effort", "velocity"),
    ("velocity_controllers/JointPositionController", "Velocity", "velocity", "position"),
])
def test_a_ros1_controller_with_a_pid_is_pid_controller_on_what_it_commands_and_reads(
        tmp_path, monkeypatch, type_, interface, command, state):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "robot.urdf").write_text(ROS1_ROBOT.format(interface=interface))
    key = "joints: [j]" if "Group" in type_ else "joint: j"
    (tmp_path / "controllers.yaml").write_text(f"hold:\n  type: {type_}\n  {key}\n")
    result = CliRunner().invoke(cli, ["convert", "robot.urdf", "--to", "ros2-p2",
                                      "--controllers", "controllers.yaml", "-o", "out.urdf"])
    assert (result.exit_code, result.stdout) == (0, "")
    assert result.stderr.splitlines()[-1] == (
        f"note: controllers.yaml:1:1: controller 'hold' ({type_}) is "
        f"pid_controller/PidController in ROS 2 (dof_names: [j], command_interface: {command}, "
        f"reference_and_state_interfaces: [{state}]); its pid gains go to pid_controller's "
        "gains; the converted <ros2_control> provides what it claims")


ALTERNATIVES = """\
position:
  type: position_controllers/JointGroupPositionController
  joints: [j1]
velocity:
  type: velocity_controllers/JointGroupVelocityController
  joints: [j1]
"""


def test_a_configured_severity_outranks_the_alternatives_warning(tmp_path):
    (tmp_path / "robot.urdf").write_text(ros1_robot(j1="PositionJointInterface"))
    (tmp_path / "c.yaml").write_text(ALTERNATIVES)
    (tmp_path / ".txtool.toml").write_text('[severity]\nTX501 = "error"\n')
    found = txtool.validate([str(tmp_path / "robot.urdf")], controllers=[str(tmp_path / "c.yaml")])
    assert [(p.line, p.code, p.severity) for p in found] == [(4, "TX501", "error")]


def test_a_ros1_interface_expression_does_not_soften_a_ros2_controllers_finding(tmp_path):
    """A robot with both generations' transmissions: the ROS 1 ``<hardwareInterface>`` a launch
    file's argument sets says nothing of its ``<ros2_control>`` block."""
    robot = ros2_robot(j1=("position", "position")).replace(
        '<robot name="r">', '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
        '<xacro:arg name="hw" default="hardware_interface/PositionJointInterface"/>'
        '<transmission name="t1"><type>transmission_interface/SimpleTransmission</type>'
        '<joint name="j1"><hardwareInterface>$(arg hw)</hardwareInterface></joint>'
        '<actuator name="m1"/></transmission>')
    (tmp_path / "robot.urdf.xacro").write_text(robot)
    yaml = manager(("c", "velocity_controllers/JointGroupVelocityController"),
                   params="c:\n  ros__parameters:\n    joints: [j1]\n")
    (tmp_path / "c.yaml").write_text(yaml)
    found = txtool.validate([str(tmp_path / "robot.urdf.xacro")],
                            controllers=[str(tmp_path / "c.yaml")])
    assert [(p.line, p.code, p.severity) for p in found if p.code >= "TX500"] == [
        (4, "TX501", "error")]


def test_a_walk_of_a_packages_robot_folder_finds_the_packages_controller_files(tmp_path):
    """The walk reaches urdf/ only; the robots it finds bring their package's config/ (and
    not that of a package nested in it)."""
    (tmp_path / "package.xml").write_text('<package format="3"><name>p</name></package>')
    for folder in ("urdf", "config", "nested/config"):
        (tmp_path / folder).mkdir(parents=True)
    (tmp_path / "nested" / "package.xml").write_text(
        '<package format="3"><name>n</name></package>')
    (tmp_path / "urdf" / "robot.urdf").write_text(ros1_robot(j1="EffortJointInterface"))
    wrong = "arm:\n  type: position_controllers/JointPositionController\n  joint: j1\n"
    (tmp_path / "config" / "arm.yaml").write_text(wrong)
    (tmp_path / "nested" / "config" / "arm.yaml").write_text(wrong)
    found = [p for p in txtool.validate([str(tmp_path / "urdf")]) if p.code >= "TX500"]
    assert [(p.path, p.line, p.code) for p in found] == [
        (str(tmp_path / "config" / "arm.yaml"), 1, "TX501")]


def test_a_controller_file_named_and_walked_is_judged_once(tmp_path, monkeypatch):
    """Named by its full path, found by the walk of '.': one file all the same."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "package.xml").write_text('<package format="3"><name>p</name></package>')
    (tmp_path / "robot.urdf").write_text(ros1_robot(j1="EffortJointInterface"))
    (tmp_path / "arm.yaml").write_text(
        "arm:\n  type: position_controllers/JointPositionController\n  joint: j1\n")
    found = txtool.validate(["."], controllers=[str(tmp_path / "arm.yaml")])
    assert [(p.line, p.code) for p in found if p.code >= "TX500"] == [(1, "TX501")]
