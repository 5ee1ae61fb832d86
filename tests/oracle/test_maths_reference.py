"""The maps of ``txtool map`` and the equivalence check, bit for bit against ros2_control's and
ros_control's transmission classes (transmission_interface simple_transmission.hpp,
differential_transmission.hpp, four_bar_linkage_transmission.hpp, and ros_control's .h files),
on seeded cases with parameters and inputs across the range of a double."""

from __future__ import annotations

import math
import random

import pytest

from tests.oracle.reference import hex_float, oracle_dir, run_lines
from txtool.mechanics.maps import from_parameters

KINDS = ("simple", "differential", "four_bar")
QUANTITIES = {"a2j": ("position", "velocity", "effort"), "j2a": ("position", "velocity", "effort")}


def cases(count: int) -> list[tuple[str, str, list[float]]]:
    rng = random.Random(2026)
    spread = (1.0, 1e-3, 1e3, 1e-150, 1e150, 1e300)

    def value(nonzero: bool) -> float:
        x = rng.uniform(-10, 10) * rng.choice(spread)
        return x if (x != 0 or not nonzero) else 1.0

    found = []
    for index in range(count):
        kind = KINDS[index % 3]
        reductions = [value(True) for _ in range(4)]
        offsets = [value(False) for _ in range(2)]
        inputs = [value(False) for _ in range(12)]
        found.append((f"c{index}", kind, reductions + offsets + inputs))
    return found


def ours(kind: str, numbers: list[float], convention: str) -> dict[str, list[float]]:
    r, o, x = numbers[:4], numbers[4:6], numbers[6:]
    n = 1 if kind == "simple" else 2
    if kind == "simple":
        ar, jr = ((r[0],), (1.0,)) if convention == "ros1" else ((1.0,), (r[0],))
    else:
        ar, jr = (r[0], r[1]), (r[2], r[3])
    t = from_parameters("t", kind, ar, jr, tuple(o[:n]), convention=convention)
    ap, av, ae, jp, jv, je = (x[2 * i:2 * i + n] for i in range(6))
    out = {}
    for quantity, values in zip(QUANTITIES["a2j"], (ap, av, ae), strict=True):
        out[f"a2j.{quantity}"] = list(t.actuator_to_joint(quantity, values))
    for quantity, values in zip(QUANTITIES["j2a"], (jp, jv, je), strict=True):
        out[f"j2a.{quantity}"] = list(t.joint_to_actuator(quantity, values))
    return out


def theirs(line: str) -> dict[str, list[float]]:
    _, status, *fields = line.split()
    assert status == "OK", line
    return {k: [hex_float(v) for v in vs.split(",")]
            for k, vs in (f.split("=", 1) for f in fields)}


def bits(values: list[float]) -> list[str]:
    return ["nan" if math.isnan(v) else float.hex(float(v)) for v in values]


@pytest.mark.parametrize(("program", "convention"), [("maths_ros2", "ros2"),
                                                     ("maths_ros1", "ros1")])
def test_maps_agree_bit_for_bit(program: str, convention: str) -> None:
    oracle_dir()
    generated = cases(300)
    lines = [" ".join([name, kind, *(float.hex(v) for v in numbers)])
             for name, kind, numbers in generated]
    for (name, kind, numbers), line in zip(generated, run_lines(program, lines), strict=True):
        expected, got = theirs(line), ours(kind, numbers, convention)
        for key, values in got.items():
            assert bits(values) == bits(expected[key]), (name, kind, key, line)
