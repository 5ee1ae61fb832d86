"""``simulate --controllers``: the joints a controller configuration commands are driven, the
others held; its effort controllers' gains are used, and a controller its manager refuses fails
the run as validate reports it.

The real configuration is gazebo_ros_demos' ``rrbot_control.yaml`` (ros-simulation/
gazebo_ros_demos @64e9200, BSD) beside the workspace's ``rrbot_description`` (../shared); the
others are inline, on the demo robot's ROS 2 conversion. Gains as the controllers read them:
effort_controllers/JointPositionController's ``pid`` (ros_controllers
effort_controllers/src/joint_position_controller.cpp:208, effort from the position and speed
errors), joint_trajectory_controller's ``gains`` (ros2_controllers joint_trajectory_controller.cpp
:439, with ``ff_velocity_scale``), pid_controller's ``gains`` (pid_controller.cpp:566-596).
"""

from __future__ import annotations

import json
from pathlib import Path

import jsonschema
import numpy as np
import pytest
from click.testing import CliRunner

import txtool
from tests.rules.test_tx5xx_real_packages import RRBOT_CONTROL, rrbot_workspace
from tests.simulate.robots import write
from txtool.cli import cli

ROOT = Path(__file__).resolve().parents[2]
SCHEMA = json.loads((ROOT / "schemas" / "simulate.schema.json").read_text(encoding="utf-8"))
DEMO_ROS2 = ROOT / "fixtures" / "demo_robot.ros2-p2.urdf"

# The demo arm's shoulder and wrist pitch through a ROS 2 trajectory controller commanding
# efforts; nothing commands the wrist roll. Gains near the default stiffness (M_ii of the
# shoulder 0.0025 kg·m², of the wrist pitch about 0.01 kg·m²).
JTC_EFFORT = """\
controller_manager:
  ros__parameters:
    update_rate: 1000
    arm_controller:
      type: joint_trajectory_controller/JointTrajectoryController
    joint_state_broadcaster:
      type: joint_state_broadcaster/JointStateBroadcaster
arm_controller:
  ros__parameters:
    joints: [shoulder, wrist_pitch]
    command_interfaces: [effort]
    state_interfaces: [position, velocity]
    gains:
      shoulder: {p: 1.0, d: 0.1, ff_velocity_scale: 1.0}
      wrist_pitch: {p: 4.0, d: 0.4}
"""


def simulate(*args: str) -> tuple[int, str, str]:
    result = CliRunner().invoke(cli, ["simulate", *args], catch_exceptions=False)
    return result.exit_code, result.stdout, result.stderr


def run_json(*args: str) -> tuple[int, dict]:
    code, out, err = simulate(*args, "--format", "json")
    assert err == "", err
    doc = json.loads(out)
    jsonschema.validate(doc, SCHEMA)
    return code, doc["runs"][0]


@pytest.fixture
def rrbot(tmp_path):
    """(robot, its controllers file, --pkg-dir) as gazebo_ros_demos keeps them."""
    src = rrbot_workspace(tmp_path, RRBOT_CONTROL)
    return (str(src / "rrbot_description" / "urdf" / "rrbot.xacro"),
            str(src / "rrbot_control" / "config" / "rrbot_control.yaml"), str(src))


def test_rrbot_is_driven_by_its_own_controllers_with_their_pid_gains(rrbot):
    robot, control, src = rrbot
    code, run = run_json(robot, "--pkg-dir", src, "--controllers", control, "--duration", "0.5")
    assert (code, run["verdict"]) == (0, "pass")
    assert run["controllers"] == {
        joint: {"controller": f"{joint}_position_controller",
                "type": "effort_controllers/JointPositionController",
                "command_interfaces": ["effort"], "file": control, "line": line,
                "units": {"line": "1"}}
        for joint, line in (("joint1", 8), ("joint2", 12))}
    for joint, line in (("joint1", 11), ("joint2", 15)):
        gains = run["gains"][joint]
        source = gains["source"]
        assert (source["file"], source["line"], source["format"]) == (
            control, line, "effort_controllers/JointPositionController (effort gains)")
        # The PID's N·m/rad over the joint's inertia: the same stiffness about the start.
        inertia = source["divided_by_inertia"]
        assert gains["kp"] * inertia == pytest.approx(100.0)
        assert gains["kd"] * inertia == pytest.approx(10.0)


def test_a_controller_its_manager_refuses_fails_the_run_with_validates_findings(rrbot, capsys):
    robot, control, src = rrbot
    Path(control).write_text(RRBOT_CONTROL.replace("effort_controllers/", "position_controllers/"))
    found = [p for p in txtool.validate([robot], controllers=[control], pkg_dirs=[src])
             if p.code.startswith("TX5") and p.severity == "error"]
    assert [(p.line, p.code) for p in found] == [(8, "TX501"), (12, "TX501")]

    code, out, err = simulate(robot, "--pkg-dir", src, "--controllers", control)
    assert (code, err) == (1, "")
    assert "not simulated" in out
    assert f"FAIL: {found[0]} (and 1 more)" in out and f"  - {found[1]}" in out
    code, run = run_json(robot, "--pkg-dir", src, "--controllers", control)
    assert (code, run["verdict"], run["steps"]) == (1, "fail", 0)
    assert run["causes"] == [{"kind": "controller_refused", "text": str(p)} for p in found]


def test_a_joint_no_controller_commands_is_held(tmp_path):
    control = write(tmp_path, "controllers.yaml", JTC_EFFORT)
    [run] = txtool.simulate(DEMO_ROS2, controllers=control, duration=0.5, keep_series=True)
    assert run.verdict == "pass"
    assert run.controllers["wrist_roll"] is None
    assert run.coverage.still == ("wrist_roll",)  # its maps checked at one pose only
    assert run.controllers["shoulder"].controller == "arm_controller"
    series = run.series
    roll = series.joints.index("wrist_roll")
    assert np.all(series.q_ref[:, roll] == series.q_ref[0, roll])
    assert np.ptp(series.q_ref[:, series.joints.index("shoulder")]) > 0
    assert "held at the middle of their range: no controller commands them, so their drive " \
           "keeps them where they are: 'wrist_roll'" in run.notes


def test_trajectory_controller_effort_gains_are_used_and_its_feed_forward_reported(tmp_path):
    control = write(tmp_path, "controllers.yaml", JTC_EFFORT)
    code, run = run_json(str(DEMO_ROS2), "--controllers", control, "--duration", "0.5")
    assert (code, run["verdict"]) == (0, "pass")
    shoulder = run["gains"]["shoulder"]
    assert shoulder["source"]["line"] == 14
    assert shoulder["source"]["given"]["p"] == 1.0
    assert shoulder["kp"] * shoulder["source"]["divided_by_inertia"] == pytest.approx(1.0)
    assert run["gains"]["wrist_roll"]["source"] == {
        "default": "bandwidth", "bandwidth": 20.0, "units": {"bandwidth": "rad/s"}}
    assert any(note.startswith(f"{control}:14: arm_controller.ros__parameters.gains.shoulder."
                               "ff_velocity_scale: 1.0 not used: joint_trajectory_controller "
                               "adds ff_velocity_scale times the reference speed")
               for note in run["notes"])


def test_a_position_interface_is_the_drives_loop_and_its_gains_are_not_used(tmp_path):
    robot = write(tmp_path, "arm.urdf", DEMO_ROS2.read_text().replace(
        '<command_interface name="effort"/>', '<command_interface name="position"/>'))
    control = write(tmp_path, "controllers.yaml", JTC_EFFORT.replace("[effort]", "[position]"))
    code, run = run_json(robot, "--controllers", control, "--duration", "0.5")
    assert (code, run["verdict"]) == (0, "pass")
    assert run["controllers"]["shoulder"]["command_interfaces"] == ["position"]
    assert all(g["source"].get("default") == "bandwidth" for g in run["gains"].values())
    assert f"{control}:9: gains of 'arm_controller' not used: its command interface is " \
           "position, so its PID output is not a joint effort" in run["notes"]
    assert "joints 'shoulder', 'wrist_pitch' take position commands from 'arm_controller': " \
           "the drive's own servo loop tracks them, which simulate does not model; its " \
           "computed-torque law stands in for that loop" in run["notes"]


def test_params_override_the_controllers_gains(tmp_path):
    control = write(tmp_path, "controllers.yaml", JTC_EFFORT)
    tuned = write(tmp_path, "tuned.toml", "[joints.shoulder]\nkp = 300.0\nkd = 35.0\n")
    code, run = run_json(str(DEMO_ROS2), "--controllers", control, "--params", tuned,
                         "--duration", "0.5")
    assert code == 0
    assert (run["gains"]["shoulder"]["kp"], run["gains"]["shoulder"]["source"]["format"]) == (
        300.0, "toml")
    assert run["gains"]["wrist_pitch"]["source"]["file"] == control


PID_CONTROLLER = """\
controller_manager:
  ros__parameters:
    pid:
      type: pid_controller/PidController
pid:
  ros__parameters:
    dof_names: [shoulder, wrist_pitch, wrist_roll]
    command_interface: effort
    reference_and_state_interfaces: [velocity]
    gains:
      shoulder: {p: 1.0, d: 0.1}
"""


def test_pid_controller_on_the_position_error_drives_its_joints_with_its_gains(tmp_path):
    control = write(tmp_path, "pid.yaml", PID_CONTROLLER.replace("[velocity]",
                                                                 "[position, velocity]"))
    code, run = run_json(str(DEMO_ROS2), "--controllers", control, "--duration", "0.5")
    assert code == 0
    assert {d["controller"] for d in run["controllers"].values()} == {"pid"}
    shoulder = run["gains"]["shoulder"]
    assert (shoulder["source"]["file"], shoulder["source"]["line"]) == (control, 11)
    assert shoulder["kp"] * shoulder["source"]["divided_by_inertia"] == pytest.approx(1.0)


def test_pid_controller_on_a_velocity_error_drives_its_joints_without_its_gains(tmp_path):
    control = write(tmp_path, "pid.yaml", PID_CONTROLLER)
    code, run = run_json(str(DEMO_ROS2), "--controllers", control, "--duration", "0.5")
    assert code == 0
    assert {d["controller"] for d in run["controllers"].values()} == {"pid"}
    assert run["gains"]["shoulder"]["source"]["default"] == "bandwidth"
    assert f"{control}:6: gains of 'pid' not used: its PID acts on the velocity error " \
           "(reference_and_state_interfaces), not the position error" in run["notes"]


def test_the_first_of_two_controllers_of_a_joint_drives_it(rrbot):
    robot, control, src = rrbot
    Path(control).write_text(RRBOT_CONTROL + """\
  joint1_effort_controller:
    type: effort_controllers/JointEffortController
    joint: joint1
""")
    code, run = run_json(robot, "--pkg-dir", src, "--controllers", control, "--duration", "0.5")
    assert code == 0
    assert run["controllers"]["joint1"]["controller"] == "joint1_position_controller"
    assert f"{control}:16: 'joint1_effort_controller' also commands joint 'joint1': simulated " \
           f"as 'joint1_position_controller' ({control}:8) drives it (the manager refuses " \
           "the second of them activated)" in run["notes"]


def test_a_configuration_commanding_no_joint_checks_nothing(tmp_path):
    control = write(tmp_path, "broadcaster.yaml", JTC_EFFORT.split("arm_controller:\n  ros")[0]
                    .replace("    arm_controller:\n      type: joint_trajectory_controller/"
                             "JointTrajectoryController\n", ""))
    code, out, err = simulate(str(DEMO_ROS2), "--controllers", control)
    assert (code, err) == (3, "")
    assert out.splitlines()[-1] == f"INCONCLUSIVE: nothing checked: no controller of {control} " \
                                   "commands a moving joint of the robot"


def test_a_controller_type_whose_interfaces_are_not_known_drives_nothing_said_so(tmp_path):
    control = write(tmp_path, "ct.yaml", """\
ct:
  type: computed_torque_controllers/PositionJointController
  joints:
    shoulder: {p: 400, d: 40}
""")
    code, out, err = simulate(str(ROOT / "fixtures" / "demo_robot.urdf"), "--controllers",
                              control)
    assert (code, err) == (3, "")
    assert f"note: {control}:1: which joints 'ct' (computed_torque_controllers/" \
           "PositionJointController) commands is not known (txtool does not work out the " \
           "interfaces of its type): they are not counted as driven (--params FILE takes its " \
           "gains)" in out.splitlines()


def test_a_file_without_controllers_is_one_line_and_exit_2(tmp_path):
    control = write(tmp_path, "empty.yaml", "robot_description: {}\n")
    code, out, err = simulate(str(DEMO_ROS2), "--controllers", control)
    assert (code, out) == (2, "")
    assert err == (f"txtool: {control}: no controller in it (a controller is a name holding "
                   "a 'type', under a ROS 2 node's ros__parameters or a ROS 1 namespace)\n")


def test_the_text_report_names_each_joints_controller(tmp_path):
    control = write(tmp_path, "controllers.yaml", JTC_EFFORT)
    code, out, err = simulate(str(DEMO_ROS2), "--controllers", control, "--duration", "0.5")
    assert (code, err) == (0, "")
    rows = [" ".join(line.replace("│", " ").split()) for line in out.splitlines()]
    assert "controllers (--controllers)" in rows
    assert "shoulder arm_controller effort controllers.yaml:4" in rows
    assert "wrist_roll none: held - -" in rows


def test_a_trajectory_moving_a_joint_no_controller_commands_holds_it_at_its_start(tmp_path):
    control = write(tmp_path, "controllers.yaml", JTC_EFFORT)
    csv = write(tmp_path, "motion.csv", "time,shoulder,wrist_roll\n0,0,0.2\n0.5,0.05,0.4\n")
    [run] = txtool.simulate(DEMO_ROS2, controllers=control, trajectory=csv, keep_series=True)
    roll = run.series.joints.index("wrist_roll")
    assert np.all(run.series.q_ref[:, roll] == 0.2)
    assert "held at the start of the trajectory: no controller commands them, so their drive " \
           "keeps them where they are: 'wrist_roll'" in run.notes
