"""Number parsing as each ROS loader does it, and exact float formatting.

Both loaders are C++: what Python's ``float()`` accepts and C++ does not (Unicode digits such as
Arabic-Indic ones, no-break and other Unicode spaces, ``1_000``) is read here as C++ reads it.
"""

from __future__ import annotations

import math
import re
import sys
from functools import lru_cache
from typing import NamedTuple

# isspace() in the "C" locale: what std::stod skips before a number and what ros2_control strips.
C_SPACE = " \t\n\v\f\r"
_HEX = r"0x(?:[0-9a-f]+\.?[0-9a-f]*|\.[0-9a-f]+)(?:p[+-]?[0-9]+)?"
_DECIMAL = r"(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:e[+-]?[0-9]+)?"
_SPECIAL = r"inf(?:inity)?|nan(?:\([0-9a-z_]*\))?"
# std::stod is strtod: C spaces, a sign, then the longest hexadecimal, decimal or inf/nan prefix.
_STOD = re.compile(
    rf"[{C_SPACE}]*([+-]?(?:{_HEX}|{_DECIMAL}|{_SPECIAL}))", re.IGNORECASE | re.ASCII
)
# ros2_control (whole stripped text, classic locale; a leading '+' is allowed): a finite decimal.
_STRICT = re.compile(r"[+-]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]+)?", re.ASCII)
_NONZERO_DIGIT = re.compile(r"[1-9a-f]", re.IGNORECASE)
_SMALLEST_NORMAL = sys.float_info.min


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
    value = float.fromhex(token) if bare.startswith("0x") else float(token)
    mantissa = re.split(r"[ep]", bare[2:] if bare.startswith("0x") else bare)[0]
    if math.isinf(value) or (abs(value) < _SMALLEST_NORMAL and _NONZERO_DIGIT.search(mantissa)):
        return Stod(None, token, rest, out_of_range=True)
    return Stod(value, token, rest)


def parse_ros1(text: str | None) -> float | None:
    """Parse like ros_control's ``std::stod``; None where it throws."""
    return stod(text).value


def parse_ros2(text: str | None) -> float | None:
    """Parse like ros2_control's parser; None where it silently falls back to the default."""
    if text is None:
        return None
    stripped = text.strip(C_SPACE)
    if not _STRICT.fullmatch(stripped):
        return None
    value = float(stripped)
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
