"""The effort convention of a transmission is that of the loader reading its file."""

from __future__ import annotations

import pytest

from txtool.mechanics.convention import effort_convention
from txtool.model.core import Transmission


def four_bar(dialect: str) -> Transmission:
    return Transmission(name="fb", type="transmission_interface/FourBarLinkageTransmission",
                        kind="four_bar", dialect=dialect)  # type: ignore[arg-type]


@pytest.mark.parametrize(("dialect", "expected"), [
    ("ros1", "ros1"), ("ros2-p1", "ros2"), ("ros2-p2", "ros2"),
])
def test_each_dialect_runs_its_loader_convention(dialect, expected):
    assert effort_convention(four_bar(dialect)) == expected


@pytest.mark.parametrize("dialect", ["ros1", "ros2-p2"])
@pytest.mark.parametrize("override", ["ros1", "ros2"])
def test_an_override_wins(dialect, override):
    assert effort_convention(four_bar(dialect), override) == override


def test_unknown_override_is_refused():
    with pytest.raises(ValueError, match="unknown effort convention 'ros3'"):
        effort_convention(four_bar("ros1"), "ros3")
