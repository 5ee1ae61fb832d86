"""The equivalence check maps its samples in plain Python floats (``roundtrip`` then never
imports numpy); numpy's maps are the reference, bit for bit, overflow and underflow included."""

from __future__ import annotations

import math
import sys

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from txtool.mechanics import points
from txtool.mechanics.equivalence import _Loaded
from txtool.mechanics.formulas import FORMULAS, formula_key, read_parameters
from txtool.mechanics.maps import from_effective
from txtool.mechanics.points import ZeroReduction
from txtool.mechanics.samples import axis, joint_samples
from txtool.model.robot import JointInfo
from txtool.model.semantics import Effective

EXTREME = st.sampled_from([1e-200, -1e-200, 1e200, 1e308, -1e308, 5e-324, 1e-160, 0.5, 50.0])
NONZERO = st.one_of(
    EXTREME,
    st.floats(allow_nan=False, allow_infinity=False, min_value=-1e6, max_value=1e6)
    .filter(lambda x: x != 0.0),
)
FINITE = st.one_of(EXTREME, st.floats(allow_nan=False, allow_infinity=False))


@st.composite
def loaded(draw):
    kind = draw(st.sampled_from(["simple", "differential", "four_bar"]))
    n = 1 if kind == "simple" else 2
    names = ("a", "b")[:n]
    eff = Effective("t", kind, names, tuple(f"m{x}" for x in names),
                    tuple(draw(NONZERO) for _ in range(n)), tuple(draw(NONZERO) for _ in range(n)),
                    tuple(draw(FINITE) for _ in range(n)), "ros2")
    return _Loaded(eff, draw(st.sampled_from(["ros2", "ros1"])))


def same_bits(x: float, y: float) -> bool:
    return (math.isnan(x) and math.isnan(y)) or (x == y and math.copysign(1, x) ==
                                                 math.copysign(1, y))


@settings(max_examples=300, deadline=None)
@given(loaded(), st.sampled_from(["position", "velocity", "effort", "torque"]),
       st.lists(st.tuples(FINITE, FINITE), min_size=1, max_size=5))
def test_python_floats_map_as_numpy_does(load, quantity, pairs):
    rows = [row[: len(load.joints)] for row in pairs]
    ours = load.joint_to_actuator(quantity, rows)
    numpy_map = from_effective(load.eff, load.convention)
    with np.errstate(all="ignore"):
        reference = numpy_map.joint_to_actuator(quantity, np.array(rows)).tolist()
        back = numpy_map.actuator_to_joint(quantity, np.array(rows)).tolist()
    assert all(same_bits(x, y) for a, b in zip(ours, reference, strict=True)
               for x, y in zip(a, b, strict=True))
    aj = FORMULAS[formula_key(load.eff.kind, quantity, load.convention)][0]
    eff = load.eff
    try:
        ours_back = [aj(row, eff.actuator_reduction, eff.joint_reduction, eff.joint_offset)
                     for row in rows]
    except ZeroDivisionError:
        return  # the equivalence check maps such a case with IEEE division (points)
    assert all(same_bits(x, y) for a, b in zip(ours_back, back, strict=True)
               for x, y in zip(a, b, strict=True))


@settings(max_examples=300, deadline=None)
@given(loaded(), loaded(), st.lists(st.tuples(FINITE, FINITE), min_size=1, max_size=5))
def test_parameters_read_alike_map_every_value_alike(load, other, pairs):
    """The equivalence check maps no samples where both sides read the same parameters: a
    simple transmission's reduction moved from the actuator (ROS 1) to the joint (ROS 2)
    reads alike, and two sides that read alike must map every value to the same bits."""
    eff = load.eff
    moved = Effective(eff.name, eff.kind, eff.joints, eff.actuators,
                      (1.0,) * len(eff.joints), tuple(a * j for a, j in zip(
                          eff.actuator_reduction, eff.joint_reduction, strict=True)),
                      eff.joint_offset, "ros1")
    assume(0.0 not in moved.joint_reduction)  # a product that underflows loads nowhere
    assert eff.kind != "simple" or reads(eff) == reads(moved)
    rows = [row[: len(load.joints)] for row in pairs]
    for second in (moved, other.eff):
        if second.kind != eff.kind or reads(second) != reads(eff):
            continue
        for quantity in ("position", "velocity", "effort"):
            ours = load.joint_to_actuator(quantity, rows)
            theirs = _Loaded(second, load.convention).joint_to_actuator(quantity, rows)
            assert all(same_bits(x, y) for a, b in zip(ours, theirs, strict=True)
                       for x, y in zip(a, b, strict=True))


def reads(eff: Effective) -> tuple:
    return read_parameters(eff.kind, eff.actuator_reduction, eff.joint_reduction,
                           eff.joint_offset)


@settings(max_examples=300, deadline=None)
@given(loaded(), st.sampled_from(["position", "velocity", "effort", "absolute_position"]),
       st.tuples(FINITE, FINITE), st.booleans())
def test_point_maps_give_numpy_s_bits_both_ways_division_by_zero_included(load, quantity,
                                                                            pair, to_joint):
    """map and show --actuator-limits compute with txtool.mechanics.points (no numpy)."""
    row = pair[: len(load.joints)]
    maps = points.from_effective(load.eff, load.convention)
    numpy_map = from_effective(load.eff, load.convention)
    if to_joint:
        ours = maps.actuator_to_joint(quantity, row)
        with np.errstate(all="ignore"):
            reference = numpy_map.actuator_to_joint(quantity, np.array(row)).tolist()
    else:
        if quantity == "absolute_position":
            quantity = "position"
        ours = maps.joint_to_actuator(quantity, row)
        with np.errstate(all="ignore"):
            reference = numpy_map.joint_to_actuator(quantity, np.array(row)).tolist()
    assert all(same_bits(x, y) for x, y in zip(ours, reference, strict=True))


@pytest.mark.parametrize(("a", "b", "expected"), [
    (1.0, 0.0, math.inf), (-1.0, 0.0, -math.inf), (1.0, -0.0, -math.inf),
    (-2.0, -0.0, math.inf), (0.0, 0.0, math.nan), (math.nan, 0.0, math.nan),
    (math.inf, -0.0, -math.inf), (3.0, 2.0, 1.5),
])
def test_ieee_division(a, b, expected):
    with np.errstate(all="ignore"):
        assert same_bits(points.divide(a, b), expected)
        assert same_bits(points.divide(a, b), float(np.float64(a) / np.float64(b)))
    assert same_bits(points.IEEE(a) / b, expected) and same_bits(a / points.IEEE(b), expected)


def test_ieee_arithmetic_stays_ieee():
    x = points.IEEE(2.0)
    for value in (x + 1, 1 + x, x - 1, 1 - x, x * 3, 3 * x, x / 2, 2 / x, -x, 2.0 * x):
        assert type(value) is points.IEEE
    assert (1 - x, 2 / x, -x) == (-1.0, 1.0, -2.0)


def test_a_zero_reduction_is_not_loadable_in_point_maps():
    eff = Effective("t", "simple", ("a",), ("m",), (0.0,), (1.0,), (0.0,), "ros2")
    with pytest.raises(ZeroReduction, match="reduction ratio cannot be zero"):
        points.from_effective(eff)
    maps = points.from_effective(
        Effective("t", "simple", ("a",), ("m",), (2.0,), (1.0,), (0.0,), "ros2"))
    with pytest.raises(ValueError, match="maps 1 value"):
        maps.joint_to_actuator("position", (1.0, 2.0))
    with pytest.raises(ValueError, match="cannot map 'absolute_position' from joint"):
        maps.joint_to_actuator("absolute_position", (1.0,))
    with pytest.raises(ValueError, match="cannot map 'mass' from actuator"):
        maps.actuator_to_joint("mass", (1.0,))


def test_an_underflowing_reduction_gives_numpy_s_infinities():
    eff = Effective("t", "simple", ("a",), ("m",), (1e-200,), (1e-200,), (0.0,), "ros2")
    # 1e-200 * 1e-200 is 0.0: Python refuses to divide by it, numpy gives inf and nan
    mapped = _Loaded(eff, "ros2").joint_to_actuator("effort", [(2.0,), (-1.0,), (0.0,)])
    assert mapped[:2] == [(math.inf,), (-math.inf,)]
    assert math.isnan(mapped[2][0])


@given(st.one_of(EXTREME, st.floats(allow_nan=False, width=64)),
       st.one_of(EXTREME, st.floats(allow_nan=False, width=64)),
       st.integers(min_value=2, max_value=9))
def test_sample_axes_are_numpy_s_linspace(lo, hi, count):
    ours = axis(lo, hi, count)
    with np.errstate(all="ignore"):
        if math.isfinite(hi - lo):
            reference = np.linspace(lo, hi, count).tolist()
        else:
            t = np.linspace(0.0, 1.0, count)
            reference = (lo * (1.0 - t) + hi * t).tolist()
    assert all(same_bits(x, y) for x, y in zip(ours, reference, strict=True))


def test_a_denormal_range_takes_numpy_s_careful_steps():
    tiny = sys.float_info.min * sys.float_info.epsilon  # 5e-324
    assert axis(0.0, 2 * tiny, 3) == np.linspace(0.0, 2 * tiny, 3).tolist()


def test_samples_span_each_joint_s_limits():
    joints = {"a": JointInfo("a", "revolute", -1.0, 2.0, 3.0, 4.0)}
    grids = joint_samples(("a", "b"), joints, per_axis=3)
    assert grids["position"][:3] == [(-1.0, -math.pi), (-1.0, 0.0), (-1.0, math.pi)]
    assert {v[0] for v in grids["velocity"]} == {-3.0, 0.0, 3.0}
    assert {v[1] for v in grids["effort"]} == {-1.0, 0.0, 1.0}
