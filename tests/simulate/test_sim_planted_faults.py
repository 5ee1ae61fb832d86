"""Faults planted in the simulator's own code that a user would pay for.

Each test here fails when its fault is planted: the integral term pushing the wrong way, the
effort-path check reading the config's actuators in the robot's order instead of binding them
by name, the limit-cycle detection off by one reversal or one step of its window.
"""

from __future__ import annotations

import numpy as np
import pytest

from tests.simulate.robots import ARM_BODY, ARM_ROS1_SHOULDER, ARM_ROS1_WRIST, arm_ros1, write
from txtool.simulation.checks import CHATTER_REVERSALS, CHATTER_WINDOW, _limit_cycle
from txtool.simulation.run import Options, simulate_one


def test_a_strong_integral_term_tracks_and_so_would_not_with_its_sign_reversed(tmp_path):
    # kp 400, kd 40, ki 2000: the closed loop s^3 + kd s^2 + kp s + ki is stable (kd·kp > ki);
    # with the integral pushing the wrong way it has a root near +3.6 /s and runs away.
    robot = write(tmp_path, "arm.urdf", arm_ros1())
    params = write(tmp_path, "p.toml", "".join(
        f"[joints.{j}]\nki = 2000.0\ni_clamp = 1e6\n" for j in ("shoulder", "elbow", "wrist")))
    run = simulate_one(Options(robot=robot, params=params, duration=3.0), None)
    assert run.passed, run.reasons
    assert max(j.max_error for j in run.joints.values()) < 2e-3


def test_the_effort_path_binds_the_configs_actuators_by_name(tmp_path):
    # The same transmissions, the config listing them (and so its actuators) in another order:
    # the controller's efforts reach the right actuators, and the effort path must agree.
    robot = write(tmp_path, "arm.urdf", arm_ros1())
    wrist = ARM_ROS1_WRIST.format(j1="elbow", j2="wrist", offset=0.1,
                                  kind="DifferentialTransmission")
    reordered = write(tmp_path, "reordered.urdf", f'<robot name="arm">{ARM_BODY}{wrist}'
                      f"{ARM_ROS1_SHOULDER.format(n=50)}</robot>")
    run = simulate_one(Options(robot=robot, duration=1.0), reordered)
    assert run.passed, run.reasons


def _alternating(turns: int, period: int, limit: float = 1.0, start: int = 10) -> np.ndarray:
    """Saturated demand reversing sign ``turns`` times, one reversal every ``period`` steps."""
    demand = np.zeros(start + (turns + 1) * period + 10)
    for n in range(turns + 1):
        demand[start + n * period] = (2 * limit) * (1 if n % 2 == 0 else -1)
    return demand


@pytest.mark.parametrize("turns, found", [(CHATTER_REVERSALS - 1, False),
                                          (CHATTER_REVERSALS, True)])
def test_a_limit_cycle_needs_exactly_the_stated_number_of_reversals(turns, found):
    hit = _limit_cycle(_alternating(turns, period=5), 1.0)
    assert (hit is not None) == found
    if found:
        assert hit == (15, CHATTER_REVERSALS)  # the first reversal, at step 10 + 5


@pytest.mark.parametrize("span, found", [(CHATTER_WINDOW - 1, True), (CHATTER_WINDOW, False)])
def test_a_limit_cycle_counts_reversals_within_the_window(span, found):
    # CHATTER_REVERSALS reversals, the first and last `span` steps apart: within a window of
    # CHATTER_WINDOW steps only when span < CHATTER_WINDOW.
    period = span / (CHATTER_REVERSALS - 1)
    demand = np.zeros(400)
    # the first saturated sample (step 10) starts the pattern; reversals at steps[1:]
    steps = [10] + [10 + 1 + round(n * period) for n in range(CHATTER_REVERSALS)]
    for n, k in enumerate(steps):
        demand[k] = 2.0 if n % 2 == 0 else -2.0
    assert steps[-1] - steps[1] == span
    assert (_limit_cycle(demand, 1.0) is not None) == found


def test_a_plant_left_singular_by_a_runaway_state_is_a_divergence_not_a_crash(tmp_path,
                                                                            monkeypatch):
    from txtool.simulation import plant

    robot = write(tmp_path, "arm.urdf", arm_ros1().replace(
        '<dynamics damping="0.05"/>', '<dynamics damping="0.05" friction="0.2"/>'))
    real = plant.Dynamics._velocity
    calls = 0

    def singular_after_a_while(self, q, v, tau, h):
        nonlocal calls
        calls += 1
        if calls > 1234:
            raise np.linalg.LinAlgError("Singular matrix")
        return real(self, q, v, tau, h)

    monkeypatch.setattr(plant.Dynamics, "_velocity", singular_after_a_while)
    run = simulate_one(Options(robot=robot, duration=2.0), None)
    assert run.verdict == "fail"
    assert run.reasons[0].startswith("the simulation diverged at t=")
    assert all(np.isfinite(j.max_error) for j in run.joints.values())
