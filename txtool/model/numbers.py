"""Number parsing as each ROS loader does it, and exact float formatting.

Both loaders are C++: what Python's ``float()`` accepts and C++ does not (Unicode digits such as
Arabic-Indic ones, no-break and other Unicode spaces, ``1_000``) is read here as C++ reads it.
"""

from __future__ import annotations

import math
import re
from fractions import Fraction
from functools import lru_cache
from typing import NamedTuple

from txtool.model.distro import NumberReading

# isspace() in the "C" locale: what std::stod skips before a number and what ros2_control strips.
C_SPACE = " \t\n\v\f\r"
_HEX = r"0x(?:[0-9a-f]+\.?[0-9a-f]*|\.[0-9a-f]+)(?:p[+-]?[0-9]+)?"
_DECIMAL = r"(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:e[+-]?[0-9]+)?"
_SPECIAL = r"inf(?:inity)?|nan(?:\([0-9a-z_]*\))?"
# std::stod is strtod: C spaces, a sign, then the longest hexadecimal, decimal or inf/nan prefix.
_STOD = re.compile(
    rf"[{C_SPACE}]*([+-]?(?:{_HEX}|{_DECIMAL}|{_SPECIAL}))", re.IGNORECASE | re.ASCII
)
# ros2_control reads the whole text stripped of C spaces (hardware_interface/src/
# lexical_casts.cpp, impl::stod). Built as C++17 (Humble) ``istringstream >> double`` in the
# classic locale takes a signed decimal (no hexadecimal, inf or nan) and fails on overflow only.
_ISTRINGSTREAM = re.compile(r"[+-]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]+)?", re.ASCII)
# Built as C++20 (Jazzy and later): one leading '+' dropped, then ``std::from_chars`` (general
# format: an optional '-', a decimal; its inf and nan are refused as not finite) must read it
# all, and fails on overflow and on a nonzero number that rounds to zero.
_FROM_CHARS = re.compile(r"-?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]+)?", re.ASCII)
_NONZERO_DIGIT = re.compile(r"[1-9a-f]", re.IGNORECASE)
_SMALLEST_NORMAL = Fraction(2) ** -1022
_MIN_NORMAL = float(_SMALLEST_NORMAL)


class Stod(NamedTuple):
    """What ``std::stod`` makes of a text.

    ``value`` is None where it throws: no number at the start (``std::invalid_argument``) or a
    number outside the range of a double (``std::out_of_range``: strtod sets ERANGE on overflow
    and underflow). ``read`` is the part it converted, ``rest`` what it silently ignored.
    """

    value: float | None
    read: str = ""
    rest: str = ""
    out_of_range: bool = False

    @property
    def special(self) -> bool:
        """The text itself says inf or nan (accepted by std::stod)."""
        return self.value is not None and not math.isfinite(self.value)

    @property
    def hexadecimal(self) -> bool:
        return self.read.lstrip("+-")[:2].lower() == "0x"


@lru_cache(maxsize=4096)  # the same few texts recur in every transmission
def stod(text: str | None) -> Stod:
    """Read ``text`` as libstdc++'s ``std::stod`` (glibc ``strtod`` in the C locale)."""
    if text is None:
        return Stod(None)  # ros_control builds a std::string from a null text: it throws
    match = _STOD.match(text)
    if not match:
        return Stod(None, rest=text)
    token = match.group(1)
    rest = text[match.end():]
    bare = token.lstrip("+-").lower()
    if bare.startswith(("inf", "nan")):
        value = math.nan if bare.startswith("nan") else math.inf
        return Stod(-value if token.startswith("-") else value, token, rest)
    value = _strtod_value(bare)
    if value is None:
        return Stod(None, token, rest, out_of_range=True)
    return Stod(-value if token.startswith("-") else value, token, rest)


def _strtod_value(bare: str) -> float | None:
    """glibc ``strtod`` of an unsigned decimal or hexadecimal number (lower case); None where
    it sets ERANGE: overflow, or a result that is subnormal after rounding to 53 bits with an
    unbounded exponent (tininess after rounding) and inexact, zero included."""
    try:
        quick = float.fromhex(bare) if bare.startswith("0x") else float(bare)
    except OverflowError:  # float.fromhex of a huge exponent
        return None
    if math.isinf(quick):
        return None
    if abs(quick) > _MIN_NORMAL:
        return quick  # a normal result: no ERANGE, and Python rounds as glibc does
    exact = _exact(bare)
    if exact is None:  # an exponent far outside a double's range
        return None if _NONZERO_DIGIT.search(_mantissa(bare)) else 0.0
    if exact == 0:
        return 0.0
    try:
        value = exact.numerator / exact.denominator  # correctly rounded, subnormals included
    except OverflowError:
        return None
    if math.isinf(value):
        return None
    if exact < _SMALLEST_NORMAL:
        scaled = exact * 2**1100  # in the normal range: rounded to 53 bits, exponent unbounded
        tiny = scaled.numerator / scaled.denominator < 2.0**78
        if tiny and Fraction(value) != exact:
            return None
    return value


def _mantissa(bare: str) -> str:
    return re.split(r"[ep]", bare[2:] if bare.startswith("0x") else bare)[0]


def _exact(bare: str) -> Fraction | None:
    """The exact value of an unsigned decimal or hexadecimal text; None where its exponent
    puts it far outside a double's range (overflow or underflow, decided by the caller)."""
    hexadecimal = bare.startswith("0x")
    body = bare[2:] if hexadecimal else bare
    mantissa, _, exponent = body.partition("p" if hexadecimal else "e")
    whole, _, fraction = mantissa.partition(".")
    digits = (whole + fraction).lstrip("0")
    if not digits:
        return Fraction(0)
    power = int(exponent) if exponent.lstrip("+-").isdigit() else 0
    if hexadecimal:
        scale = power - 4 * len(fraction)
        magnitude = scale + 4 * len(digits)  # 2 ** magnitude bounds the value
        if not -1200 < magnitude < 1100:
            return None
        return Fraction(int(digits, 16)) * Fraction(2) ** scale
    scale = power - len(fraction)
    magnitude = scale + len(digits)  # 10 ** magnitude bounds the value
    if not -360 < magnitude < 330:
        return None
    return Fraction(int(digits)) * Fraction(10) ** scale


def parse_ros1(text: str | None) -> float | None:
    """Parse like ros_control's ``std::stod``; None where it throws."""
    return stod(text).value


def parse_ros2(text: str | None, reading: NumberReading | None = None) -> float | None:
    """Read ``text`` as ros2_control's parser does; None where it silently falls back to the
    default (hardware_interface/src/component_parser.cpp ``get_parameter_value_or`` catches
    the failure of ``hardware_interface::stod``).

    ``reading`` is how the distribution's build reads numbers (:func:`txtool.model.distro.
    numbers_of`). None: the value every ROS 2 distribution reads, None where any of them does
    not read that value (see :func:`ros2_readings` for each one's).
    """
    if text is None:
        return None
    if reading is None:
        return _read_every_ros2(text)
    return _read_ros2(text.strip(C_SPACE), reading)


@lru_cache(maxsize=4096)  # the same few texts recur in every transmission
def _read_every_ros2(text: str) -> float | None:
    """:func:`parse_ros2` of ``text`` without a reading: the value all builds agree on."""
    stripped = text.strip(C_SPACE)
    values = {_read_ros2(stripped, r) for r in ROS2_READINGS}
    return values.pop() if len(values) == 1 else None


ROS2_READINGS = (NumberReading.ISTRINGSTREAM, NumberReading.FROM_CHARS)


@lru_cache(maxsize=4096)
def ros2_readings_differ(text: str | None) -> bool:
    """Some ROS 2 builds read ``text`` as another value (or as none) than others do."""
    if text is None:
        return False
    stripped = text.strip(C_SPACE)
    if len(stripped) < 300 and _SHORT_DECIMAL.fullmatch(stripped):
        return False  # no '+', no exponent, too short to overflow: read alike
    return len({_read_ros2(stripped, r) for r in ROS2_READINGS}) > 1


_SHORT_DECIMAL = re.compile(r"-?(?:[0-9]+\.?[0-9]*|\.[0-9]+)", re.ASCII)


def ros2_readings(text: str | None) -> dict[NumberReading, float | None]:
    """What each ROS 2 build reads from ``text`` (None: it falls back to the default)."""
    return {reading: parse_ros2(text, reading) for reading in ROS2_READINGS}


@lru_cache(maxsize=4096)
def _read_ros2(stripped: str, reading: NumberReading) -> float | None:
    if reading is NumberReading.STOD:
        raise ValueError("std::stod is ros_control's reading: use parse_ros1")
    if reading is NumberReading.FROM_CHARS:
        # lexical_casts.cpp: one leading '+' is dropped (from_chars takes none), then the
        # rest must be a number from_chars reads whole.
        unsigned = stripped[1:] if stripped.startswith("+") else stripped
        if not _FROM_CHARS.fullmatch(unsigned):
            return None
        value = float(unsigned)
        if value == 0 and _NONZERO_DIGIT.search(_mantissa(unsigned.lstrip("-").lower())):
            return None  # from_chars: result_out_of_range where a nonzero number rounds to 0
    else:
        if not _ISTRINGSTREAM.fullmatch(stripped):
            return None
        value = float(stripped)  # an underflow is no failure for istringstream
    return value if math.isfinite(value) else None


def parse_strict(text: str | None) -> float | None:
    """A plain finite number or None: the form txtool itself writes."""
    return parse_ros2(text)


def format_float(value: float) -> str:
    """Shortest text that reads back as exactly ``value`` (``50.0`` -> ``50``)."""
    if math.isnan(value) or math.isinf(value):
        return repr(value)
    text = repr(value)
    if text.endswith(".0"):
        text = text[:-2]
    return text
