"""A static gravity load beyond a joint's effort limit: an undescribed counterbalance carries it.

The URDFs of PR2 (shoulder counterbalance springs) and TIAGo (base suspension springs) leave out
what holds part of their weight, so their actuators' effort limits sit below the gravity torque.
simulate applies the excess to the joint directly and checks the actuator on the rest; with
``--no-counterbalance`` the robot fails, naming the actuator that cannot hold its joint. The
assumption never hides a transmission fault: the fault matrix still fails with its causes.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

from tests.simulate.robots import pendulum, write
from tests.simulate.test_sim_cli import txtool
from tests.simulate.test_sim_faults import FAULTS, causes
from txtool.simulation.counterbalance import KEEP
from txtool.simulation.run import Options, simulate_one

# 1 kg at 0.5 m: gravity needs up to 9.81 * 0.5 = 4.905 N·m at the horizontal; the motor
# (reduction 40, effort limit 0.05 N·m) gives the joint 2 N·m.
WEAK_MOTOR = "[actuators.m_swing]\neffort_limit = 0.05\n"


def weak_pendulum(tmp_path, reduction: float = 40.0) -> tuple[str, str]:
    return (write(tmp_path, "p.urdf", pendulum(1.0, 0.5, reduction)),
            write(tmp_path, "p.toml", WEAK_MOTOR))


def test_the_excess_static_load_is_carried_and_named(tmp_path):
    robot, params = weak_pendulum(tmp_path)
    run = simulate_one(Options(robot=robot, params=params, duration=2.0), None)
    assert run.passed, run.reasons
    entry = run.counterbalance["swing"]
    # the reference swings the range [-3, 3] from 25% to 75%: through the horizontal
    assert entry["static_load"] == pytest.approx(9.81 * 0.5, rel=1e-3)
    assert entry["limit"] == pytest.approx(2.0)
    assert entry["carried"] == pytest.approx(entry["static_load"] - KEEP * 2.0, rel=1e-9)
    assert entry["units"] == "N·m"
    note = next(n for n in run.notes if n.startswith("joint 'swing': gravity needs"))
    assert note == ("joint 'swing': gravity needs up to 4.905 N·m to hold it, beyond its effort "
                    "limit 2 N·m: a counterbalance or spring the URDF does not describe is "
                    "assumed to carry up to 3.905 N·m (what exceeds 50% of the limit), applied "
                    "to the joint directly; the actuator is checked on the rest "
                    "(--no-counterbalance: off)")
    # the motor holds only what is left: at most half its limit for gravity, plus the motion
    assert run.actuators["m_swing"].peak_effort <= 0.05
    assert not any("held still" in n for n in run.notes)


def test_a_motion_cut_below_the_limit_is_not_said_to_go_beyond_it(tmp_path):
    """Hanging at the centre of its range, the pendulum loads its joint beyond the limit only
    far from it: a given duration that cuts the motion leaves it over half its limit (the
    counterbalance carries the excess over that half, and the note says so), or below half
    (nothing carried, no note)."""
    hanging = pendulum(1.0, 0.5, 40.0).replace('<origin xyz="0.5 0 0"/>',
                                                '<origin xyz="0 0 -0.5"/>')
    robot = write(tmp_path, "p.urdf", hanging)
    params = write(tmp_path, "p.toml", WEAK_MOTOR)
    run = simulate_one(Options(robot=robot, params=params, duration=1.0), None)
    (note,) = [n for n in run.notes if n.startswith("joint 'swing': gravity needs")]
    load = run.counterbalance["swing"]["static_load"]
    assert KEEP * 2.0 < load < 2.0 and run.passed
    assert note.startswith(f"joint 'swing': gravity needs up to {load:.4g} N·m to hold it, "
                           f"{50 * load:.0f}% of its effort limit 2 N·m (beyond the limit on "
                           "the motion before it was cut): a counterbalance")
    run = simulate_one(Options(robot=robot, params=params, duration=0.5), None)
    assert run.passed and run.counterbalance == {}
    assert not any("counterbalance or spring" in n for n in run.notes)


def test_without_the_assumption_the_robot_cannot_hold_itself(tmp_path):
    robot, params = weak_pendulum(tmp_path)
    run = simulate_one(Options(robot=robot, params=params, duration=2.0, counterbalance=False),
                       None)
    assert not run.passed and run.counterbalance == {}
    assert run.reasons[0].startswith("actuator 'm_swing': holding joint 'swing' against gravity "
                                     "needs 0.12")
    assert not any("counterbalance or spring the URDF does not describe" in n for n in run.notes)


def test_the_cli_reports_the_counterbalance_in_text_and_json(tmp_path):
    robot, params = weak_pendulum(tmp_path)
    code, out, err = txtool(robot, "--params", params, "--duration", "2", "--format", "json")
    doc = json.loads(out)["runs"][0]
    assert (code, err) == (0, "") and doc["verdict"] == "pass"
    assert set(doc["counterbalance"]) == {"swing"}
    assert set(doc["counterbalance"]["swing"]) == {"static_load", "limit", "carried", "units"}
    assert doc["counterbalance"]["swing"]["units"] == {"static_load": "N·m", "limit": "N·m",
                                                       "carried": "N·m"}
    assert any(n.startswith("joint 'swing': gravity needs up to") for n in doc["notes"])
    code, out, err = txtool(robot, "--params", params, "--duration", "2", "--no-counterbalance")
    assert (code, err) == (1, "")
    assert "FAIL: actuator 'm_swing': holding joint 'swing' against gravity needs" in out


@pytest.mark.parametrize("reduction, cause", [
    (80.0, "joint 'swing': reduction off by a factor 2 in the config's transmission 't_swing' "
           "(reduction 80, the robot's 40)"),
    (-40.0, "joint 'swing': direction reversed in the config's transmission 't_swing' "
            "(reduction -40, the robot's 40)"),
])
def test_a_fault_on_a_counterbalanced_joint_still_fails(tmp_path, reduction, cause):
    robot, params = weak_pendulum(tmp_path)
    candidate = write(tmp_path, "candidate.urdf", pendulum(1.0, 0.5, reduction))
    run = simulate_one(Options(robot=robot, params=params, duration=2.0), candidate)
    assert "swing" in run.counterbalance
    assert not run.passed
    assert causes(run) == [cause]


# The 3-DoF test arm with a shoulder motor too weak for the arm's weight (0.15 N·m through the
# reduction 50: 7.5 N·m at the joint, where gravity needs up to about 10.8 N·m).
WEAK_SHOULDER = "[actuators.m_shoulder]\neffort_limit = 0.15\n"


@pytest.mark.parametrize("fault", list(FAULTS))
def test_the_fault_matrix_still_fails_with_a_counterbalanced_shoulder(tmp_path, fault):
    robot_text, candidate_text, options, expected = FAULTS[fault]
    robot = write(tmp_path, "robot.urdf", robot_text())
    candidate = write(tmp_path, "candidate.urdf", candidate_text())
    params = write(tmp_path, "p.toml", WEAK_SHOULDER)
    options = {"duration": 2.0, **options}
    own = simulate_one(Options(robot=robot, params=params, **options), None)
    assert own.passed, own.reasons
    assert set(own.counterbalance) == {"shoulder"}
    run = simulate_one(Options(robot=robot, params=params, **options), candidate)
    assert not run.passed
    assert causes(run) == expected


def test_the_carried_torque_follows_the_reference_pose(tmp_path):
    """g(q_ref): the static part at each step's reference pose, not the dynamic part."""
    robot, params = weak_pendulum(tmp_path)
    run = simulate_one(Options(robot=robot, params=params, duration=2.0), None)
    angle = run.series.q_ref[:, 0]
    gravity = 9.81 * 0.5 * np.cos(angle)  # positive angle lifts the mass (axis -y)
    expected = gravity - np.clip(gravity, -KEEP * 2.0, KEEP * 2.0)
    assert run.counterbalance["swing"]["carried"] == pytest.approx(np.abs(expected).max(),
                                                                   rel=1e-6)


def test_a_limit_far_below_the_static_load_is_a_finding_not_a_spring(tmp_path):
    from tests.simulate.robots import arm_ros1

    # The shoulder holds about 10.9 N·m at rest: a limit of 4 N·m (2.7x) may be a spring left
    # out of the URDF; 0.8 N·m (13.6x) is a limit written wrong, and the run fails on it.
    plausible = write(tmp_path, "a.urdf", arm_ros1().replace('effort="40"', 'effort="4"'))
    run = simulate_one(Options(robot=plausible, duration=2.0), None)
    assert run.passed and set(run.counterbalance) == {"shoulder"}
    wrong = write(tmp_path, "b.urdf", arm_ros1().replace('effort="40"', 'effort="0.8"'))
    run = simulate_one(Options(robot=wrong, duration=2.0), None)
    assert run.verdict == "fail" and run.counterbalance == {}
    assert run.reasons[0].startswith("actuator 'm_shoulder': holding joint 'shoulder' against "
                                     "gravity needs")
    assert ("joint 'shoulder': gravity needs up to 10.89 N·m, 13.6 times its effort limit "
            "0.8 N·m: no counterbalance is assumed beyond 4 times the limit (the limit is more "
            "likely wrong than a spring that large left out)") in run.notes
