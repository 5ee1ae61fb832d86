"""The default motion gives each joint a reference of its own, so alike joints are told apart."""

from __future__ import annotations

import itertools

import numpy as np
import pytest

from tests.simulate.robots import write
from tests.simulate.test_sim_faults import twin_fingers
from txtool.simulation.reference import SHIFT, default_shifts
from txtool.simulation.run import Options, simulate_one


def test_every_joint_moves_about_a_centre_of_its_own():
    shifts = default_shifts(60)
    assert shifts[0] == 0.0  # a single joint keeps the middle of its range
    assert np.all(np.abs(shifts) <= SHIFT)
    assert len(set(shifts.round(12))) == 60
    # neighbours in the DoF order (twin fingers, a pair of wheels) are far apart
    assert np.abs(np.diff(shifts)).min() > 0.7 * SHIFT


def test_swapped_twins_are_caught_by_the_default_motion_alone(tmp_path):
    robot = write(tmp_path, "gripper.urdf", twin_fingers("left", "right"))
    swapped = write(tmp_path, "swapped.urdf", twin_fingers("right", "left"))
    run = simulate_one(Options(robot=robot, duration=1.0), swapped)
    # each finger tracks the other's reference: off by the difference of their centres
    offset = 2.0 * abs(default_shifts(2)[1] - default_shifts(2)[0])  # range 2 rad
    tracking = {r.split("'")[1]: r for r in run.reasons if "tracking error" in r}
    assert set(tracking) == {"left", "right"}
    for joint in ("left", "right"):
        error = float(tracking[joint].split("tracking error ")[1].split()[0])
        assert error == pytest.approx(offset, rel=0.02)  # and the loop's own small lag
    assert any("joints 'left' and 'right' swapped" in r for r in run.reasons)


def test_twins_follow_different_references_at_every_step(tmp_path):
    robot = write(tmp_path, "gripper.urdf", twin_fingers("left", "right"))
    run = simulate_one(Options(robot=robot, duration=1.0), None)
    assert run.passed, run.reasons
    q = run.series.q_ref
    for a, b in itertools.combinations(range(q.shape[1]), 2):
        assert np.abs(q[:, a] - q[:, b]).min() > 5 * run.tolerance
