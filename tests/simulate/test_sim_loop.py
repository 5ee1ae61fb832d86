"""The delayed fast loop (a ring of working rows, Phi folded into H and PD) against the plain one.

``loop.plain_steps`` is the loop as the docs describe it, one product per matrix and one view
per column per step; ``ring.delayed_steps`` is what the default settings run. They must agree
to round-off: x and v within 1e-12, efforts within 1e-12 of their peak. Accelerations get
1e-11 of their peak: ``aba`` divides the torque's round-off (the folded sums) by the inertia.
The fast loop leaves out the clip where it changes nothing; that must change no bit.
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from tests.simulate.robots import arm_ros1, pendulum, write
from tests.simulate.test_sim_counterbalance import WEAK_MOTOR
from txtool.simulation import loop, ring
from txtool.simulation.run import Options, prepare

FIXTURES = Path(__file__).resolve().parents[2] / "fixtures"


def robots(tmp_path) -> dict[str, Options]:
    pendulum_path = write(tmp_path, "p.urdf", pendulum(1.0, 0.5, 40.0))
    return {
        # damping: a bias row; a differential: C is no identity
        "demo robot": Options(robot=str(FIXTURES / "demo_robot.urdf")),
        "arm (simple + differential)": Options(robot=write(tmp_path, "arm.urdf", arm_ros1())),
        # reductions of 1: C is the identity
        "direct pendulum": Options(robot=write(tmp_path, "d.urdf", pendulum(1.0, 0.5, 1.0))),
        # a counterbalance column in PD and in the bias
        "counterbalanced pendulum": Options(robot=pendulum_path,
                                            params=write(tmp_path, "w.toml", WEAK_MOTOR)),
        # saturation on a fast move: the clip is active
        "saturating": Options(robot=write(tmp_path, "a2.urdf", arm_ros1()),
                              allow_saturation=True, params=write(
                                  tmp_path, "s.toml", "[actuators.m_shoulder]\n"
                                  "effort_limit = 0.3\n"),
                              trajectory=write(tmp_path, "fast.csv",
                                               "time,shoulder\n0,0\n0.3,1\n0.6,0\n1,0\n")),
    }


CASES = ["demo robot", "arm (simple + differential)", "direct pendulum",
         "counterbalanced pendulum", "saturating"]


@pytest.mark.parametrize("case", CASES)
def test_the_delayed_loop_matches_the_plain_loop(tmp_path, case):
    plan = prepare(robots(tmp_path)[case], None).plan
    assert plan.delay and plan.dynamics.simple and plan.ki is None
    assert loop.step_loop(plan) is ring.delayed_steps
    fast = loop.run(plan)
    plain = loop.run(plan, steps=loop.plain_steps)  # the same plan, run again from its start
    end = plan.steps
    for name in ("x", "v"):
        assert np.abs(fast.column(name) - plain.column(name)).max() <= 1e-12
    for name, rows, bound in (("sat", slice(None), 1e-12), ("ta", slice(0, end), 1e-12),
                              ("a", slice(0, end), 1e-11)):
        a, b = fast.column(name)[rows], plain.column(name)[rows]
        assert np.abs(a - b).max() <= bound * max(1.0, np.abs(b).max()), name
    if case == "saturating":
        assert (np.abs(fast.column("ta")[:end]) > plan.limit).any()


def test_a_run_leaves_its_plan_as_it_was(tmp_path):
    """The plan is what is fixed for a run: a run writes only its own state, so running a plan
    twice gives the same history, to the bit."""
    plan = prepare(robots(tmp_path)["saturating"], None).plan
    start = plan.start_rows.copy()
    first, again = loop.run(plan), loop.run(plan)
    assert np.array_equal(plan.start_rows, start)
    assert first.done == again.done == plan.steps and first.rows is not again.rows
    assert first.rows.tobytes() == again.rows.tobytes()


def test_the_step_loop_follows_the_plan(tmp_path):
    options = robots(tmp_path)["direct pendulum"]
    assert loop.step_loop(prepare(options, None).plan) is ring.delayed_steps
    undelayed = prepare(replace(options, delay=False), None).plan
    assert loop.step_loop(undelayed) is loop.plain_steps
    integral = prepare(replace(options, params=write(
        tmp_path, "ki.toml", "[joints.swing]\nki = 1.0\n")), None).plan
    assert loop.step_loop(integral) is loop.general_steps


@pytest.mark.parametrize("case", CASES)
def test_leaving_out_a_clip_that_changes_nothing_changes_no_bit(tmp_path, case, monkeypatch):
    options = robots(tmp_path)[case]
    plan = prepare(options, None).plan
    checked = loop.run(plan)
    monkeypatch.setattr(ring, "_changed", lambda a, b: True)  # every block clips
    clipped = loop.run(plan)
    assert checked.rows.tobytes() == clipped.rows.tobytes()


def test_a_block_that_saturates_runs_again_with_the_clip(tmp_path, monkeypatch):
    blocks: list[str] = []
    block = ring._block

    def spy(plan, state, working, views, n, *, clip):
        blocks.append("C" if clip else ".")
        block(plan, state, working, views, n, clip=clip)

    monkeypatch.setattr(ring, "_block", spy)
    prepared = prepare(robots(tmp_path)["saturating"], None)
    loop.run(prepared.plan)
    runs = "".join(blocks)
    # unclipped, then again with the clip; clipping while it saturates; checking again after
    assert ".C" in runs and "CC" in runs and "C." in runs
    steps = len(runs) - runs.count(".C")  # a block run twice counts once
    assert steps * ring.RING >= prepared.plan.steps > (steps - 2) * ring.RING
