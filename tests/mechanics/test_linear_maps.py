"""The pure-Python linear maps the linter uses: A, determinant, condition, power conservation."""

from __future__ import annotations

import math
import subprocess
import sys

import numpy as np
import pytest

from txtool.mechanics import from_effective, linear
from txtool.model.semantics import Effective


def eff(kind: str, ar: tuple, jr: tuple, off: tuple | None = None) -> Effective:
    n = len(ar)
    return Effective(
        name="t",
        kind=kind,  # type: ignore[arg-type]
        joints=tuple(f"j{i}" for i in range(n)),
        actuators=tuple(f"a{i}" for i in range(n)),
        actuator_reduction=ar,
        joint_reduction=jr,
        joint_offset=off or (0.0,) * n,
        loader="ros2",
    )


def test_a_matrices_match_the_velocity_formulas() -> None:
    for kind in ("differential", "four_bar"):
        e = eff(kind, (10.0, -20.0), (-2.0, 4.0))
        a = np.array(linear.a_matrix(e))
        tmap = from_effective(e)
        qdot = np.array([[1.0, 0.0], [0.0, 1.0], [0.3, -0.7]])
        np.testing.assert_allclose(qdot @ a.T, tmap.joint_to_actuator("velocity", qdot),
                                   rtol=0, atol=1e-12)
        np.testing.assert_array_equal(a, tmap.A)


def test_simple_a_is_the_product_of_reductions() -> None:
    assert linear.a_matrix(eff("simple", (50.0,), (1.0,))) == [[50.0]]
    assert linear.a_matrix(eff("simple", (1.0,), (-3.0,))) == [[-3.0]]


def test_determinant_and_condition_agree_with_numpy() -> None:
    for kind in ("differential", "four_bar"):
        e = eff(kind, (10.0, -20.0), (-2.0, 4.0))
        a = np.array(linear.a_matrix(e))
        assert linear.determinant(linear.a_matrix(e)) == pytest.approx(np.linalg.det(a))
        assert linear.condition_number(e) == pytest.approx(np.linalg.cond(a), rel=1e-12)
    assert linear.condition_number(eff("simple", (7.0,), (1.0,))) == 1.0


def test_singular_reasons() -> None:
    assert linear.singular(eff("differential", (10.0, -20.0), (-2.0, 4.0))) is None
    zero = linear.singular(eff("differential", (10.0, 0.0), (1.0, 1.0)))
    assert zero == "actuator reduction of 'a1' is zero"
    assert linear.singular(eff("four_bar", (1.0, 1.0), (0.0, 1.0))) == (
        "joint reduction of 'j0' is zero"
    )
    assert linear.condition_number(eff("simple", (0.0,), (1.0,))) == math.inf
    # Products that underflow make A exactly singular although no reduction is zero.
    tiny = linear.singular(eff("differential", (1e-200, 1e-200), (1e-200, 1e-200)))
    assert tiny == "the velocity map A has determinant 0"
    ill = eff("differential", (1e-7, 1e7), (1.0, 1.0))
    assert linear.singular(ill) == "the velocity map A is ill-conditioned"
    assert linear.condition_number(ill) == pytest.approx(1e14)
    assert linear.singular(ill, max_condition=1e15) is None


def test_power_mismatch_flags_only_the_ros1_four_bar() -> None:
    for kind in ("differential", "four_bar"):
        e = eff(kind, (10.0, -20.0), (-2.0, 4.0))
        assert linear.power_mismatch(e, "ros2") == 0.0
    assert linear.power_mismatch(eff("simple", (5.0,), (1.0,)), "ros1") == 0.0
    assert linear.power_mismatch(eff("differential", (10.0, 10.0), (2.0, 2.0)), "ros1") == 0.0
    ros1 = linear.power_mismatch(eff("four_bar", (10.0, 10.0), (2.0, 2.0)), "ros1")
    # E^T - A = [[0, -40], [-10, 0]] relative to max|A| = 20.
    assert ros1 == pytest.approx(2.0)


def test_effort_matrix_matches_the_maps() -> None:
    for convention in ("ros2", "ros1"):
        e = eff("four_bar", (10.0, -20.0), (-2.0, 4.0))
        m = np.array(linear.effort_matrix("four_bar", e.actuator_reduction, e.joint_reduction,
                                          convention))
        tmap = from_effective(e, convention)
        tau_a = np.array([[3.0, 5.0], [1.0, 0.0], [0.0, 1.0]])
        np.testing.assert_allclose(tau_a @ m.T, tmap.actuator_to_joint("effort", tau_a),
                                   rtol=0, atol=1e-12)


def test_unknown_convention_is_rejected() -> None:
    with pytest.raises(ValueError, match="unknown effort convention 'ros3'"):
        linear.power_mismatch(eff("simple", (1.0,), (1.0,)), "ros3")


def test_linear_does_not_import_numpy() -> None:
    code = ("import sys; import txtool.mechanics.linear; import txtool.transform.bb.export; "
            "print('numpy' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"
