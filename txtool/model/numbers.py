"""Number parsing as each ROS loader does it, and exact float formatting."""

from __future__ import annotations

import math
import re

# std::stod: leading whitespace, a sign, a decimal number or inf/nan; trailing junk is ignored.
_STOD = re.compile(
    r"\s*([+-]?(?:(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?|inf(?:inity)?|nan(?:\([^)]*\))?))",
    re.IGNORECASE,
)
# ros2_control (from_chars after strip; a leading '+' is skipped first): the whole text must be a
# finite decimal number.
_STRICT = re.compile(r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?")


def parse_ros1(text: str | None) -> float | None:
    """Parse like ros_control's ``std::stod``; None where it throws (empty, no leading number)."""
    if text is None:
        return None
    match = _STOD.match(text)
    if not match:
        return None
    token = match.group(1).lower()
    if token.startswith("nan"):
        return math.nan
    return float(token)


def parse_ros2(text: str | None) -> float | None:
    """Parse like ros2_control's parser; None where it silently falls back to the default."""
    if text is None:
        return None
    stripped = text.strip()
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

