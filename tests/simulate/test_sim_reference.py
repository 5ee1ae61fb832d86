"""Reference motions: minimum-jerk defaults and CSV trajectories with consistent derivatives."""

from __future__ import annotations

import numpy as np
import pytest

from tests.simulate.robots import arm_ros1, write
from txtool.io.xmlio import InputError
from txtool.simulation.feasible import Motion, sample
from txtool.simulation.reference import (
    Reference,
    default_shifts,
    from_table,
    minimum_jerk,
    read_csv,
    saturate,
    step_times,
)
from txtool.simulation.run import Options, prepare, simulate_one

JOINTS = ("a", "b")


def assert_consistent(t, q, qd, qdd, tol):
    """Central differences of q and qd agree with qd and qdd (inside the interval)."""
    dt = t[1] - t[0]
    inner = slice(1, -1)
    assert np.max(np.abs(np.gradient(q, dt, axis=0) - qd)[inner]) < tol
    assert np.max(np.abs(np.gradient(qd, dt, axis=0) - qdd)[inner]) < tol * 10


def test_minimum_jerk_rest_to_rest():
    t = np.linspace(0, 2, 2001)
    q, qd, qdd = minimum_jerk(t, 0.0, 2.0, -1.0, 3.0)
    assert q[0] == -1.0 and q[-1] == 3.0
    assert qd[0] == qd[-1] == 0 and qdd[0] == qdd[-1] == 0
    assert qd.max() == pytest.approx(1.875 * 4 / 2, rel=1e-6)
    assert_consistent(t, q, qd, qdd, 1e-3)


def test_default_motion_spans_25_to_75_percent_and_back_about_each_joints_centre():
    ref = sample([(-2.0, 2.0), (0.0, 1.0)], Motion(2.0, np.ones(2), "", ()), 0.001)
    assert len(ref.time) == 4001
    shift = default_shifts(2)[1]  # of the second joint's range; the first keeps its middle
    low, high = [-1.0, 0.25 + shift], [1.0, 0.75 + shift]
    assert np.allclose(ref.q[0], low) and np.allclose(ref.q[-1], low)
    assert np.allclose(ref.q[2000], high)
    assert np.allclose(ref.q.min(axis=0), low) and np.allclose(ref.q.max(axis=0), high)
    assert_consistent(ref.time, ref.q, ref.qd, ref.qdd, 1e-3)


def table(tmp_path, text):
    return read_csv(write(tmp_path, "t.csv", text), set(JOINTS))


def test_linear_interpolation(tmp_path):
    tab = table(tmp_path, "time,b\n0,0\n1,2\n2,2\n")
    ref = from_table(tab, JOINTS, np.array([0.5, 0.0]), step_times(3.0, 0.25), "linear")
    assert np.allclose(ref.q[:, 0], 0.5)  # not in the CSV: held
    assert np.allclose(ref.q[:5, 1], [0, 0.5, 1.0, 1.5, 2.0])
    assert np.allclose(ref.qd[:5, 1], [2, 2, 2, 2, 0])
    assert np.allclose(ref.q[-1, 1], 2.0) and not ref.qdd.any()


def test_cubic_interpolation_passes_the_samples_and_starts_at_rest(tmp_path):
    tab = table(tmp_path, "time,a,b\n0,0,1\n0.5,0.4,1\n1.2,-0.3,0.5\n2,0.1,0.5\n")
    t = step_times(2.5, 0.0005)
    ref = from_table(tab, JOINTS, np.zeros(2), t, "cubic")
    for time, a, b in ((0, 0, 1), (0.5, 0.4, 1), (1.2, -0.3, 0.5), (2.0, 0.1, 0.5)):
        k = int(round(time / 0.0005))
        assert ref.q[k] == pytest.approx([a, b], abs=1e-12)
    assert np.allclose(ref.qd[0], 0) and np.allclose(ref.qd[-1], 0)
    inside = t <= 2.0
    assert_consistent(t[inside], ref.q[inside], ref.qd[inside], ref.qdd[inside], 1e-3)


def test_single_row_holds(tmp_path):
    tab = table(tmp_path, "time,a\n0,0.3\n")
    ref = from_table(tab, JOINTS, np.zeros(2), step_times(1.0, 0.1), "cubic")
    assert np.allclose(ref.q[:, 0], 0.3) and not ref.qd.any()


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("", "t.csv:1: empty trajectory"),
        ("t,a\n0,1\n", "t.csv:1: header must be time,<joint>,..."),
        ("time,c\n0,1\n", "t.csv:1: 'c' is not a moving joint of the robot"),
        ("time,a\n", "t.csv:2: no samples after the header"),
        ("time,a\n0,1\n1,x\n", "t.csv:3: 'x' is not a finite number"),
        ("time,a\n0,1\n1\n", "t.csv:3: expected 2 values, got 1"),
        ("time,a\n0,1\n1,2\n1,3\n", "t.csv:4: times must increase"),
        ("time,a\n-1,1\n", "t.csv:2: time must not be negative"),
    ],
)
def test_bad_csv(tmp_path, text, message):
    with pytest.raises(InputError) as caught:
        table(tmp_path, text)
    assert message in str(caught.value)


def test_trajectory_sets_the_duration_unless_given(tmp_path):
    robot = write(tmp_path, "arm.urdf", arm_ros1())
    csv = write(tmp_path, "t.csv", "time,shoulder,elbow\n0,0,0\n0.5,0.1,0.2\n1.5,0,0\n")
    assert prepare(Options(robot=robot, trajectory=csv), None).duration == 1.5
    assert prepare(Options(robot=robot, trajectory=csv, duration=2.0), None).duration == 2.0
    run = simulate_one(Options(robot=robot, trajectory=csv, interpolation="linear"), None)
    assert run.steps == 1500 and "linear" in run.reference


@pytest.mark.parametrize(("move", "dt"), [(1.0, 0.001), (4.69, 0.001), (0.37, 0.0007)])
def test_the_default_motion_is_each_joints_profile_to_the_bit(move, dt):
    ranges = [(-1.0, 1.0), (-3.1, 0.4), (0.0, 2.5)]
    motion = Motion(move, np.array([1.0, 0.37, 0.9]), "", ())
    ref = sample(ranges, motion, dt)
    # One joint at a time over the whole run, each move picked where it applies.
    second = ref.time >= move
    shifts = default_shifts(len(ranges))
    for i, (lo, hi) in enumerate(ranges):
        middle = (lo + hi) / 2 + (hi - lo) * shifts[i]
        half = 0.25 * (hi - lo) * motion.amplitude[i]
        up = minimum_jerk(ref.time, 0.0, move, middle - half, middle + half)
        down = minimum_jerk(ref.time, move, 2 * move, middle + half, middle - half)
        for got, a, b in zip((ref.q, ref.qd, ref.qdd), up, down, strict=True):
            assert got[:, i].tobytes() == np.where(second, b, a).tobytes()


def test_saturated_joints_are_carried_as_data_not_read_back_from_the_notes():
    """The run's "exceeds the limits of joint ..." reason names the joints of
    ``Reference.saturated``: a name with a quote in it is kept whole."""
    t = np.linspace(0.0, 1.0, 11)
    q = np.column_stack([2.0 * t, 0.5 * t, 0.1 * t])  # over its limit, too fast, within both
    qd = np.column_stack([np.full_like(t, 2.0), np.full_like(t, 0.5), np.full_like(t, 0.1)])
    ref = Reference(t, q, qd, np.zeros_like(q), "test")
    joints = ("o'hare knee", "wrist", "elbow")
    limits = np.array([1.0, 1.0, 1.0])
    saturated, notes = saturate(ref, joints, -limits, limits, np.array([5.0, 0.2, 5.0]), 0.1)
    assert saturated.saturated == ("o'hare knee", "wrist")
    assert len(notes) == 2 and saturate(ref, joints, -3 * limits, 3 * limits,
                                         np.full(3, 5.0), 0.1) == (ref, [])
    assert ref.saturated == ()
