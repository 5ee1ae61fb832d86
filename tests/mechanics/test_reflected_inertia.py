"""Rotor inertia reflected into joint space: A^T diag(J) A."""

from __future__ import annotations

import numpy as np
import pytest

from txtool.mechanics import TransmissionMap, from_parameters, reflected_inertia


def test_simple_is_j_n_squared() -> None:
    for n in (50.0, -50.0):
        tmap = from_parameters("t", "simple", (n,), (1.0,), (0.3,))
        np.testing.assert_allclose(reflected_inertia(tmap, [2e-5]), [[2e-5 * 2500]], rtol=1e-15)


def test_coupled_example_has_off_diagonal_terms() -> None:
    tmap = TransmissionMap("t", "differential", ("a", "b"), ("m1", "m2"),
                           np.array([[50.0, 50.0], [40.0, -40.0]]), np.zeros(2))
    m = reflected_inertia(tmap, [1e-5, 2e-5])
    np.testing.assert_allclose(m, [[0.057, -0.007], [-0.007, 0.057]], rtol=0, atol=1e-15)


def test_matches_the_kinetic_energy_of_the_rotors() -> None:
    tmap = from_parameters("t", "four_bar", (10.0, -20.0), (-2.0, 4.0), (0.0, 0.0))
    j = np.array([3e-5, 7e-5])
    qdot = np.array([0.4, -1.3])
    qdot_a = tmap.joint_to_actuator("velocity", qdot)
    energy = 0.5 * qdot @ reflected_inertia(tmap, j) @ qdot
    assert energy == pytest.approx(0.5 * np.sum(j * qdot_a**2), rel=1e-14)


def test_scalar_inertia_and_wrong_length() -> None:
    tmap = from_parameters("t", "differential", (10.0, 10.0), (1.0, 1.0), (0.0, 0.0))
    np.testing.assert_allclose(reflected_inertia(tmap, 1e-4),
                               reflected_inertia(tmap, [1e-4, 1e-4]))
    with pytest.raises(ValueError, match="2 actuator"):
        reflected_inertia(tmap, [1e-4, 1e-4, 1e-4])
