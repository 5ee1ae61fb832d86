"""A rule run alone, with the rules it defers to, finds what it finds among all of them.

The check of a conversion lints the input with only the rules that found an error in what was
written (``txtool.lint.target_check``); that is the same verdict only if no rule's findings
depend on which other rules run, except through ``Rule.defers_to``.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from tests.rules.helpers import problems
from txtool.rules import all_rules

FIXTURES = Path(__file__).resolve().parents[2] / "fixtures"

# TX205 leaves an unprefixed registered name to TX300 while TX300 runs.
UNPREFIXED = """
<robot name="r">
  <link name="a"/><link name="b"/>
  <joint name="j" type="revolute"><parent link="a"/><child link="b"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <transmission name="t">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="j"><hardwareInterface>PositionJointInterface</hardwareInterface></joint>
    <actuator name="m"><mechanicalReduction>1</mechanicalReduction></actuator>
  </transmission>
</robot>
"""


DOCUMENTS = [("unprefixed", UNPREFIXED), *(
    (path.name, path.read_text(encoding="utf-8")) for path in sorted(FIXTURES.glob("*.urdf")))]


def _found(xml: str, code: str, select: list[str]) -> list[tuple[int, int, str, str]]:
    return [(p.line, p.column, p.message, p.severity)
            for p in problems(xml, select=select) if p.code == code]


@pytest.mark.parametrize(("name", "xml"), DOCUMENTS, ids=[name for name, _ in DOCUMENTS])
def test_each_rule_alone_finds_what_it_finds_among_all(name, xml):
    rules = all_rules()
    every = problems(xml)
    for code, rule in rules.items():
        if rule.check is None:
            continue
        among_all = [(p.line, p.column, p.message, p.severity) for p in every if p.code == code]
        assert _found(xml, code, [code, *rule.defers_to]) == among_all, (name, code)


def test_a_rule_that_defers_says_so():
    # Without TX300, TX205 reports the refusal itself: which is why it declares TX300.
    assert all_rules()["TX205"].defers_to == ("TX300",)
    assert _found(UNPREFIXED, "TX205", ["TX205"]) != []
    assert _found(UNPREFIXED, "TX205", ["TX205", "TX300"]) == []
    assert {code for rule in all_rules().values() for code in rule.defers_to} <= set(all_rules())
