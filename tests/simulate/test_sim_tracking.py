"""Closed-loop verdicts: matching configs pass, mismatches fail and name what is wrong."""

from __future__ import annotations

import numpy as np
import pytest

from tests.simulate.robots import arm_both, arm_ros1, arm_ros2, pendulum, write
from txtool.simulation.run import Options, simulate_one


@pytest.fixture
def arm(tmp_path):
    return write(tmp_path, "arm.urdf", arm_ros1())


def run_with(tmp_path, robot: str, candidate_text: str | None, **options):
    config = write(tmp_path, "candidate.urdf", candidate_text) if candidate_text else None
    return simulate_one(Options(robot=robot, **options), config)


def test_identical_configs_track_within_1e_3(tmp_path, arm):
    run = run_with(tmp_path, arm, arm_ros1())
    assert run.passed, run.reasons
    assert max(j.max_error for j in run.joints.values()) < 1e-3
    assert run.steps == 5000 and run.dt == 0.001
    assert all(a.saturated_fraction == 0 for a in run.actuators.values())


def test_flipped_sign_fails_and_names_the_joint(tmp_path, arm):
    run = run_with(tmp_path, arm, arm_ros1(n=-50))
    assert not run.passed
    assert run.reasons[0].startswith("joint 'shoulder': tracking error")
    assert run.joints["shoulder"].max_error > 0.5


def test_shifted_offset_fails_and_names_the_joint(tmp_path, arm):
    run = run_with(tmp_path, arm, arm_ros1(offset=0.3), duration=2.0)
    assert not run.passed
    assert run.reasons[0].startswith("joint 'elbow': tracking error")
    assert run.joints["elbow"].max_error == pytest.approx(0.2, abs=0.03)


def test_swapped_differential_roles_fail_and_name_the_joints(tmp_path, arm):
    run = run_with(tmp_path, arm, arm_ros1(swap=True), duration=2.0)
    assert not run.passed
    failing = " ".join(r for r in run.reasons if "tracking error" in r)
    assert "'elbow'" in failing and "'wrist'" in failing


def test_ros1_robot_against_its_ros2_conversion_gives_the_same_trajectory(tmp_path, arm):
    own = run_with(tmp_path, arm, None, duration=2.0, keep_series=True)
    converted = run_with(tmp_path, arm, arm_ros2(), duration=2.0, keep_series=True)
    assert converted.passed, converted.reasons
    assert np.max(np.abs(own.series.q - converted.series.q)) < 1e-9
    assert np.max(np.abs(own.series.effort - converted.series.effort)) < 1e-9
    ros2_robot = write(tmp_path, "arm-ros2.urdf", arm_ros2())
    reverse = run_with(tmp_path, ros2_robot, arm_ros1(), duration=2.0)
    assert np.max(np.abs(reverse.series.q - own.series.q)) < 1e-9


def test_too_small_effort_limit_names_the_actuator_and_the_first_violation(tmp_path, arm):
    params = write(tmp_path, "p.toml", "[actuators.m_shoulder]\neffort_limit = 0.05\n")
    run = run_with(tmp_path, arm, None, params=params, duration=2.0)
    assert not run.passed
    reason = next(r for r in run.reasons if r.startswith("actuator 'm_shoulder': effort"))
    first = run.actuators["m_shoulder"].first_violation
    assert first is not None and f"first at t={first:.3f} s" in reason
    assert run.actuators["m_shoulder"].saturated_fraction > 0
    assert run.actuators["m_shoulder"].peak_effort > 0.05
    allowed = run_with(tmp_path, arm, None, params=params, duration=2.0, allow_saturation=True)
    assert not any(r.startswith("actuator") for r in allowed.reasons)


def test_speed_limit_shrinks_the_default_motion_and_fails_a_faster_trajectory(tmp_path, arm):
    params = write(tmp_path, "p.toml", "[actuators.m_left]\nvelocity_limit = 10.0\n")
    run = run_with(tmp_path, arm, None, params=params, duration=2.0)
    assert run.passed, run.reasons
    assert run.actuators["m_left"].peak_velocity <= 10.0
    assert any("share of the default amplitude: " in n and "'elbow'" in n for n in run.notes)
    fast = write(tmp_path, "fast.csv", "time,elbow\n0,0\n0.5,1\n1,0\n")
    run = run_with(tmp_path, arm, None, params=params, trajectory=fast)
    assert any(r.startswith("actuator 'm_left': speed") for r in run.reasons)


def test_renamed_actuator_is_reported(tmp_path, arm):
    run = run_with(tmp_path, arm, arm_ros1().replace('"m_shoulder"', '"m_other"'), duration=1.0)
    assert "actuator 'm_other' of the config is not an actuator of the robot" in run.reasons
    assert "actuator 'm_shoulder' of the robot gets no command from the config" in run.reasons
    assert "joint 'shoulder': the config cannot measure it" in run.reasons


def test_joint_without_transmission_is_driven_directly(tmp_path):
    robot = write(tmp_path, "partial.urdf", arm_ros1(shoulder=False))
    run = simulate_one(Options(robot=robot, duration=3.0), None)
    assert run.passed, run.reasons
    assert "shoulder" in run.actuators and run.actuators["shoulder"].transmission == ""
    assert any("driven directly" in note and "shoulder" in note for note in run.notes)


def test_leaving_the_position_limits_fails(tmp_path):
    robot = write(tmp_path, "p.urdf", pendulum(1.0, 0.3, 10.0))
    beyond = write(tmp_path, "beyond.csv", "time,swing\n0,2.5\n0.5,3.2\n")
    run = simulate_one(Options(robot=robot, trajectory=beyond, allow_saturation=True), None)
    assert any(r.startswith("joint 'swing': leaves its position limits by") for r in run.reasons)
    assert run.joints["swing"].limit_margin < 0


def test_unstable_gains_fail_without_a_traceback(tmp_path, arm):
    unlimited = "".join(f"[actuators.{a}]\neffort_limit = 1e300\n"
                        for a in ("m_shoulder", "m_left", "m_right"))
    params = write(tmp_path, "p.toml", unlimited)
    run = run_with(tmp_path, arm, None, bandwidth=3000.0, duration=1.0, params=params)
    assert not run.passed
    assert run.reasons[0].startswith("the simulation diverged at t=")
    assert "its gains are too high for --dt 0.001 (kp·dt² 9, kd·dt 6; with the one-period " \
           "delay it needs kd·dt < 1 and kp·dt² < kd·dt·(1 - kd·dt))" in run.reasons[0]
    assert all(np.isfinite(j.max_error) for j in run.joints.values())


def test_damping_friction_and_integral_terms(tmp_path):
    text = arm_ros1().replace('<dynamics damping="0.05"/>',
                              '<dynamics damping="0.3" friction="0.2"/>')
    params = write(tmp_path, "p.toml", "[joints.shoulder]\nki = 20.0\ni_clamp = 0.5\n")
    run = simulate_one(Options(robot=write(tmp_path, "f.urdf", text), params=params), None)
    assert run.passed, run.reasons


def test_file_with_both_dialects_simulates_the_ros2_ones_by_default(tmp_path):
    robot = write(tmp_path, "both.urdf", arm_both())
    run = simulate_one(Options(robot=robot, duration=1.0), None)
    assert run.passed, run.reasons
    assert "has both ROS 1 and ROS 2 transmissions: the ROS 2 ones are simulated " \
           "(--loader ros1 for the others)" in run.notes
    for loader in ("ros1", "ros2"):
        run = simulate_one(Options(robot=robot, loader=loader, duration=1.0), None)
        assert run.passed and not any("both ROS 1" in note for note in run.notes)


def test_config_transmission_on_an_unknown_joint_fails_naming_it(tmp_path, arm):
    bad = write(tmp_path, "bad.urdf", arm_ros1().replace('<joint name="shoulder">',
                                                         '<joint name="shoulderr">'))
    run = simulate_one(Options(robot=arm, duration=1.0), bad)
    assert (
        "actuator 'm_shoulder' of the robot gets no command from the config (its transmission "
        "'t_shoulder' is not simulated in the config: joint 'shoulderr' is not a joint of the "
        "robot)") in run.reasons
    assert any(note.startswith(f"config: {bad}:") and "'t_shoulder' is not simulated" in note
               for note in run.notes)


def test_ros1_four_bar_runs_ros_controls_effort_map_by_default(tmp_path):
    """A ROS 1 robot's own four-bar, as ros_control runs it, against the physical robot."""
    robot = write(tmp_path, "fb.urdf", arm_ros1(kind="FourBarLinkageTransmission"))
    loader = simulate_one(Options(robot=robot), None)
    assert not loader.passed
    assert any(r.startswith("joint 'wrist': tracking error") for r in loader.reasons)
    assert any(r.startswith("likely cause: transmission 't_wrist': the config's effort map is "
                            "ros_control's (ROS 1) four-bar map") for r in loader.reasons)
    assert "the controller maps efforts of four-bar 't_wrist' as ros_control does (ROS 1; not " \
           "power-conserving, ros_control#523); the plant is physics (--effort-convention " \
           "ros2: ros2_control's map)" in loader.notes
    physical = simulate_one(Options(robot=robot, convention="ros2"), None)
    assert physical.passed, physical.reasons
    assert not any("ros_control does" in n for n in physical.notes)
