"""The equivalence check maps its samples in plain Python floats (``roundtrip`` then never
imports numpy); numpy's maps are the reference, bit for bit, overflow and underflow included."""

from __future__ import annotations

import math
import sys

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from txtool.mechanics.equivalence import _Loaded
from txtool.mechanics.formulas import FORMULAS, formula_key
from txtool.mechanics.maps import from_effective
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
        return  # numpy's inf or nan: the equivalence check maps such a case with numpy
    assert all(same_bits(x, y) for a, b in zip(ours_back, back, strict=True)
               for x, y in zip(a, b, strict=True))


def test_an_underflowing_reduction_falls_back_to_numpy_s_infinities():
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
