"""Numeric checks: invertibility, round trip across joint limits, power conservation."""

from __future__ import annotations

import numpy as np
import pytest

from txtool.mechanics import checks
from txtool.mechanics.maps import TransmissionMap, from_parameters
from txtool.model.core import Member, Number, Transmission
from txtool.model.robot import JointInfo


def num(value: float) -> Number:
    return Number(value=value, text=repr(value))


def test_standard_maps_pass_all_checks() -> None:
    joints = {"joint1": JointInfo("joint1", "revolute", -1.0, 2.0, 3.0, 40.0)}
    result = checks.check_map(from_parameters("t", "simple", (50.0,), (1.0,), (0.5,)), joints)
    assert result.status == "ok" and result.problems == ()
    assert result.round_trip is not None and result.round_trip.ok
    assert result.round_trip.samples == 9
    for kind in ("differential", "four_bar"):
        tmap = from_parameters("t", kind, (10.0, -20.0), (-2.0, 4.0), (-2.0, 4.0))
        result = checks.check_map(tmap)
        assert result.status == "ok", result.problems
        assert result.round_trip is not None and result.round_trip.samples == 81
        assert result.power_mismatch is not None and result.power_mismatch <= 1e-15


def test_ros1_four_bar_fails_power_conservation() -> None:
    tmap = from_parameters("t", "four_bar", (10.0, 10.0), (2.0, 2.0), (0.0, 0.0),
                           convention="ros1")
    result = checks.check_map(tmap)
    assert result.status == "failed"
    assert result.round_trip is not None and result.round_trip.ok
    assert len(result.problems) == 1
    assert result.problems[0].startswith("the ros1 effort map does not conserve power")


def test_samples_follow_joint_limits() -> None:
    tmap = from_parameters("t", "simple", (2.0,), (1.0,), (0.0,), joints=("j",))
    limited = {"j": JointInfo("j", "revolute", -0.5, 1.5, 2.0, 7.0)}
    samples = checks.sample_joint_values(tmap, limited, per_axis=5)
    np.testing.assert_allclose(samples["position"][:, 0], [-0.5, 0.0, 0.5, 1.0, 1.5])
    np.testing.assert_allclose(samples["velocity"][[0, -1], 0], [-2.0, 2.0])
    np.testing.assert_allclose(samples["effort"][[0, -1], 0], [-7.0, 7.0])
    free = checks.sample_joint_values(tmap, {"j": JointInfo("j", "continuous")}, per_axis=3)
    np.testing.assert_allclose(free["position"][:, 0], [-np.pi, 0.0, np.pi])


def test_round_trip_detects_a_broken_inverse() -> None:
    class Broken(TransmissionMap):
        def actuator_to_joint(self, quantity: str, values):  # type: ignore[no-untyped-def]
            return super().actuator_to_joint(quantity, values) * (1 + 1e-9)

    tmap = Broken("t", "simple", ("j",), ("a",), np.array([[3.0]]), np.array([0.0]))
    trip = checks.round_trip(tmap)
    assert not trip.ok
    assert trip.errors["velocity"] == pytest.approx(1e-9, rel=1e-3)


def test_invertibility_of_an_ill_conditioned_map() -> None:
    tmap = from_parameters("t", "differential", (1e-7, 1e7), (1.0, 1.0), (0.0, 0.0))
    inv = checks.invertibility(tmap)
    assert inv.condition_number == pytest.approx(1e14)
    assert inv.reason == "the velocity map A is ill-conditioned"
    result = checks.check_map(tmap)
    assert result.status == "failed"
    assert result.problems[0] == "the velocity map A is ill-conditioned (condition number 1e+14)"


def test_check_all_reports_not_loadable() -> None:
    good = Transmission(
        name="ok", type="transmission_interface/SimpleTransmission", kind="simple",
        joints=(Member(name="j"),), actuators=(Member(name="a", mechanical_reduction=num(5.0)),),
        dialect="ros1",
    )
    custom = Transmission(name="odd", type="my/Custom", kind="other", dialect="ros1")
    results = checks.check_all([good, custom])
    assert [(r.name, r.status) for r in results] == [("ok", "ok"), ("odd", "not loadable")]
    assert results[1].problems == ("custom type 'my/Custom' has no standard maths",)
