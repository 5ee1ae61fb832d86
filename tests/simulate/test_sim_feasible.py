"""The default motion respects the robot's limits; a trajectory beyond them is saturated."""

from __future__ import annotations

import numpy as np
import pytest

from tests.simulate.robots import arm_ros1, pendulum, write
from txtool.simulation.feasible import MARGIN
from txtool.simulation.run import Options, simulate_one

# every joint 25% -> 75% -> 25% of its range, about a centre of its own (reference.py)
MOTION = ("minimum-jerk 25% -> 75% -> 25% of each range, shifted by a share of its own per "
          "joint (within ±5%)")


def fast_arm(tmp_path, velocity: float = 0.5) -> str:
    """The test arm with slow joints (velocity limit 0.5 rad/s on the shoulder)."""
    text = arm_ros1().replace('effort="40" velocity="3"', f'effort="40" velocity="{velocity}"')
    return write(tmp_path, "slow.urdf", text)


def test_default_motion_is_slowed_for_the_binding_velocity_limit(tmp_path):
    run = simulate_one(Options(robot=fast_arm(tmp_path)), None)
    assert run.passed, run.reasons
    # shoulder range 3 rad: a 1.5 rad move peaks at 1.875 * 1.5 / T <= 0.8 * 0.5 rad/s
    move = 1.875 * 1.5 / (MARGIN * 0.5)
    assert run.reference == (f"{MOTION}, "
                             f"{move:.3g} s per move (slowed for joint 'shoulder' velocity "
                             "limit)")
    assert run.duration == pytest.approx(2 * move, rel=1e-3)
    peak = np.abs(np.diff(run.series.q_ref[:, 0])).max() / run.dt
    assert peak == pytest.approx(MARGIN * 0.5, rel=1e-3)
    assert run.actuators["m_shoulder"].peak_velocity <= 50 * 0.5


def test_a_given_duration_shrinks_the_motion_instead(tmp_path):
    run = simulate_one(Options(robot=fast_arm(tmp_path), duration=4.0), None)
    assert run.passed, run.reasons
    assert run.duration == 4.0
    share = MARGIN * 0.5 * 2.0 / (1.875 * 1.5)
    assert ("to stay within the limits at 2 s per move, joints move this share of the default "
            f"amplitude: 'shoulder' {100 * share:.0f}%") in run.notes
    assert np.ptp(run.series.q_ref[:, 0]) == pytest.approx(1.5 * share, rel=1e-3)
    # the header says plainly how much and why
    assert run.reference == (f"{MOTION}, 2 s per move; "
                             f"amplitude cut to {100 * share:.0f}% of the default for 1 of 3 "
                             "joints to fit the given duration of 4 s (joint velocity limits; "
                             "see the notes)")


def test_without_a_given_duration_time_stretches_instead_of_the_amplitude(tmp_path):
    """A slow joint (0.04 rad/s) needs an 88 s move: well beyond 30 s, still in full. Only
    past 120 s per move does the amplitude shrink, and the header says so."""
    run = simulate_one(Options(robot=fast_arm(tmp_path, velocity=0.04), keep_series=False),
                       None)
    assert run.passed, run.reasons
    move = 1.875 * 1.5 / (MARGIN * 0.04)
    assert move > 2 * 30
    assert run.reference == (f"{MOTION}, "
                             f"{move:.3g} s per move (slowed for joint 'shoulder' velocity "
                             "limit)")
    assert not any("share of the default amplitude" in n for n in run.notes)
    slower = simulate_one(Options(robot=fast_arm(tmp_path, velocity=0.02), keep_series=False),
                          None)
    share = 120 / (1.875 * 1.5 / (MARGIN * 0.02))
    assert slower.passed, slower.reasons
    assert slower.reference == (f"{MOTION}, 120 s per move; "
                                f"amplitude cut to {100 * share:.0f}% of the default for 1 of 3 "
                                "joints to keep the run within 240 s (joint velocity limits; "
                                "see the notes)")


def test_default_motion_is_slowed_for_an_actuator_effort_limit(tmp_path):
    # turning in the horizontal plane: 1 kg at 0.5 m needs 0.25 qdd N m, 0.0173 N m at the
    # motor (reduction 40) for the 3 rad move in 2.5 s; the limit is 0.01
    text = pendulum(1.0, 0.5, 40.0).replace('<axis xyz="0 -1 0"/>', '<axis xyz="0 0 1"/>')
    robot = write(tmp_path, "p.urdf", text)
    params = write(tmp_path, "p.toml", "[actuators.m_swing]\neffort_limit = 0.01\n")
    run = simulate_one(Options(robot=robot, params=params), None)
    assert run.passed, run.reasons
    assert run.reference.endswith("(slowed for actuator 'm_swing' effort limit)")
    assert MARGIN * 0.01 * 0.9 < run.actuators["m_swing"].peak_effort <= 0.01


def test_a_robot_that_cannot_hold_itself_fails_naming_the_actuator(tmp_path):
    robot = write(tmp_path, "p.urdf", pendulum(1.0, 0.5, 40.0))
    params = write(tmp_path, "p.toml", "[actuators.m_swing]\neffort_limit = 0.05\n")
    run = simulate_one(Options(robot=robot, params=params, duration=1.0, counterbalance=False),
                       None)
    assert not run.passed
    assert run.reasons[0].startswith("actuator 'm_swing': holding joint 'swing' against gravity "
                                     "needs 0.12")
    assert "beyond its effort limit 0.05 (the URDF may lack a counterbalance or spring)" \
        in run.reasons[0]
    assert any(n.startswith("joint 'swing' is held still: gravity and friction alone need")
               for n in run.notes)


def test_trajectory_beyond_the_limits_is_saturated_and_reported_apart(tmp_path):
    robot = write(tmp_path, "arm.urdf", arm_ros1())
    beyond = write(tmp_path, "beyond.csv", "time,shoulder\n0,0\n2,1.8\n4,0\n")
    run = simulate_one(Options(robot=robot, trajectory=beyond), None)
    assert run.series.q_ref[:, 0].max() == pytest.approx(1.5)
    notes = " ".join(run.notes)
    assert "reference: joint 'shoulder' goes outside its position limits [-1.5, 1.5] from " \
           "t=1." in notes
    assert "saturated as computed_torque_controllers does (q_sp = saturate(q_cmd))" in notes
    # meeting the limit at 0.9 rad/s asks for more than the motor has, for one step
    assert run.reasons[0] == ("the reference exceeds the limits of joint 'shoulder' and was "
                              "saturated (see the notes): the failures may come from the "
                              "reference, not the config")
    flipped = write(tmp_path, "flipped.urdf", arm_ros1(n=-50))
    fault = simulate_one(Options(robot=robot, trajectory=beyond), flipped)
    assert fault.joints["shoulder"].max_error > 0.5
    assert any(r.startswith("joint 'shoulder': tracking error") for r in fault.reasons)


def test_saturated_setpoint_inside_the_limits_is_followed(tmp_path):
    robot = write(tmp_path, "arm.urdf", arm_ros1())
    # the command creeps 5 mrad past the upper limit: the setpoint stops there, the plant too
    creep = write(tmp_path, "creep.csv", "time,shoulder\n0,1.49\n1,1.495\n3,1.505\n4,1.5\n")
    prompt = simulate_one(Options(robot=robot, trajectory=creep, interpolation="linear",
                                  delay=False), None)
    assert prompt.series.q_ref[:, 0].max() == 1.5
    assert prompt.joints["shoulder"].max_error < 1e-4
    assert prompt.series.q[:, 0].max() - 1.5 < 1e-6
    assert any(n.startswith("reference: joint 'shoulder' goes outside") for n in prompt.notes)
    # With the loop's delay the torque acts a period late: the plant runs on past the stop by
    # about what the reference (2.5 mrad/s) covers in the delay and the hold, two periods.
    late = simulate_one(Options(robot=robot, trajectory=creep, interpolation="linear"), None)
    assert 0 < late.series.q[:, 0].max() - 1.5 < 2 * 0.0025 * late.dt


def test_trajectory_faster_than_the_joint_is_rate_limited(tmp_path):
    robot = write(tmp_path, "arm.urdf", arm_ros1())
    jump = write(tmp_path, "jump.csv", "time,elbow\n0,0\n0.1,1\n2,1\n")
    run = simulate_one(Options(robot=robot, trajectory=jump, interpolation="linear",
                               allow_saturation=True), None)
    elbow = run.series.joints.index("elbow")
    assert np.abs(np.diff(run.series.q_ref[:, elbow])).max() / run.dt == pytest.approx(3.0)
    assert any(n.startswith("reference: joint 'elbow' moves at up to 10, beyond its velocity "
                            "limit 3") for n in run.notes)
