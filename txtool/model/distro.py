"""ROS distributions, as far as they change how a transmission is read.

ros_control (ROS 1) is read as on Noetic. ros2_control's component parser reads numbers with
``std::istringstream`` when built as C++17 (Humble) and with ``std::from_chars`` when built as
C++20 (Jazzy, Kilted, Rolling): ros2_control hardware_interface/src/lexical_casts.cpp,
``stod``. The readers model (which program reads a file) picks the distribution; everything
that reads a value asks it through :func:`numbers_of`.
"""

from __future__ import annotations

from enum import Enum


class Distro(str, Enum):
    """A ROS distribution whose loaders txtool models."""

    NOETIC = "noetic"
    HUMBLE = "humble"
    JAZZY = "jazzy"
    KILTED = "kilted"
    ROLLING = "rolling"

    @property
    def ros2(self) -> bool:
        return self is not Distro.NOETIC


class NumberReading(str, Enum):
    """How a loader turns an element's text into a double."""

    STOD = "stod"  # ros_control: std::stod, a valid prefix, trailing text ignored
    ISTRINGSTREAM = "istringstream"  # ros2_control built as C++17 (Humble)
    FROM_CHARS = "from_chars"  # ros2_control built as C++20 (Jazzy and later)


# Where nothing says which ROS 2 distribution reads a file, every one of these may: a verdict
# is an error only where all of them refuse, a warning where some do.
ROS2 = (Distro.HUMBLE, Distro.JAZZY, Distro.KILTED, Distro.ROLLING)
CHOICES = tuple(d.value for d in Distro)


def numbers_of(distro: Distro) -> NumberReading:
    """How ``distro``'s transmission loader reads numbers."""
    if distro is Distro.NOETIC:
        return NumberReading.STOD
    if distro is Distro.HUMBLE:
        return NumberReading.ISTRINGSTREAM
    return NumberReading.FROM_CHARS


def parse_distro(text: str) -> Distro:
    """``Distro`` from a user's text; ``ValueError`` naming the choices otherwise."""
    try:
        return Distro(text.strip().lower())
    except ValueError:
        choices = ", ".join(CHOICES)
        raise ValueError(f"unknown ROS distribution {text!r} (choose from {choices})") from None
