"""URDF joint limits mapped into actuator space."""

from __future__ import annotations

import pytest

from txtool.mechanics.limits import ActuatorLimit, actuator_limits
from txtool.mechanics.maps import from_parameters
from txtool.model.robot import JointInfo


def simple(reduction: float, offset: float = 0.0):  # type: ignore[no-untyped-def]
    return from_parameters("t", "simple", (reduction,), (1.0,), (offset,), joints=("j",),
                           actuators=("m",))


def test_beam_bots_motor_profile_example() -> None:
    joints = {"j": JointInfo("j", "revolute", -1.0, 2.0, velocity=3.0, effort=40.0)}
    (limit,) = actuator_limits(simple(10.0, 0.5), joints)
    assert limit == ActuatorLimit("m", (-15.0, 15.0), 30.0, 4.0)


def test_reversed_reduction_swaps_the_bounds() -> None:
    (limit,) = actuator_limits(simple(-1.0), {"j": JointInfo("j", "revolute", 0.0, 1.0)})
    assert limit.position == (-1.0, 0.0)
    assert str(limit.position[1]) == "0.0"  # not -0.0
    assert limit.velocity is None and limit.effort is None


def test_missing_joint_or_continuous_joint_has_no_position_limits() -> None:
    assert actuator_limits(simple(2.0), {}) == [ActuatorLimit("m", None, None, None)]
    (limit,) = actuator_limits(simple(-2.0), {"j": JointInfo("j", "continuous", velocity=1.5)})
    assert limit.position is None and limit.velocity == 3.0


def test_differential_worst_case_over_the_box() -> None:
    tmap = from_parameters("t", "differential", (10.0, -20.0), (-2.0, 4.0), (-2.0, 4.0),
                           joints=("p", "r"), actuators=("left", "right"))
    joints = {
        "p": JointInfo("p", "revolute", -3.0, 1.0, velocity=2.0, effort=50.0),
        "r": JointInfo("r", "revolute", 3.0, 5.0, velocity=4.0, effort=20.0),
    }
    left, right = actuator_limits(tmap, joints)
    # x_a0 = (-2 (p + 2) + 4 (r - 4)) * 10 over p in [-3, 1], r in [3, 5].
    assert left.position == pytest.approx((-100.0, 60.0))
    # x_a1 = (-2 (p + 2) - 4 (r - 4)) * -20
    assert right.position == pytest.approx((-120.0, 200.0))  # [-10, 6] * -20
    assert left.velocity == pytest.approx((2 * 2 + 4 * 4) * 10)
    assert right.velocity == pytest.approx((2 * 2 + 4 * 4) * 20)
    assert left.effort == pytest.approx((50 / 2 + 20 / 4) / 20)
    assert right.effort == pytest.approx((50 / 2 + 20 / 4) / 40)


def test_four_bar_first_actuator_depends_on_the_first_joint_only() -> None:
    tmap = from_parameters("t", "four_bar", (10.0, 10.0), (2.0, 2.0), (0.0, 0.0),
                           joints=("a", "b"), actuators=("m1", "m2"))
    joints = {
        "a": JointInfo("a", "revolute", 0.0, 1.0, velocity=1.0, effort=10.0),
        "b": JointInfo("b", "continuous", velocity=2.0),
    }
    m1, m2 = actuator_limits(tmap, joints)
    assert m1.position == (0.0, 20.0) and m1.velocity == 20.0
    assert m2.position is None  # needs b's position limits
    assert m2.velocity == pytest.approx(10.0 * (1.0 + 2.0 * 2.0))
    # ros2_control effort: e_a0 = (e_j0 - e_j1/2)/20 needs b's effort, e_a1 = e_j1/20 too.
    assert m1.effort is None and m2.effort is None
