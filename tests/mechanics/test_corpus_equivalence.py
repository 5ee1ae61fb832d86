"""A ROS 1 corpus file and its ROS 2 conversion drive the actuators alike wherever it converts.

A case that cannot compare anything (the file needs packages, convert refuses it, nothing to
convert) is skipped with its reason, so the count of passes is the count of real comparisons;
``test_enough_cases_really_compare`` holds that count so a change in convert or the corpus
cannot quietly turn comparisons into skips.
"""

from __future__ import annotations

from functools import cache

import pytest

from tests.corpus import corpus_file, corpus_names
from txtool.dialects.read import read_source
from txtool.io.load import load
from txtool.io.xmlio import InputError, Source, parse_bytes
from txtool.mechanics.equivalence import compare
from txtool.model.core import Transmission
from txtool.model.robot import robot_joints
from txtool.transform.convert import convert_source

TARGETS = ("ros2-p1", "ros2-p2", "ros1")
# Cases (file, target) that compare at least one loadable transmission, measured on the 48-file
# corpus. Raise it when more compare; never lower it to make a change pass. (41, not 42: the
# simple transmission with two joints of ros2_control_test_assets__invalid_transmission_
# too_many_joints.urdf is refused by ros2_control's SimpleTransmission::configure, so it was
# never a loadable case to compare.)
COMPARED_FLOOR = 41


Case = tuple[list[Transmission], list[Transmission], dict]


@cache
def comparison(name: str, target: str) -> Case | str:
    """(before, after, robot joints) of ``name`` converted to ``target``, or why none."""
    try:
        source = load(str(corpus_file(name)))
    except InputError as exc:
        return f"not loadable without packages or arguments: {exc}"
    result = convert_source(source, target)
    if result.losses:
        return f"convert to {target} refuses it (exit 1): {result.losses[0]}"
    if not result.converted:
        return f"nothing to convert to {target}"
    converted = Source(source.path, result.data, parse_bytes(result.data, source.path))
    before = [f.transmission for f in read_source(source) if f.transmission.kind != "other"]
    after = [f.transmission for f in read_source(converted) if f.transmission.kind != "other"]
    joints = robot_joints(source.root)
    report = compare(before, after, joints, convention="ros2")
    if not any(row.status == "equivalent" for row in report.rows):
        return f"no transmission loadable before and after converting to {target}"
    return before, after, joints


@pytest.mark.parametrize("target", TARGETS)
@pytest.mark.parametrize("name", corpus_names())
def test_lossless_conversions_are_equivalent(name: str, target: str) -> None:
    case = comparison(name, target)
    if isinstance(case, str):
        pytest.skip(case)
    before, after, joints = case
    for convention in ("ros2", "ros1"):  # the same maths on both sides
        for row in compare(before, after, joints, convention=convention).rows:
            assert row.status in ("equivalent", "not loadable"), (convention, row.a, row.reason)
    # Each side with its own loader's maths: only a four-bar crossing between ros_control and
    # ros2_control changes, and only in effort.
    kinds = {t.name: t.kind for t in before}
    crosses = (before[0].dialect == "ros1") != (target == "ros1")
    for row in compare(before, after, joints).rows:
        if row.status == "differs":
            assert crosses and kinds[row.a] == "four_bar", (row.a, row.reason)
            assert row.differences["position"] == row.differences["velocity"] == 0.0
            assert " effort differs by " in row.reason


def test_enough_cases_really_compare() -> None:
    names = corpus_names()
    corpus_file(names[0])  # skips, or fails under TXTOOL_REQUIRE_CORPUS=1, without a corpus
    compared = sorted((name, target) for name in names for target in TARGETS
                      if not isinstance(comparison(name, target), str))
    assert len(compared) >= COMPARED_FLOOR, f"only {len(compared)} cases compare: {compared}"
    assert len(compared) == COMPARED_FLOOR, (
        f"{len(compared)} cases compare now: raise COMPARED_FLOOR to {len(compared)}"
    )
