"""Numbers exactly as the loaders read them, and no "internal error" on any spelling.

ros_control (ROS 1) converts with ``std::stod`` (transmission_interface/src/
transmission_loader.cpp, ``TransmissionLoader::checkActuatorMemberSpecs`` and the loaders'
``getActuatorReduction``: ``std::stod(reduction_el->GetText())`` inside a ``catch`` of
``std::logic_error``); ros2_control through ``hardware_interface::stod``
(hardware_interface/src/lexical_casts.cpp, ``impl::stod``: ``istringstream`` below C++20,
``from_chars`` after one leading ``+`` is dropped from C++20).
"""

from __future__ import annotations

import math
import random

import pytest
from click.testing import CliRunner

from tests.oracle.reference import oracle_dir, run_lines
from tests.oracle.variants import NUMBERS
from txtool.cli import cli
from txtool.model.distro import NumberReading
from txtool.model.numbers import parse_ros2, ros2_readings, stod

HUMBLE, JAZZY = NumberReading.ISTRINGSTREAM, NumberReading.FROM_CHARS


@pytest.mark.parametrize(("text", "humble", "jazzy"), [
    ("2", 2.0, 2.0),
    ("+2", 2.0, 2.0),
    (" \t2\n", 2.0, 2.0),
    ("\v2\f", 2.0, 2.0),          # both strip C whitespace first (ros2_control::strip)
    ("+-1", None, -1.0),          # from_chars after the one '+' is dropped
    ("++1", None, None),
    ("1e-400", 0.0, None),        # istringstream keeps an underflow, from_chars refuses it
    ("1e-310", 1e-310, 1e-310),   # a subnormal is read by both
    ("1e400", None, None),
    ("0x1p3", None, None),        # neither reads hexadecimal
    ("inf", None, None),
    ("nan", None, None),
    ("2abc", None, None),
    ("1.", 1.0, 1.0),
    (".5", 0.5, 0.5),
    ("\u00a02", None, None),      # a no-break space is no C space
])
def test_ros2_numbers_per_distribution(text, humble, jazzy):
    assert ros2_readings(text) == {HUMBLE: humble, JAZZY: jazzy}
    assert parse_ros2(text) == (humble if humble == jazzy else None)


@pytest.mark.parametrize(("text", "value", "read"), [
    ("-inf", -math.inf, "-inf"),
    ("+infinity", math.inf, "+infinity"),
    ("0x1p-1074", 5e-324, "0x1p-1074"),                          # exact subnormal: no ERANGE
    ("0x1.0p3junk", 8.0, "0x1.0p3"),
])
def test_stod_reads_a_prefix(text, value, read):
    assert (stod(text).value, stod(text).read) == (value, read)


@pytest.mark.parametrize("text", [
    "0x1p99999999999999999999", "-0x1p99999999999999999999", "1e99999999999999999999",
    "2.2250738585072011e-308",   # subnormal and inexact: glibc sets ERANGE
    "2.2250738585072012e-308",   # subnormal after rounding to 53 bits, although the double is
    "0x1.fffffffffffffp-1023",   # normal: glibc detects tininess after rounding
    "1e-400",
])
def test_stod_out_of_range(text):
    assert stod(text).value is None and stod(text).out_of_range


def test_stod_sign_of_nan():
    assert math.copysign(1.0, stod("-nan").value) == -1.0


def stod_texts() -> list[str]:
    """Every number spelling, then seeded texts around the limits of a double."""
    rng = random.Random(1074)
    texts = list(NUMBERS)
    for _ in range(300):
        if rng.random() < 0.5:
            exponent = rng.choice([-1075, -1074, -1023, -1022, -1021, 1023, 1024]) + rng.randint(-2, 2)
            texts.append(f"{rng.choice('+-')}0x{rng.getrandbits(56):x}.{rng.getrandbits(8):x}p{exponent - 56}")
        else:
            digits = "".join(rng.choice("0123456789") for _ in range(rng.randint(1, 25)))
            exponent = rng.choice([-330, -324, -323, -308, -307, 308, 309]) - len(digits) + 1
            texts.append(f"{digits[0]}.{digits[1:]}e{exponent}{rng.choice(['', 'x', ' 1'])}")
    return texts


def test_stod_agrees_with_the_compiled_stod():
    oracle_dir()
    texts = stod_texts()
    for text, answer in zip(texts, run_lines("stod", [t.encode().hex() for t in texts]),
                            strict=True):
        ours = stod(text)
        if answer.startswith("EXC"):
            assert ours.value is None, (text, answer)
            assert ours.out_of_range == (answer == "EXC out_of_range"), (text, answer)
            continue
        _, value, used = answer.split()
        assert ours.value is not None, (text, answer)
        shown = "nan" if math.isnan(ours.value) else ours.value.hex()
        expected = "nan" if value == "nan" else float.fromhex(value).hex()
        assert (shown, len(text) - len(ours.rest)) == (expected, int(used)), (text, answer)


HUGE = """<robot name="r">
  <link name="base"/><link name="l1"/>
  <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <transmission name="t1">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="j1"><hardwareInterface>hardware_interface/PositionJointInterface</hardwareInterface></joint>
    <actuator name="m1"><mechanicalReduction>0x1p99999999999999999999</mechanicalReduction></actuator>
  </transmission>
</robot>
"""
REFUSED = ("reduction of actuator 'm1' of transmission 't1' is '0x1p99999999999999999999', "
           "out of the range of a double")


@pytest.fixture
def huge(tmp_path):
    path = tmp_path / "huge.urdf"
    path.write_text(HUGE)
    return str(path)


def invoke(*args: str) -> tuple[int, str, str]:
    result = CliRunner().invoke(cli, list(args), catch_exceptions=False)
    return result.exit_code, result.stdout, result.stderr


def test_validate_reports_a_huge_hexadecimal_exponent(huge):
    code, out, err = invoke("validate", huge)
    assert (code, err) == (1, "")
    assert f"{huge}:8:" in out and "error TX105" in out and REFUSED in out


def test_show_effective_says_ros_control_refuses_it(huge):
    code, out, err = invoke("show", "--effective", huge)
    assert (code, err) == (0, "")
    flat = " ".join(out.split())  # (lines folded to the terminal's width)
    assert ("read by ros_control, which refuses it or reads it other than written (TX105); not "
            "loaded: 'm1' reduction '0x1p99999999999999999999' is not a number") in flat


def test_map_refuses_it_in_one_line(huge):
    code, out, err = invoke("map", huge, "-t", "t1", "--to", "joint", "--position", "1")
    assert (code, out) == (2, "")
    assert err == (f"txtool: {huge}: transmission 't1' cannot be loaded: 'm1' reduction "
                   "'0x1p99999999999999999999' is not a number\n")


def test_convert_keeps_the_text_and_says_it_was_not_loadable(huge):
    # ros2_control reads the kept text as "not a number" and uses 1.0: what is written is
    # refused for it (target_check), unless losses are allowed
    code, out, err = invoke("convert", huge, "--to", "ros2-p2")
    assert (code, out) == (1, "")
    assert ("TX105 invalid-number for ros2_control (humble, jazzy, kilted, rolling): reduction "
            "of joint 'j1' of transmission 't1' is '0x1p99999999999999999999', not a finite "
            "number: ros2_control silently uses 1.0") in err
    code, out, err = invoke("convert", huge, "--to", "ros2-p2", "--allow-lossy")
    assert code == 0
    assert "<mechanical_reduction>0x1p99999999999999999999</mechanical_reduction>" in out
    assert "the original is not loadable ('m1' reduction '0x1p99999999999999999999' is not a number)" in err
