"""The simulator's physics against rigid-body dynamics written from scratch.

``independent_dynamics`` reads the URDF with lxml and computes its dynamics with Featherstone's
algorithms, sharing no code with Pinocchio or txtool. Two checks:

* the model: the mass matrix and the bias forces (gravity, Coriolis and centrifugal)
  of the model txtool builds agree at random states, on real robots of the corpus
  and on the test arm, to round-off;
* the integration: the same closed loop (the same controller, computed at every control step
  from each simulator's own state and held over the step) run for 3 s through txtool's plant
  and through classical Runge-Kutta (a step per control step: its own error, about 1e-10 rad
  here, is nothing beside the plant's), stays together within the plant's
  integration error, and that error halves with the step (a first-order method, as documented
  in docs/simulate.md, "Plant numerics"), so what differs is integration, not physics.
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest

from tests.corpus import corpus_file
from tests.simulate.independent_dynamics import Chain, rk4
from tests.simulate.robots import arm_ros1
from txtool.io.load import load
from txtool.io.xmlio import serialize
from txtool.simulation.loop import make_model
from txtool.simulation.model import build
from txtool.simulation.plant import Dynamics, substeps_for

ROBOTS = ("universal_robot__ur5e.urdf", "iiwa_stack__iiwa14.urdf", "kinova_ros__j2s7s300.urdf")


def _arm(tmp_path):
    path = tmp_path / "arm.urdf"
    path.write_text(arm_ros1(), encoding="utf-8")
    return str(path)


def _pair(path: str):
    source = load(path)
    robot = build(source)
    chain = Chain(serialize(source.tree))
    order = [chain.names.index(j) for j in robot.joints]
    return robot, chain, order


@pytest.fixture(params=["arm", *ROBOTS])
def robot_path(request, tmp_path):
    if request.param == "arm":
        return _arm(tmp_path)
    return str(corpus_file(request.param))


def test_mass_matrix_and_bias_forces_agree_with_dynamics_written_from_scratch(robot_path):
    robot, chain, order = _pair(robot_path)
    assert not robot.mimic and not robot.locked
    rng = np.random.default_rng(7)
    data = robot.model.createData()
    lower = np.tril_indices(robot.nv, -1)
    for _ in range(10):
        x = rng.uniform(-2.0, 2.0, robot.nv)
        v = rng.uniform(-2.0, 2.0, robot.nv)
        q = robot.config(x)
        mass = pin.crba(robot.model, data, q).copy()
        mass[lower] = mass.T[lower]
        bias = pin.rnea(robot.model, data, q, v, np.zeros(robot.nv))
        mine_x, mine_v = np.zeros(len(chain.names)), np.zeros(len(chain.names))
        mine_x[order], mine_v[order] = x, v
        scale = max(1.0, float(np.abs(mass).max()))
        assert np.allclose(chain.mass_matrix(mine_x)[np.ix_(order, order)], mass,
                           rtol=0, atol=1e-9 * scale)
        assert np.allclose(chain.bias(mine_x, mine_v)[order], bias, rtol=0,
                           atol=1e-9 * max(1.0, float(np.abs(bias).max())))


def _closed_loop(robot, chain, order, dt: float, seconds: float):
    """The same PD law with gravity compensation (computed from the scratch model) run
    through txtool's plant and through RK4; the largest difference in joint positions."""
    nv = robot.nv
    damping = robot.damping.copy()
    model, block = make_model(robot, np.zeros((nv, nv)))
    substeps, _ = substeps_for(dt, damping, np.ones(nv))
    model.armature = np.full(nv, dt / substeps) * damping  # the implicit damping term
    plant = Dynamics(model=model, data=model.createData(), dt=dt, substeps=substeps,
                     damping=damping, friction=None, block=block,
                     config=(lambda x, q: q.__setitem__(slice(None), robot.config(x)))
                     if robot.has_continuous else None, nq=model.nq)
    kp, kd = 100.0, 20.0
    start = np.clip(0.3 * np.ones(nv), robot.lower, robot.upper)
    x_a, v_a = start.copy(), np.zeros(nv)
    x_b, v_b = start.copy(), np.zeros(nv)
    out = np.empty(2 * nv)
    worst = 0.0
    for k in range(round(seconds / dt)):
        target = start + 0.4 * np.sin(2.0 * k * dt)

        def law(x, v, target=target):
            # gravity + M (kp e - kd v): the forces of that acceleration at rest, in one pass
            mine, wanted = np.zeros(nv), np.zeros(nv)
            mine[order], wanted[order] = x, kp * (target - x) - kd * v
            return chain.inverse_dynamics(mine, np.zeros(nv), wanted)[order] + damping * v

        plant.advance(x_a, v_a, law(x_a, v_a), out)
        x_a, v_a = out[:nv].copy(), out[nv:].copy()
        tau_b = law(x_b, v_b)
        mine_x, mine_v, mine_tau = np.zeros(nv), np.zeros(nv), np.zeros(nv)
        mine_x[order], mine_v[order], mine_tau[order] = x_b, v_b, tau_b
        mine_x, mine_v = rk4(chain, mine_x, mine_v, mine_tau, dt, 1, np.zeros(nv),
                             _in_order(damping, order, nv))
        x_b, v_b = mine_x[order], mine_v[order]
        worst = max(worst, float(np.abs(x_a - x_b).max()))
    return worst


def _in_order(values: np.ndarray, order: list[int], n: int) -> np.ndarray:
    mine = np.zeros(n)
    mine[order] = values
    return mine


def test_a_closed_loop_follows_runge_kutta_within_the_plants_first_order_error(tmp_path):
    robot, chain, order = _pair(_arm(tmp_path))
    coarse = _closed_loop(robot, chain, order, dt=0.002, seconds=3.0)
    fine = _closed_loop(robot, chain, order, dt=0.001, seconds=3.0)
    assert fine < 1e-3, fine  # rad, over 3 s of motion of +-0.4 rad
    assert 1.6 < coarse / fine < 2.4, (coarse, fine)  # first order: the step's own error
