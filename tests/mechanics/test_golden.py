"""The test vectors of ros2_control / ros_control's transmission tests, both directions."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from txtool.mechanics import ZeroReduction, from_effective, from_parameters
from txtool.model.semantics import Effective

TOL = 1e-12


def close(actual: np.ndarray, expected: list[float]) -> None:
    np.testing.assert_allclose(actual, expected, rtol=0, atol=TOL)


# --- simple ---------------------------------------------------------------------------------


@pytest.mark.parametrize("quantity", ["effort", "torque", "force"])
def test_simple_effort_and_aliases(quantity: str) -> None:
    m = from_parameters("t", "simple", (10.0,), (1.0,), (1.0,))
    close(m.actuator_to_joint(quantity, [1.0]), [10.0])
    close(m.joint_to_actuator(quantity, [10.0]), [1.0])


def test_simple_velocity_position_absolute_position() -> None:
    m = from_parameters("t", "simple", (10.0,), (1.0,), (1.0,))
    close(m.actuator_to_joint("velocity", [1.0]), [0.1])
    close(m.actuator_to_joint("position", [1.0]), [1.1])
    close(m.actuator_to_joint("absolute_position", [1.0]), [1.1])
    close(m.joint_to_actuator("velocity", [0.1]), [1.0])
    close(m.joint_to_actuator("position", [1.1]), [1.0])


def test_simple_reduction_may_sit_on_joint_or_actuator() -> None:
    ros1 = from_parameters("t", "simple", (10.0,), (1.0,), (1.0,))
    ros2 = from_parameters("t", "simple", (1.0,), (10.0,), (1.0,))
    x = np.linspace(-3, 3, 7)[:, None]
    for quantity in ("position", "velocity", "effort"):
        close(ros2.joint_to_actuator(quantity, x), ros1.joint_to_actuator(quantity, x))


@pytest.mark.parametrize("n", [10.0, -10.0])
@pytest.mark.parametrize("off", [0.0, 1.0, -1.0])
@pytest.mark.parametrize("quantity", ["position", "velocity", "effort"])
def test_simple_identity_round_trip(n: float, off: float, quantity: str) -> None:
    m = from_parameters("t", "simple", (n,), (1.0,), (off,))
    x = np.array([[1.0], [-1.0], [0.0]])
    close(m.actuator_to_joint(quantity, m.joint_to_actuator(quantity, x)), x)
    close(m.joint_to_actuator(quantity, m.actuator_to_joint(quantity, x)), x)


def test_simple_absolute_position_has_no_inverse() -> None:
    m = from_parameters("t", "simple", (10.0,), (1.0,), (0.0,))
    with pytest.raises(ValueError, match="absolute_position"):
        m.joint_to_actuator("absolute_position", [1.0])


# --- differential ---------------------------------------------------------------------------

DIFFERENTIAL = [
    # ar, jr, off, actuator in, effort j, velocity j, position j
    ((10, 10), (2, 2), (1, 1), (0, 0), (0, 0), (0, 0), (1, 1)),
    ((10, 10), (2, 2), (0, 0), (10, 10), (400, 0), (0.5, 0), (0.5, 0)),
    ((10, 10), (2, 2), (0, 0), (10, -10), (0, 400), (0, 0.5), (0, 0.5)),
    ((10, -20), (-2, 4), (-2, 4), (3, 5), (140, 520), (-0.0125, 0.06875), (-2.0125, 4.06875)),
]


@pytest.mark.parametrize(("ar", "jr", "off", "a_in", "eff", "vel", "pos"), DIFFERENTIAL)
def test_differential_forward(ar, jr, off, a_in, eff, vel, pos) -> None:  # type: ignore[no-untyped-def]
    m = from_parameters("t", "differential", ar, jr, off)
    for quantity in ("effort", "torque", "force"):
        close(m.actuator_to_joint(quantity, a_in), eff)
    close(m.actuator_to_joint("velocity", a_in), vel)
    close(m.actuator_to_joint("position", a_in), pos)
    close(m.actuator_to_joint("absolute_position", a_in), pos)


@pytest.mark.parametrize(("ar", "jr", "off", "a_in", "eff", "vel", "pos"), DIFFERENTIAL)
def test_differential_inverse(ar, jr, off, a_in, eff, vel, pos) -> None:  # type: ignore[no-untyped-def]
    m = from_parameters("t", "differential", ar, jr, off)
    close(m.joint_to_actuator("effort", eff), a_in)
    close(m.joint_to_actuator("velocity", vel), a_in)
    close(m.joint_to_actuator("position", pos), a_in)


def test_differential_inverse_of_reference_case() -> None:
    m = from_parameters("t", "differential", (10, -20), (-2, 4), (-2, 4))
    close(m.joint_to_actuator("position", [-2.0125, 4.06875]), [3, 5])
    close(m.joint_to_actuator("effort", [140, 520]), [3, 5])


# --- four-bar -------------------------------------------------------------------------------

FOUR_BAR = [
    # ar, jr, off, effort a in, effort j ros2, effort j ros1, vel/pos a in, vel j, pos j
    ((10, 10), (2, 2), (1, 1), (0, 0), (0, 0), (0, 0), (0, 0), (0, 0), (1, 1)),
    ((10, 10), (2, 2), (0, 0), (5, 10), (200, 200), (100, 0), (10, 5), (0.5, 0), (0.5, 0)),
    ((10, 10), (2, 2), (0, 0), (0, 10), (100, 200), (0, 200), (0, 10), (0, 0.5), (0, 0.5)),
    ((10, -20), (-2, 4), (-2, 4), (3, 5), (-160, -400), (-60, -160), (3, 5), (-0.15, -0.025),
     (-2.15, 3.975)),
]
FB_ARGS = ("ar", "jr", "off", "ea", "ej2", "ej1", "xa", "vj", "pj")


@pytest.mark.parametrize(FB_ARGS, FOUR_BAR)
def test_four_bar_forward(ar, jr, off, ea, ej2, ej1, xa, vj, pj) -> None:  # type: ignore[no-untyped-def]
    ros2 = from_parameters("t", "four_bar", ar, jr, off)
    ros1 = from_parameters("t", "four_bar", ar, jr, off, convention="ros1")
    close(ros2.actuator_to_joint("effort", ea), ej2)
    close(ros1.actuator_to_joint("effort", ea), ej1)
    for m in (ros1, ros2):
        close(m.actuator_to_joint("velocity", xa), vj)
        close(m.actuator_to_joint("position", xa), pj)


@pytest.mark.parametrize(FB_ARGS, FOUR_BAR)
def test_four_bar_inverse(ar, jr, off, ea, ej2, ej1, xa, vj, pj) -> None:  # type: ignore[no-untyped-def]
    ros2 = from_parameters("t", "four_bar", ar, jr, off)
    ros1 = from_parameters("t", "four_bar", ar, jr, off, convention="ros1")
    close(ros2.joint_to_actuator("effort", ej2), ea)
    close(ros1.joint_to_actuator("effort", ej1), ea)
    for m in (ros1, ros2):
        close(m.joint_to_actuator("velocity", vj), xa)
        close(m.joint_to_actuator("position", pj), xa)


def test_four_bar_inverse_of_reference_case() -> None:
    ros2 = from_parameters("t", "four_bar", (10, -20), (-2, 4), (-2, 4))
    ros1 = from_parameters("t", "four_bar", (10, -20), (-2, 4), (-2, 4), convention="ros1")
    close(ros2.joint_to_actuator("effort", [-160, -400]), [3, 5])
    close(ros1.joint_to_actuator("effort", [-60, -160]), [3, 5])
    close(ros2.joint_to_actuator("position", [-2.15, 3.975]), [3, 5])


# --- construction ---------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("kind", "ar", "jr"),
    [
        ("simple", (0.0,), (1.0,)),
        ("simple", (1.0,), (0.0,)),
        ("differential", (0.0, 0.0), (1.0, 1.0)),
        ("differential", (1.0, 0.0), (1.0, 1.0)),
        ("four_bar", (1.0, 1.0), (0.0, 1.0)),
        ("four_bar", (1.0, 1.0), (1.0, 0.0)),
    ],
)
def test_zero_reduction_names_the_transmission(kind: str, ar: tuple, jr: tuple) -> None:
    off = (0.0,) * len(ar)
    with pytest.raises(ZeroReduction, match="transmission 'wrist'.*cannot be zero") as info:
        from_parameters("wrist", kind, ar, jr, off)
    assert isinstance(info.value, ValueError)


def test_from_effective_zero_reduction() -> None:
    eff = Effective("elbow", "simple", ("j",), ("a",), (0.0,), (1.0,), (0.0,), "ros1")
    with pytest.raises(ZeroReduction, match="'elbow'"):
        from_effective(eff)


def test_vectorised_shapes() -> None:
    m = from_parameters("t", "differential", (10, -20), (-2, 4), (-2, 4))
    batch = np.tile([3.0, 5.0], (4, 3, 1))
    out = m.actuator_to_joint("position", batch)
    assert out.shape == (4, 3, 2)
    close(out.reshape(-1, 2), [[-2.0125, 4.06875]] * 12)
    with pytest.raises(ValueError, match="2 value"):
        m.actuator_to_joint("position", [1.0, 2.0, 3.0])
    with pytest.raises(ValueError, match="cannot map 'speed'"):
        m.joint_to_actuator("speed", [1.0, 2.0])


# --- property: joint -> actuator -> joint is the identity -----------------------------------

reduction = st.floats(0.05, 200.0).flatmap(lambda v: st.sampled_from([v, -v]))
offset = st.floats(-5.0, 5.0)
value = st.floats(-10.0, 10.0)


@settings(max_examples=150, deadline=None)
@given(
    kind=st.sampled_from(["simple", "differential", "four_bar"]),
    convention=st.sampled_from(["ros2", "ros1"]),
    quantity=st.sampled_from(["position", "velocity", "effort", "torque", "force"]),
    ar=st.tuples(reduction, reduction),
    jr=st.tuples(reduction, reduction),
    off=st.tuples(offset, offset),
    x=st.tuples(value, value),
)
def test_round_trip_is_identity(kind, convention, quantity, ar, jr, off, x) -> None:  # type: ignore[no-untyped-def]
    n = 1 if kind == "simple" else 2
    m = from_parameters("t", kind, ar[:n], jr[:n], off[:n], convention=convention)
    joint = np.array(x[:n])
    back = m.actuator_to_joint(quantity, m.joint_to_actuator(quantity, joint))
    scale = max(1.0, *np.abs(joint), *np.abs(off[:n]))
    np.testing.assert_allclose(back, joint, rtol=0, atol=1e-12 * scale)


def test_a_given_directly_must_have_the_kind_structure() -> None:
    from txtool.mechanics import TransmissionMap

    ok = TransmissionMap("t", "four_bar", ("a", "b"), ("m", "n"), np.array([[-20.0, 0.0],
                         [-20.0, -80.0]]), np.array([-2.0, 4.0]))
    close(ok.actuator_to_joint("position", [3, 5]), [-2.15, 3.975])
    with pytest.raises(ValueError, match="structure of a four_bar"):
        TransmissionMap("t", "four_bar", ("a", "b"), ("m", "n"), np.eye(2) + 1, np.zeros(2))
    with pytest.raises(ValueError, match="structure of a differential"):
        TransmissionMap("t", "differential", ("a", "b"), ("m", "n"), np.eye(2) + 1, np.zeros(2))
