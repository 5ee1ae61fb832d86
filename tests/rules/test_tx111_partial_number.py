"""TX111: numbers the loader reads only part of (std::stod prefix, hex, split by a comment).

std::stod: ros_control transmission_interface/src/transmission_loader.cpp:60, :95, :130
@63b6afd. First text node: GetText() there and in ros2_control
hardware_interface/src/component_parser.cpp:145 @157446a.
"""

from __future__ import annotations

import pytest

from tests.rules.helpers import check, problems
from tests.rules.test_tx105_invalid_number import ROS1, ROS2


@pytest.mark.parametrize(
    ("reduction", "reads", "how"),
    [
        ("50abc", "50", "ignores 'abc' after it"),
        ("5_0", "5", "ignores '_0' after it"),
        ("1e", "1", "ignores 'e' after it"),
        ("0x10", "16", "reads it as hexadecimal"),
    ],
)
def test_ros1_prefix_loads_with_a_warning_naming_the_ros2_default(reduction, reads, how):
    found = problems(ROS1.format(offset="0", reduction=reduction), select=["TX111"])
    assert [(p.line, p.column, p.code, p.severity) for p in found] == [
        (8, 24, "TX111", "warning")
    ]
    assert f"std::stod reads {reads} and {how}" in found[0].message
    assert "ros2_control would not read it and silently use 1.0" in found[0].message


def test_ros1_offset_names_the_offset_default():
    found = problems(ROS1.format(offset="0.5rad", reduction="50"), select=["TX111"])
    assert [(p.line, p.column) for p in found] == [(6, 7)]
    assert "silently use 0.0" in found[0].message


@pytest.mark.parametrize("reduction", ["50", " 50 ", "fifty", "inf", "1.8e308", "-2.5e1"])
def test_plain_refused_and_special_numbers_are_not_tx111(reduction):
    assert check(ROS1.format(offset="0", reduction=reduction), select=["TX111"]) == []


@pytest.mark.parametrize("split", ["5<!-- gear -->0", "5<![CDATA[0]]>"])
def test_ros1_number_split_by_a_comment_or_cdata_is_read_up_to_the_split(split):
    found = problems(ROS1.format(offset="0", reduction=split), select=["TX111", "TX105"])
    assert [(p.code, p.severity) for p in found] == [("TX111", "warning")]
    assert "ros_control reads only the text before it, '5' (5), not '50'" in found[0].message


def test_ros2_number_split_by_a_comment_is_read_up_to_the_split():
    found = problems(ROS2.format(reduction="5<!-- gear -->0", offset="0"),
                     select=["TX111", "TX105"])
    assert [(p.code, p.severity) for p in found] == [("TX111", "warning")]
    assert "ros2_control reads only the text before it, '5' (5)" in found[0].message


def test_ros2_junk_is_tx105_not_tx111():
    assert check(ROS2.format(reduction="50abc", offset="0"), select=["TX111"]) == []
