"""The simulate part of ``txtool demo``."""

from __future__ import annotations

import io

from rich.console import Console

from tests.simulate.robots import arm_ros1, write
from txtool.io.resources import shipped
from txtool.simulation.demo import demo_runs, flipped_copy
from txtool.simulation.run import Options, simulate_one


def test_demo_runs_pass_then_fail_naming_the_joint():
    robot = shipped("fixtures", "demo_robot.urdf")
    out = io.StringIO()
    demo_runs(Console(file=out, width=120), robot)
    text = out.getvalue()
    assert "PASS: largest tracking error" in text
    assert "reversed: FAIL: joint '" in text


def test_flipped_copy_negates_the_first_simple_reduction(tmp_path):
    robot = write(tmp_path, "arm.urdf", arm_ros1())
    flipped, what = flipped_copy(robot, tmp_path)
    assert what == "'t_shoulder' reversed"
    assert "<mechanicalReduction>-50</mechanicalReduction>" in flipped.read_text()
    run = simulate_one(Options(robot=robot), str(flipped))
    assert run.reasons[0].startswith("joint 'shoulder'")
