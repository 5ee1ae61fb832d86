"""The model: gravity through a transmission, rnea against the analytic 2-link arm, rotor terms."""

from __future__ import annotations

import math

import numpy as np
import pinocchio as pin
import pytest

from tests.simulate.robots import arm_ros1, pendulum, planar_two_link, with_transmission, write
from txtool.io.load import load
from txtool.mechanics.inertia import reflected_inertia
from txtool.simulation.model import build
from txtool.simulation.run import Options, prepare, simulate_one

G = 9.81


def test_pendulum_holding_torque_at_joint_and_actuator(tmp_path):
    mass, length, n = 2.0, 0.5, 40.0
    robot = write(tmp_path, "pendulum.urdf", pendulum(mass, length, n))
    hold = write(tmp_path, "hold.csv", "time,swing\n0,0\n")
    run = simulate_one(Options(robot=robot, trajectory=hold, duration=0.5), None)
    assert run.passed, run.reasons
    actuator = run.series.effort[-1, 0]
    joint = actuator * n
    assert joint == pytest.approx(mass * G * length, rel=0.01)
    assert actuator == pytest.approx(mass * G * length / n, rel=0.01)
    assert run.joints["swing"].max_error < 1e-6


def test_pendulum_reversed_reduction_reverses_the_actuator_effort(tmp_path):
    robot = write(tmp_path, "pendulum.urdf", pendulum(1.0, 0.4, -25.0))
    hold = write(tmp_path, "hold.csv", "time,swing\n0,0\n")
    run = simulate_one(Options(robot=robot, trajectory=hold, duration=0.3), None)
    assert run.passed, run.reasons
    assert run.series.effort[-1, 0] == pytest.approx(-1.0 * G * 0.4 / 25.0, rel=0.01)


def analytic_two_link(q, qd, qdd, m1, m2, l1, lc1, lc2, i1, i2):
    c2, s2 = math.cos(q[1]), math.sin(q[1])
    m11 = m1 * lc1**2 + i1 + m2 * (l1**2 + lc2**2 + 2 * l1 * lc2 * c2) + i2
    m12 = m2 * (lc2**2 + l1 * lc2 * c2) + i2
    m22 = m2 * lc2**2 + i2
    h = m2 * l1 * lc2 * s2
    coriolis = np.array([-h * (2 * qd[0] * qd[1] + qd[1] ** 2), h * qd[0] ** 2])
    gravity = np.array([
        (m1 * lc1 + m2 * l1) * G * math.cos(q[0]) + m2 * lc2 * G * math.cos(q[0] + q[1]),
        m2 * lc2 * G * math.cos(q[0] + q[1]),
    ])
    mass = np.array([[m11, m12], [m12, m22]])
    return mass @ qdd + coriolis + gravity


def test_rnea_matches_the_analytic_two_link_arm(tmp_path):
    p = dict(m1=1.3, m2=0.7, l1=0.6, lc1=0.25, lc2=0.2, i1=0.02, i2=0.008)
    robot = build(load(write(tmp_path, "planar.urdf", planar_two_link(**p))))
    model = robot.model
    model.gravity.linear = np.array([0.0, 0.0, -G])
    data = model.createData()
    rng = np.random.default_rng(7)
    for _ in range(20):
        q, qd, qdd = rng.uniform(-2, 2, 2), rng.uniform(-3, 3, 2), rng.uniform(-5, 5, 2)
        expected = analytic_two_link(q, qd, qdd, **p)
        assert np.allclose(pin.rnea(model, data, q, qd, qdd), expected, atol=1e-9)


def test_continuous_configuration_is_pinocchio_integrate(tmp_path):
    text = planar_two_link(1, 1, 0.5, 0.2, 0.2, 0.01, 0.01).replace(
        'name="q2" type="revolute"', 'name="q2" type="continuous"')
    robot = build(load(write(tmp_path, "c.urdf", text)))
    assert robot.kinds == ("revolute", "continuous") and robot.model.nq == 3
    x = np.array([0.3, 7.5])
    expected = pin.integrate(robot.model, pin.neutral(robot.model), x)
    assert np.allclose(robot.config(x), expected, atol=1e-12)


def test_continuous_joint_tracks(tmp_path):
    text = planar_two_link(1, 1, 0.5, 0.2, 0.2, 0.01, 0.01).replace(
        'name="q2" type="revolute"', 'name="q2" type="continuous"')
    text = with_transmission(text, "q2")
    run = simulate_one(Options(robot=write(tmp_path, "c.urdf", text), duration=3.0), None)
    assert run.passed, run.reasons
    assert run.joints["q2"].limit_margin is None
    assert np.ptp(run.series.q_ref[:, 1]) == pytest.approx(1.0)  # 25%..75% of +-1 rad


def test_rotor_inertia_is_armature_for_simple_and_a_block_for_differential(tmp_path):
    params = write(tmp_path, "p.toml", """
[actuators.m_shoulder]
rotor_inertia = 2e-5
[actuators.m_left]
rotor_inertia = 1e-5
[actuators.m_right]
rotor_inertia = 3e-5
""")
    p = prepare(Options(robot=write(tmp_path, "arm.urdf", arm_ros1()), params=params), None)
    plant_model = p.plan.plant
    # the plant's armature also carries dt * damping: the implicit damping term (shoulder 0.05)
    h = p.plan.dt / p.plan.dynamics.substeps
    assert plant_model.armature[0] == pytest.approx(2e-5 * 50**2 + h * 0.05)
    wrist = next(m for m in p.plant.maps if m.name == "t_wrist")
    block = reflected_inertia(wrist, [1e-5, 3e-5])
    assert np.allclose(plant_model.armature[1:], np.diag(block))
    assert p.plan.plant_block is not None
    assert p.plan.plant_block[1, 2] == pytest.approx(block[0, 1]) and block[0, 1] != 0
    run = simulate_one(Options(robot=p.options.robot, params=params), None)
    assert run.passed, run.reasons


def test_drake_rotor_inertia_tag_is_read(tmp_path):
    text = arm_ros1().replace(
        '<actuator name="m_shoulder">',
        '<actuator name="m_shoulder"><drake:rotor_inertia value="4e-5"/>'
        '<drake:gear_ratio value="60"/>')
    p = prepare(Options(robot=write(tmp_path, "arm.urdf", text)), None)
    assert p.plan.ctrl.armature[0] == pytest.approx(4e-5 * 50**2)
    run = simulate_one(Options(robot=p.options.robot, duration=0.5), None)
    assert any("drake:gear_ratio 60 differs" in note for note in run.notes)


def test_mimic_joint_follows_its_leader(tmp_path):
    text = planar_two_link(1, 0.5, 0.5, 0.2, 0.2, 0.01, 0.01).replace(
        "<limit lower=\"-3\" upper=\"3\" effort=\"100\" velocity=\"5\"/></joint>\n</robot>",
        '<limit lower="-3" upper="3" effort="100" velocity="5"/>'
        '<mimic joint="q1" multiplier="0.5"/></joint>\n</robot>')
    text = with_transmission(text, "q1")
    run = simulate_one(Options(robot=write(tmp_path, "m.urdf", text)), None)
    assert run.passed, run.reasons
    assert list(run.joints) == ["q1"]
    assert any("mimic" in note for note in run.notes)
