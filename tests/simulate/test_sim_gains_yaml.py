"""Gains from the YAML files of ROS controllers: the gains a run uses, in its JSON, with sources.

Layouts as the controllers read them: computed_torque_controllers ``<ns>/joints/<joint>/{p,i,d}``
(yoshito-n-students/computed_torque_controllers README.md, "Parameters"); joint_trajectory_
controller and pid_controller ``gains/<joint>/{p,i,d,i_clamp_max,i_clamp_min}`` (ros-controls/
ros2_controllers joint_trajectory_controller/src/joint_trajectory_controller_parameters.yaml,
pid_controller/src/pid_controller.yaml); ROS 1 control_toolbox ``Pid::init`` requires ``p`` and
defaults ``i_clamp`` to 0 (ros-controls/control_toolbox src/pid.cpp, melodic/noetic).
"""

from __future__ import annotations

import json

import pytest
from click.testing import CliRunner

from tests.corpus import corpus_file
from tests.simulate.robots import arm_ros1, pendulum, write
from txtool.cli import cli

MASS, LENGTH, REDUCTION, ROTOR = 2.0, 0.5, 10.0, 1e-4
# Joint inertia of the pendulum: the point mass, its 1e-9 own inertia, the reflected rotor.
M_II = MASS * LENGTH**2 + 1e-9 + ROTOR * REDUCTION**2


def simulate(*args: str) -> tuple[int, str, str]:
    result = CliRunner().invoke(cli, ["simulate", *args], catch_exceptions=False)
    return result.exit_code, result.stdout, result.stderr


@pytest.fixture
def swing(tmp_path):
    robot = write(tmp_path, "pendulum.urdf", pendulum(MASS, LENGTH, REDUCTION))
    rotor = write(tmp_path, "motors.toml", f"[actuators.m_swing]\nrotor_inertia = {ROTOR}\n")
    return robot, rotor


def gains_of(tmp_path, robot: str, *params: str, duration: str = "0.2") -> dict:
    args = [robot, "--format", "json", "--duration", duration]
    for path in params:
        args += ["--params", path]
    code, out, err = simulate(*args)
    assert err == "" and code in (0, 1), err
    return json.loads(out)["runs"][0]


COMPUTED_TORQUE = """\
computed_torque_controller:
  type: computed_torque_controllers/PositionJointController
  joints:
    swing:
      p: 900.
      d: 60.
      i: 2.
"""


def test_computed_torque_gains_are_accelerations_used_as_given(tmp_path, swing):
    robot, _ = swing
    yaml_path = write(tmp_path, "ct.yaml", COMPUTED_TORQUE)
    doc = gains_of(tmp_path, robot, yaml_path)
    g = doc["gains"]["swing"]
    assert (g["kp"], g["kd"], g["ki"]) == (900.0, 60.0, 2.0)
    assert g["i_clamp"] == 0.0  # control_toolbox's default i_clamp: the I-term stays 0
    assert g["units"] == {"kp": "1/s²", "kd": "1/s", "ki": "1/s³", "i_clamp": "rad/s²"}
    assert g["source"] == {
        "file": yaml_path, "line": 4, "key": "computed_torque_controller.joints.swing",
        "format": "computed_torque_controllers", "units": {"line": "1"},
        "given": {"p": 900.0, "d": 60.0, "i": 2.0,
                  "units": {"p": "1/s²", "d": "1/s", "i": "1/s³"}}}
    assert any("ct.yaml:4: computed_torque_controller.joints.swing: i_clamp is 0" in note
               for note in doc["notes"])


ROS2_JTC = """\
controller_manager:
  ros__parameters:
    update_rate: 1000
    arm_controller:
      type: joint_trajectory_controller/JointTrajectoryController

arm_controller:
  ros__parameters:
    joints: [swing]
    command_interfaces: [effort]
    state_interfaces: [position, velocity]
    gains:
      swing: {p: 200.0, d: 20.0, i: 5.0, i_clamp_max: 3.0, i_clamp_min: -3.0,
              ff_velocity_scale: 0.0}
"""


def test_ros2_effort_gains_are_divided_by_the_joint_inertia(tmp_path, swing):
    robot, rotor = swing
    yaml_path = write(tmp_path, "controllers.yaml", ROS2_JTC)
    doc = gains_of(tmp_path, robot, rotor, yaml_path)
    g = doc["gains"]["swing"]
    assert g["kp"] == pytest.approx(200.0 / M_II, rel=1e-9)
    assert g["kd"] == pytest.approx(20.0 / M_II, rel=1e-9)
    assert g["ki"] == pytest.approx(5.0 / M_II, rel=1e-9)
    assert g["i_clamp"] == pytest.approx(3.0 / M_II, rel=1e-9)
    source = g["source"]
    assert source["key"] == "arm_controller.ros__parameters.gains.swing"
    assert source["line"] == 13 and source["file"] == yaml_path
    assert source["format"] == "joint_trajectory_controller (effort gains)"
    assert source["divided_by_inertia"] == pytest.approx(M_II, rel=1e-9)
    assert source["units"] == {"line": "1", "divided_by_inertia": "kg·m²"}
    assert source["given"] == {"p": 200.0, "d": 20.0, "i": 5.0, "i_clamp_max": 3.0,
                               "i_clamp_min": 3.0, "units": {
                                   "p": "N·m/rad", "d": "N·m·s/rad", "i": "N·m/(rad·s)",
                                   "i_clamp_max": "N·m", "i_clamp_min": "N·m"}}


def test_pid_controller_and_the_text_report(tmp_path, swing):
    robot, _ = swing
    text = ("pid_controller:\n  ros__parameters:\n    dof_names: [swing]\n"
            "    command_interface: effort\n    reference_and_state_interfaces: [position]\n"
            "    gains:\n      swing: {p: 50.0, d: 5.0}\n")
    yaml_path = write(tmp_path, "pid.yaml", text)
    doc = gains_of(tmp_path, robot, yaml_path)
    g = doc["gains"]["swing"]
    m = MASS * LENGTH**2 + 1e-9
    assert g["kp"] == pytest.approx(50.0 / m) and g["kd"] == pytest.approx(5.0 / m)
    assert g["ki"] == 0.0 and g["i_clamp"] is None  # ROS 2: no clamp unless given
    assert g["source"]["format"] == "pid_controller (effort gains)"
    code, out, err = simulate(robot, "--params", yaml_path, "--duration", "0.2")
    assert err == "" and code in (0, 1)
    assert "gains (acceleration per error" in out and "pid.yaml:7" in out
    assert f"{m:.3g}" in out  # the M_ii the effort gains were divided by


def test_ros1_effort_controllers_and_joint_position_controller(tmp_path):
    robot = write(tmp_path, "arm.urdf", arm_ros1())
    text = """\
arm:
  trajectory_controller:
    type: effort_controllers/JointTrajectoryController
    joints: [shoulder, elbow]
    gains:
      shoulder: {p: 100, d: 10, i: 1, i_clamp: 1}
      elbow: {p: 80, d: 8}
  wrist_controller:
    type: effort_controllers/JointPositionController
    joint: wrist
    pid: {p: 20, d: 1}
"""
    yaml_path = write(tmp_path, "ros1.yaml", text)
    doc = gains_of(tmp_path, robot, yaml_path)
    gains = doc["gains"]
    assert gains["shoulder"]["source"]["key"] == "arm.trajectory_controller.gains.shoulder"
    assert gains["shoulder"]["source"]["line"] == 6
    assert gains["wrist"]["source"]["key"] == "arm.wrist_controller.pid"
    assert gains["wrist"]["source"]["format"] == \
        "effort_controllers/JointPositionController (effort gains)"
    for joint in ("shoulder", "elbow", "wrist"):
        m = gains[joint]["source"]["divided_by_inertia"]
        given = gains[joint]["source"]["given"]
        assert gains[joint]["kp"] == pytest.approx(given["p"] / m)
        assert gains[joint]["kd"] == pytest.approx(given["d"] / m)


def test_velocity_controllers_are_not_used_and_said_so(tmp_path, swing):
    robot, _ = swing
    velocity = ("vel_controller:\n  ros__parameters:\n    command_interfaces: [velocity]\n"
                "    gains:\n      swing: {p: 5.0}\n")
    both = velocity + COMPUTED_TORQUE
    doc = gains_of(tmp_path, robot, write(tmp_path, "both.yaml", both))
    assert doc["gains"]["swing"]["source"]["format"] == "computed_torque_controllers"
    assert any("gains of 'vel_controller' not used: its command interface is velocity" in n
               for n in doc["notes"])
    only = write(tmp_path, "velocity.yaml", velocity)
    code, out, err = simulate(robot, "--params", only)
    assert (code, out) == (2, "")
    assert err == (f"txtool: {only}: no gains of an effort or computed-torque controller: "
                   "'vel_controller' its command interface is velocity, so its PID output is "
                   "not a joint effort\n")


def test_toml_gains_report_their_source_and_defaults(tmp_path, swing):
    robot, _ = swing
    toml_path = write(tmp_path, "p.toml", "[joints.swing]\nkp = 100.0\n")
    g = gains_of(tmp_path, robot, toml_path)["gains"]["swing"]
    assert (g["kp"], g["kd"]) == (100.0, 40.0)  # kd from --bandwidth 20
    assert g["source"] == {"file": toml_path, "line": 1, "key": "joints.swing",
                           "format": "toml", "given": {"kp": 100.0, "units": {"kp": "1/s²"}},
                           "bandwidth": 20.0, "units": {"line": "1", "bandwidth": "rad/s"}}
    g = gains_of(tmp_path, robot)["gains"]["swing"]
    assert g["source"] == {"default": "bandwidth", "bandwidth": 20.0,
                           "units": {"bandwidth": "rad/s"}}
    assert (g["kp"], g["kd"], g["ki"], g["i_clamp"]) == (400.0, 40.0, 0.0, None)


def test_a_later_file_replaces_an_earlier_joint(tmp_path, swing):
    robot, _ = swing
    toml_path = write(tmp_path, "p.toml", "[joints.swing]\nkp = 100.0\n")
    yaml_path = write(tmp_path, "ct.yaml", COMPUTED_TORQUE)
    g = gains_of(tmp_path, robot, toml_path, yaml_path)["gains"]["swing"]
    assert g["kp"] == 900.0 and g["source"]["file"] == yaml_path
    g = gains_of(tmp_path, robot, yaml_path, toml_path)["gains"]["swing"]
    assert g["kp"] == 100.0 and g["source"]["file"] == toml_path


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("ctrl:\n  joints:\n    swing: {p: 1, d: [2]\n",
         "bad.yaml:4: invalid YAML: expected ',' or '}', but got '<stream end>' (while "
         "parsing a flow mapping from line 3)"),
        ("ctrl:\n  joints:\n    swing:\n      p: 1\n      kd: 2\n",
         "bad.yaml:5: ctrl.joints.swing.kd: unknown key (expected p, i, d, i_clamp, "
         "i_clamp_max, i_clamp_min)"),
        ("ctrl:\n  joints:\n    swing: {p: -1}\n",
         "bad.yaml:3: ctrl.joints.swing.p: must be finite and zero or positive, got -1"),
        ("ctrl:\n  joints:\n    swing: {p: high}\n",
         "bad.yaml:3: ctrl.joints.swing.p: expected a number, got 'high'"),
        ("ctrl:\n  joints:\n    swing: {d: 2}\n",
         "bad.yaml:3: ctrl.joints.swing: no p gain: control_toolbox's Pid refuses to start "
         "without one"),
        ("ctrl:\n  joints:\n    knee: {p: 1}\n",
         "bad.yaml:3: ctrl.joints.knee: no moving joint 'knee' in"),
        ("- a\n- b\n", "bad.yaml: expected a mapping of controllers, got list"),
        ("ctrl: {type: x}\n", "bad.yaml: no controller gains found"),
        ("a: !!python/object:os.system {}\n", "bad.yaml:1: invalid YAML: "),
        ("a: 1\n---\nb: 2\n", "bad.yaml:2: invalid YAML: but found another document (expected a single "
                           "document in the stream from line 1)"),
    ],
)
def test_bad_yaml_is_one_line_exit_2(tmp_path, swing, text, message):
    robot, _ = swing
    path = write(tmp_path, "bad.yaml", text)
    code, out, err = simulate(robot, "--params", path)
    assert (code, out) == (2, "")
    assert err.count("\n") == 1 and err.startswith("txtool: ") and message in err, err


# The layout of IFL-CAMP/iiwa_stack iiwa_control/config/iiwa_control.yaml (ROS 1): alternative
# controllers for the same joints in one file; two joints and the gains abridged.
IIWA_CONTROL = """\
  joint_state_controller:
    type: joint_state_controller/JointStateController
    publish_rate: 50
  EffortJointInterface_J1_controller:
    type: effort_controllers/JointPositionController
    joint: iiwa_joint_1
    pid: {p: 800.0, i: 0, d: 80.0, i_clamp_min: -10000, i_clamp_max: 10000}
  EffortJointInterface_trajectory_controller:
    type: effort_controllers/JointTrajectoryController
    joints: [iiwa_joint_1, iiwa_joint_7]
    gains:
      iiwa_joint_1: {p: 500,  d: 30, i: 15, i_clamp: 30}
      iiwa_joint_7: {p: 17,  d: 2, i: 2.5, i_clamp: 10}
    constraints:
      goal_time: 0.5
  VelocityJointInterface_trajectory_controller:
    type: velocity_controllers/JointTrajectoryController
    joints: [iiwa_joint_1]
    gains:
      iiwa_joint_1: {p: 500,  d: 30, i: 15, i_clamp: 30}
"""


def test_a_file_of_alternative_controllers_and_picking_one(tmp_path):
    robot = str(corpus_file("iiwa_stack__iiwa14.urdf"))
    yaml_path = write(tmp_path, "iiwa_control.yaml", IIWA_CONTROL)
    doc = gains_of(tmp_path, robot, yaml_path, duration="0.1")
    gains, notes = doc["gains"], doc["notes"]
    assert gains["iiwa_joint_1"]["source"]["key"] == "EffortJointInterface_J1_controller.pid"
    assert gains["iiwa_joint_7"]["source"]["line"] == 13
    assert gains["iiwa_joint_4"]["source"] == {"default": "bandwidth", "bandwidth": 20.0,
                                               "units": {"bandwidth": "rad/s"}}
    assert f"{yaml_path}:8: gains of 'EffortJointInterface_trajectory_controller' for " \
           "iiwa_joint_1 not used: an earlier controller in the file gives them (pick one " \
           "with iiwa_control.yaml#EffortJointInterface_trajectory_controller)" in notes
    assert f"{yaml_path}:16: gains of 'VelocityJointInterface_trajectory_controller' not " \
           "used: a velocity_controllers/JointTrajectoryController does not output a joint " \
           "effort" in notes
    picked = gains_of(tmp_path, robot, yaml_path + "#EffortJointInterface_trajectory_controller",
                      duration="0.1")
    assert picked["gains"]["iiwa_joint_1"]["source"]["line"] == 12
    code, out, err = simulate(robot, "--params", yaml_path + "#J9")
    assert (code, out) == (2, "")
    assert err == (f"txtool: {yaml_path}: no controller 'J9' with gains (there are: "
                   "EffortJointInterface_J1_controller, EffortJointInterface_trajectory_"
                   "controller, VelocityJointInterface_trajectory_controller)\n")


def test_gains_beyond_the_undamped_bound_that_damping_steadies_are_named(tmp_path):
    """Joint 7 of the iiwa is light: its effort gains d = 2 N·m·s/rad over M_ii = 0.001 kg·m²
    give kd = 2000 1/s, and kd·dt = 2 at 1 kHz: an undamped joint's loop would oscillate and
    grow. Its URDF damping (0.5 N·m·s/rad, 511-555 1/s over its effective inertia) keeps the
    sampled loop stable, so it tracks, and the note says that instead of "cannot be stable"."""
    robot = str(corpus_file("iiwa_stack__iiwa14.urdf"))
    yaml_path = write(tmp_path, "iiwa_control.yaml", IIWA_CONTROL)
    code, out, err = simulate(robot, "--params", yaml_path, "--format", "json")
    doc = json.loads(out)["runs"][0]
    assert (code, err) == (0, "") and doc["verdict"] == "pass"
    assert doc["joints"]["iiwa_joint_7"]["max_error"] < 1e-4
    stiff = [n for n in doc["notes"] if n.startswith("gains")]
    assert len(stiff) == 1
    assert stiff[0].startswith(
        "gains beyond the stable region of an undamped joint at --dt 0.001 s (with the one-period "
        "delay it needs kd·dt < 1 and kp·dt² < kd·dt·(1 - kd·dt)); the URDF damping keeps the "
        "sampled loop stable, so less real damping would make it oscillate: iiwa_joint_7 "
        "(kp·dt² 0.017, kd·dt 2; x0.99")
    # the same gains without the damping: unstable, named in the note and in the verdict
    undamped = write(tmp_path, "iiwa.urdf", corpus_file("iiwa_stack__iiwa14.urdf").read_text(
        encoding="utf-8").replace('damping="0.5"', 'damping="0"'))
    code, out, err = simulate(undamped, "--params", yaml_path, "--format", "json")
    doc = json.loads(out)["runs"][0]
    assert (code, doc["verdict"]) == (1, "fail")
    assert "gains too stiff for --dt 0.001 s, the loop cannot be stable" in " ".join(doc["notes"])
    assert any(r.startswith("joint 'iiwa_joint_7': gains too stiff for --dt 0.001 s: the "
                            "sampled loop is unstable, its error grows x1.4") for r in doc["reasons"])
    code, out, err = simulate(robot, "--params", yaml_path, "--dt", "0.0002", "--format", "json")
    doc = json.loads(out)["runs"][0]
    assert (code, err) == (0, "") and doc["verdict"] == "pass"
    assert not any(n.startswith("gains") for n in doc["notes"])


def test_an_unstable_loop_fails_even_when_the_run_is_too_short_to_show_it(tmp_path):
    """kp·dt² 0.252 just past the delayed loop's bound b (1 - b) = 0.25 at kd·dt 0.5: the error
    grows by 0.2% per step, too slowly to leave the tolerance in 0.5 s, but it is unstable."""
    robot = write(tmp_path, "p.urdf", pendulum(1.0, 0.5, 40.0))
    params = write(tmp_path, "g.toml", "[joints.swing]\nkp = 252000.0\nkd = 500.0\n")
    code, out, err = simulate(robot, "--params", params, "--duration", "0.5", "--format", "json")
    doc = json.loads(out)["runs"][0]
    assert (code, err) == (1, "")
    assert doc["joints"]["swing"]["max_error"] < 0.01  # tracking alone would pass
    assert doc["reasons"][0] == (
        "joint 'swing': gains too stiff for --dt 0.001 s: the sampled loop is unstable, its "
        "error grows x1.002 per step (kp·dt² 0.252, kd·dt 0.5; with the one-period delay it "
        "needs kd·dt < 1 and kp·dt² < kd·dt·(1 - kd·dt))")
