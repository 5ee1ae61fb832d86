"""--plot for big robots: a grid sized for the number of joints, failing ones first."""

from __future__ import annotations

import importlib.util
import struct

import numpy as np
import pytest

from txtool.simulation.plot import MAX_COLUMNS, cell_order, grid, plot
from txtool.simulation.result import (
    Coverage,
    RunResult,
    Series,
    actuator_stats,
    joint_stats,
)


def made_run(joints: int, failing: dict[int, float], steps: int = 200) -> RunResult:
    """A run of ``joints`` simple joints whose errors peak at ``failing[v]`` (else 1e-4)."""
    time = np.linspace(0.0, 1.0, steps + 1)
    q_ref = np.sin(np.outer(time, np.ones(joints)))
    error = np.full(joints, 1e-4)
    for v, peak in failing.items():
        error[v] = peak
    q = q_ref + np.outer(np.sin(np.pi * time), error)
    names = tuple(f"j{v}" for v in range(joints))
    actuators = tuple(f"m{v}" for v in range(joints))
    effort = np.full((steps, joints), 1.0)
    series = Series(time=time, joints=names, units=("rad",) * joints, actuators=actuators,
                    transmission_of=tuple(f"t{v}" for v in range(joints)), q_ref=q_ref, q=q,
                    effort_demand=effort, effort=effort, velocity=np.zeros((steps + 1, joints)),
                    effort_limit=np.full(joints, 10.0), velocity_limit=np.full(joints, 5.0),
                    lower=np.full(joints, -2.0), upper=np.full(joints, 2.0),
                    joint_actuators={n: [v] for v, n in enumerate(names)})
    return RunResult("robot.urdf", "config.urdf", 0.005, steps, 1.0, "made", joint_stats(series),
                     actuator_stats(series), [], [], series=series, tolerance=0.01,
                     coverage=Coverage(joints, tuple(f"t{v}" for v in range(joints))))


def test_the_grid_grows_in_columns_not_only_in_rows():
    assert grid(1) == (1, 1)
    assert grid(6) == (3, 2)  # the demo arm: 3 joints, 3 actuators
    columns, rows = grid(60)  # 30 joints and their 30 actuators
    assert (columns, rows) == (MAX_COLUMNS, 10)


def test_failing_joints_come_first_the_worst_first():
    run = made_run(6, {4: 0.05, 2: 0.2})
    order = cell_order([run])
    assert order[:6] == [("joint", "j2"), ("joint", "j4"), ("joint", "j0"), ("joint", "j1"),
                         ("joint", "j3"), ("joint", "j5")]
    assert order[6:] == [("actuator", f"m{v}") for v in range(6)]


@pytest.mark.skipif(importlib.util.find_spec("matplotlib") is None,
                    reason="matplotlib (extra 'plot') is not installed")
def test_a_30_joint_robot_plots_at_a_readable_size(tmp_path):
    target = tmp_path / "many.png"
    plot([made_run(30, {17: 0.3})], str(target))
    width, height = struct.unpack(">II", target.read_bytes()[16:24])
    # six columns of 5 x 3.4 in cells at 100 dpi: about 3000 x 3500 px (one row a joint
    # made it 13,000 px tall)
    assert width <= 3200 and height <= 3800, (width, height)
