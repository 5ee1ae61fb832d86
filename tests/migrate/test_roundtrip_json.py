"""``roundtrip --format json`` writes what ``json.dumps`` writes of the report."""

from __future__ import annotations

import json

from hypothesis import given, settings
from hypothesis import strategies as st

from txtool.transform.roundtrip import CycleRow, RoundTripReport
from txtool.views.report_json import roundtrip_json

NAMES = st.text(st.characters(exclude_categories=()), max_size=12)  # surrogates too
ROWS = st.builds(
    CycleRow, NAMES, st.sampled_from([("ros1", "ros2-p2", "ros1"),
                                       ("ros2-p1", "ros1", "ros2-p2", "ros2-p1")]),
    st.fixed_dictionaries({"reduction": st.booleans(), "offset": st.booleans()}),
    st.sampled_from(["yes", "no: it \"differs\"", "n/a: lost"]),
    st.lists(NAMES, max_size=2).map(tuple))


@settings(max_examples=200, deadline=None)
@given(path=NAMES, rows=st.lists(ROWS, max_size=6), skipped=st.lists(NAMES, max_size=3))
def test_the_json_text_is_json_dumps_of_the_report(path, rows, skipped) -> None:
    report = RoundTripReport(path, rows, skipped)
    assert roundtrip_json(report) == json.dumps(report.to_json(), indent=2)
