"""--plot for big robots: a summary first, the driven joints only (or those --joints names),
the worst first, in a grid sized for their number."""

from __future__ import annotations

import importlib.util
import struct

import numpy as np
import pytest

from txtool.io.xmlio import InputError
from txtool.simulation.plot import MAX_COLUMNS, cell_order, grid, plot, selected
from txtool.simulation.result import (
    Coverage,
    RunResult,
    Series,
    actuator_stats,
    joint_stats,
)

NEEDS_MATPLOTLIB = pytest.mark.skipif(importlib.util.find_spec("matplotlib") is None,
                                      reason="matplotlib (extra 'plot') is not installed")


def made_run(joints: int, failing: dict[int, float], steps: int = 200,
             direct: tuple[int, ...] = ()) -> RunResult:
    """A run of ``joints`` simple joints whose errors peak at ``failing[v]`` (else 1e-4);
    those in ``direct`` driven without a transmission."""
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
                    transmission_of=tuple("" if v in direct else f"t{v}" for v in range(joints)),
                    q_ref=q_ref, q=q,
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


@NEEDS_MATPLOTLIB
def test_a_30_joint_robot_plots_at_a_readable_size(tmp_path):
    target = tmp_path / "many.png"
    plot([made_run(30, {17: 0.3})], str(target))
    width, height = struct.unpack(">II", target.read_bytes()[16:24])
    # the summary and 60 cells in six columns of 5 x 3.4 in at 100 dpi: 11 rows, about
    # 3000 x 3860 px (one row a joint made it 13,000 px tall)
    assert width <= 3200 and height <= 3900, (width, height)


def test_by_default_only_the_joints_a_transmission_drives_are_drawn():
    """A hand's or a caster's joints driven directly are left out, with their actuators."""
    run = made_run(8, {6: 0.05}, direct=(1, 2, 3, 7))
    assert selected([run], ()) == ["j0", "j4", "j5", "j6"]
    assert cell_order([run], selected([run], ())) == [
        ("joint", "j6"), ("joint", "j0"), ("joint", "j4"), ("joint", "j5"),
        ("actuator", "m0"), ("actuator", "m4"), ("actuator", "m5"), ("actuator", "m6")]


def test_joints_named_or_matched_are_drawn_and_an_unmatched_name_is_one_line():
    run = made_run(12, {}, direct=(10, 11))
    assert selected([run], ("j1*",)) == ["j1", "j10", "j11"]
    assert selected([run], ("j3", "j0")) == ["j0", "j3"]
    with pytest.raises(InputError, match=r"^--joints: no joint of robot.urdf is named 'arm_\*'$"):
        selected([run], ("arm_*",))


@NEEDS_MATPLOTLIB
def test_the_figure_opens_with_a_summary_of_every_drawn_joint_worst_first(tmp_path):
    target = tmp_path / "summary.svg"
    plot([made_run(5, {3: 0.2, 1: 0.05}, direct=(4,))], str(target))
    svg = target.read_text()
    assert "max error / tolerance" in svg and "peak / limit" in svg
    assert "worst first" in svg
    # the joints' bars are labelled in the order drawn: j3, j1, then the rest; j4 not at all
    first = {name: svg.find(f"<!-- {name} -->") for name in ("j0", "j1", "j2", "j3", "j4")}
    assert sorted(first, key=first.get)[1:] == ["j3", "j1", "j0", "j2"] and first["j4"] == -1
