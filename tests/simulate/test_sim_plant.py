"""The plant's numerics: implicit damping, Coulomb friction with stiction, sub-steps."""

from __future__ import annotations

import numpy as np
import pytest

from tests.simulate.robots import EFFORT, write
from txtool.io.load import load
from txtool.simulation.model import build
from txtool.simulation.reference import Reference
from txtool.simulation.run import Options, simulate_one
from txtool.simulation.setup import plant_dynamics

# A 5 g fingertip 3 cm out: inertia 4.6e-6 kg m^2 against damping 0.05 N m s/rad
# (damping / inertia = 1.1e4 1/s, eleven times what an explicit step of 1 ms can carry).
LIGHT = f"""<robot name="finger"><link name="base"/>
  <link name="tip"><inertial><origin xyz="0.03 0 0"/><mass value="0.005"/>
    <inertia ixx="1e-7" iyy="1e-7" izz="1e-7" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="flex" type="revolute"><parent link="base"/><child link="tip"/>
    <axis xyz="0 {{axis}}"/><limit lower="-1" upper="1" effort="2" velocity="2"/>
    <dynamics damping="{{damping}}" friction="{{friction}}"/></joint>
  <transmission name="t_flex"><type>transmission_interface/SimpleTransmission</type>
    <joint name="flex">{EFFORT}</joint>
    <actuator name="m_flex"><mechanicalReduction>10</mechanicalReduction></actuator>
  </transmission>
</robot>"""


def finger(tmp_path, damping: float = 0.05, friction: float = 0.02, axis: str = "-1 0") -> str:
    return write(tmp_path, "finger.urdf",
                 LIGHT.format(damping=damping, friction=friction, axis=axis))


def test_light_link_with_damping_and_friction_holds_its_reference_within_2_mrad(tmp_path):
    robot = finger(tmp_path)
    hold = write(tmp_path, "hold.csv", "time,flex\n0,0.3\n")
    run = simulate_one(Options(robot=robot, trajectory=hold, duration=1.0), None)
    assert run.passed, run.reasons
    assert run.joints["flex"].max_error <= 2e-3
    effort = run.series.effort[:, 0]
    assert np.count_nonzero(np.diff(np.sign(effort))) == 0  # no chatter
    assert "plant: 4 sub-steps per control step (joint 'flex': damping / inertia = 1.087e+04 " \
           "1/s)" in run.notes


def test_light_link_follows_the_default_motion_within_2_mrad(tmp_path):
    # 4 s fixed: the motion shrinks (unfixed, it slows to 2 x 10.2 s, 1.4 mrad)
    run = simulate_one(Options(robot=finger(tmp_path), duration=4.0), None)
    assert run.passed, run.reasons
    assert run.joints["flex"].max_error <= 2e-3
    assert any("share of the default amplitude: 'flex'" in n for n in run.notes)


def horizontal_finger(tmp_path, damping: float, friction: float):
    """The finger turning about the vertical (no gravity) and its plant integrator."""
    robot = build(load(finger(tmp_path, damping, friction, axis="0 1")))
    ref = Reference(np.zeros(2), np.zeros((2, 1)), np.zeros((2, 1)), np.zeros((2, 1)), "")
    inertia = 0.005 * 0.03**2 + 1e-7
    return plant_dynamics(robot, np.zeros((1, 1)), ref, 0.001), inertia


@pytest.mark.parametrize("share", [0.0, 0.5, 0.99])
def test_a_joint_pushed_below_its_friction_stays_exactly_still(tmp_path, share):
    dynamics, _ = horizontal_finger(tmp_path, damping=0.0, friction=0.02)
    state = np.zeros(2)
    for _ in range(2000):
        dynamics.advance(state[:1].copy(), state[1:].copy(), np.array([share * 0.02]), state)
    assert state[0] == 0.0 and state[1] == 0.0


def test_a_joint_pushed_past_its_friction_slides_with_the_difference(tmp_path):
    dynamics, inertia = horizontal_finger(tmp_path, damping=0.0, friction=0.02)
    state = np.zeros(2)
    steps = 100
    for _ in range(steps):
        dynamics.advance(state[:1].copy(), state[1:].copy(), np.array([0.03]), state)
    assert state[1] == pytest.approx(steps * 0.001 * (0.03 - 0.02) / inertia, rel=1e-9)
    for _ in range(steps):  # released: friction brings it to rest and keeps it there
        dynamics.advance(state[:1].copy(), state[1:].copy(), np.array([0.0]), state)
    assert state[1] == 0.0


def test_damping_far_stiffer_than_the_step_decays_without_overshoot(tmp_path):
    dynamics, inertia = horizontal_finger(tmp_path, damping=0.5, friction=0.0)
    assert 0.001 * 0.5 / inertia > 100  # an explicit step would multiply v by about -100
    state = np.array([0.0, 1.0])
    speeds = []
    for _ in range(20):
        dynamics.advance(state[:1].copy(), state[1:].copy(), np.zeros(1), state)
        speeds.append(state[1])
    assert all(0.0 <= b <= a for a, b in zip([1.0, *speeds], speeds, strict=False))
    assert speeds[-1] < 1e-12
    assert state[0] == pytest.approx(inertia / 0.5, rel=1e-9)  # it coasts v0 M / D, as exact


def test_projected_gauss_seidel_meets_the_friction_conditions():
    """The fallback friction solver (used when the active set cycles): every joint either
    sticks (no residual velocity, |p| within its bound) or slides at its bound in the
    direction of its residual, for coupled inertia matrices."""
    import numpy as np

    from txtool.simulation.plant import Dynamics

    solver = Dynamics.__new__(Dynamics)  # the solver uses no state of the plant
    rng = np.random.default_rng(7)
    for _ in range(50):
        n = int(rng.integers(2, 7))
        a = rng.normal(size=(n, n))
        G = a @ a.T + n * np.eye(n)  # symmetric positive definite, like M^-1 blocks
        w_free = rng.normal(scale=3.0, size=n)
        b = rng.uniform(0.1, 2.0, size=n)
        p = solver._gauss_seidel(G, w_free, b)
        w = w_free - G @ p
        assert np.all(np.abs(p) <= b + 1e-12)
        for i in range(n):
            if abs(p[i]) < b[i] - 1e-9:
                assert abs(w[i]) < 1e-8, (i, p, w)
            else:
                assert w[i] * np.sign(p[i]) >= -1e-8, (i, p, w)
