"""The loop as ros2_control runs it: read -> update -> write delay, encoders, limit cycles."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

from tests.simulate.robots import arm_ros1, pendulum, planar_two_link, with_transmission, write
from txtool.cli import cli
from txtool.simulation import loop
from txtool.simulation.run import Options, prepare, simulate_one

DEMO_ROBOT = Path(__file__).resolve().parents[2] / "fixtures" / "demo_robot.urdf"  # damped


@pytest.fixture
def hold(tmp_path):
    return write(tmp_path, "hold.csv", "time,swing\n0,0.3\n")


def test_the_effort_computed_at_one_step_acts_at_the_next(tmp_path):
    robot = write(tmp_path, "p.urdf", pendulum(2.0, 0.5, 40.0))
    move = write(tmp_path, "move.csv", "time,swing\n0,0\n0.2,0.3\n")
    run = simulate_one(Options(robot=robot, trajectory=move, duration=0.2), None)
    demand, applied = run.series.effort_demand[:, 0], run.series.effort[:, 0]
    assert applied[0] == applied[1] == demand[0]  # step 0 acts at once: the loop was holding
    assert np.array_equal(applied[2:], demand[1:-1])
    assert not np.array_equal(applied[1:], demand[1:])


def test_without_delay_each_effort_acts_in_its_own_step(tmp_path, hold):
    robot = write(tmp_path, "p.urdf", pendulum(2.0, 0.5, 40.0))
    run = simulate_one(Options(robot=robot, trajectory=hold, duration=0.2, delay=False), None)
    assert np.array_equal(run.series.effort[:, 0], run.series.effort_demand[:, 0])
    assert "no read-to-write delay (--no-delay): each command acts in its own step" in run.notes


def test_the_delay_changes_the_motion_but_a_sound_loop_still_tracks(tmp_path):
    robot = write(tmp_path, "arm.urdf", arm_ros1())
    late = simulate_one(Options(robot=robot, duration=2.0), None)
    prompt = simulate_one(Options(robot=robot, duration=2.0, delay=False), None)
    assert late.passed and prompt.passed
    assert 1e-7 < np.abs(late.series.q - prompt.series.q).max() < 1e-3


def test_encoder_readings_are_whole_counts_and_velocity_their_difference(tmp_path):
    robot = write(tmp_path, "arm.urdf", arm_ros1())
    p = prepare(Options(robot=robot, duration=0.5, encoder_counts=1000), None)
    state = loop.run(p.plan)
    rows, s = state.rows[:-1], p.plan.slots
    reading, speed = rows[:, s["enc"]], rows[:, s["encv"]]
    counts = reading / (2 * math.pi / 1000)
    assert np.allclose(counts, np.rint(counts), rtol=0, atol=1e-6)
    true = rows[:, s["x"]] @ p.plant.pos_j2a.T + p.plant.pos_j2a_c
    assert np.abs(reading - true).max() <= math.pi / 1000 + 1e-12
    assert np.allclose(speed[1:], np.diff(reading, axis=0) / p.plan.dt, rtol=0, atol=1e-9)
    assert len(np.unique(reading[:, 0])) > 10  # the shoulder moves through many counts


def test_fine_encoders_on_a_damped_robot_track_as_exact_readings_do(tmp_path):
    """Encoders take the general loop, whose plant applies the joint damping itself: the
    fast loop's explicit damping term must not be added to it a second time."""
    robot = write(tmp_path, "demo.urdf", DEMO_ROBOT.read_text())
    exact = simulate_one(Options(robot=robot, duration=1.0), None)
    fine = simulate_one(Options(robot=robot, duration=1.0, encoder_counts=10**8), None)
    assert exact.passed and fine.passed
    for joint, stats in exact.joints.items():
        assert fine.joints[joint].max_error == pytest.approx(stats.max_error, rel=1e-3)


def test_encoder_resolution_is_divided_by_the_reduction(tmp_path, hold):
    """64 counts per revolution: 0.098 rad at a direct joint, 0.0025 rad behind n = 40."""
    direct = simulate_one(Options(robot=write(tmp_path, "d.urdf", pendulum(2.0, 0.5, 1.0)),
                                  trajectory=hold, duration=1.0, encoder_counts=64), None)
    geared = simulate_one(Options(robot=write(tmp_path, "g.urdf", pendulum(2.0, 0.5, 40.0)),
                                  trajectory=hold, duration=1.0, encoder_counts=64), None)
    assert not direct.passed and direct.joints["swing"].max_error > 0.01
    assert geared.passed, geared.reasons
    assert geared.joints["swing"].max_error < 2 * math.pi / 64 / 40
    assert "encoders of 64 counts per actuator revolution; velocity by finite differences" \
        in geared.notes


def test_unstable_gains_chatter_against_the_limits_and_fail_with_allow_saturation(tmp_path):
    robot = write(tmp_path, "p.urdf", pendulum(2.0, 0.5, 40.0))
    run = simulate_one(Options(robot=robot, allow_saturation=True, bandwidth=1000.0,
                               duration=1.0), None)
    assert run.joints["swing"].max_error < 0.01  # the joint itself still tracks
    assert not run.passed
    # kd·dt = 2: the stability check names the gains, the chatter check the limit cycle
    assert len(run.reasons) == 2
    assert run.reasons[0].startswith("joint 'swing': gains too stiff for --dt 0.001 s: the "
                                     "sampled loop is unstable")
    assert run.reasons[1].startswith("actuator 'm_swing': chatters against its effort limit 2.5 "
                                     "from t=")
    assert "(a limit cycle: the loop is unstable)" in run.reasons[1]


def test_a_weak_motor_saturating_on_the_moves_is_no_limit_cycle(tmp_path):
    robot = write(tmp_path, "p.urdf", pendulum(2.0, 0.5, 40.0))
    params = write(tmp_path, "p.toml", "[actuators.m_swing]\neffort_limit = 0.3\n")
    # the default motion would hold the joint still (gravity alone needs 82% of the limit)
    swings = write(tmp_path, "swings.csv", "time,swing\n0,0\n0.3,0.5\n0.6,0\n0.9,0.5\n1.2,0\n")
    run = simulate_one(Options(robot=robot, allow_saturation=True, params=params,
                               trajectory=swings, duration=2.0), None)
    assert run.actuators["m_swing"].saturated_fraction > 0.01
    assert not any("chatters" in r for r in run.reasons)


def test_cli_options_for_the_loop(tmp_path):
    robot = write(tmp_path, "arm.urdf", arm_ros1())
    result = CliRunner().invoke(cli, ["simulate", robot, "--duration", "3", "--no-delay",
                                      "--encoder-counts", "4096"])
    assert result.exit_code == 0, result.output
    assert "note: no read-to-write delay (--no-delay)" in result.stdout
    assert "note: encoders of 4096 counts per actuator revolution" in result.stdout
    bad = CliRunner().invoke(cli, ["simulate", robot, "--encoder-counts", "0"])
    assert bad.exit_code == 2
    assert "Invalid value for '--encoder-counts': 0 is not in the range x>=1." in bad.stderr


def test_a_prismatic_joint_driven_directly_has_a_linear_actuator_not_quantised(tmp_path):
    text = planar_two_link(1, 1, 0.5, 0.2, 0.2, 0.01, 0.01).replace(
        'name="q2" type="revolute"', 'name="q2" type="prismatic"').replace(
        'lower="-3" upper="3" effort="100" velocity="5"/></joint>\n</robot>',
        'lower="0" upper="0.2" effort="100" velocity="5"/></joint>\n</robot>')
    robot = write(tmp_path, "slide.urdf", with_transmission(text, "q1"))
    p = prepare(Options(robot=robot, duration=0.5, encoder_counts=16), None)
    state = loop.run(p.plan)
    reading = state.column("enc")[:-1]
    true = state.column("x")[:-1]
    assert np.array_equal(reading[:, 1], true[:, 1])  # the slide: exact, in metres
    counts = reading[:, 0] / (2 * math.pi / 16)
    assert np.allclose(counts, np.rint(counts), rtol=0, atol=1e-9) and np.ptp(counts) >= 3
    run = simulate_one(Options(robot=robot, duration=0.5, encoder_counts=16), None)
    assert ("encoders of 16 counts per actuator revolution; velocity by finite differences; "
            "not quantised (linear): q2") in run.notes
