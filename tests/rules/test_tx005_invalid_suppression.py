from __future__ import annotations

import pytest

from tests.rules.helpers import check, problems

XML = """
<robot name="r">
  <transmission name="t">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="j"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
    </joint>
    <!-- txtool: {directive} -->
    <actuator name="m"><mechanicalReduction>0</mechanicalReduction></actuator>
  </transmission>
</robot>
"""


@pytest.mark.parametrize(("directive", "reason"), [
    ("disable-nextline TX106",
     "unknown directive 'txtool: disable-nextline': did you mean 'disable-next-line'?"),
    ("ignore TX106", "unknown directive 'txtool: ignore': use disable-next-line, disable-line, "
                     "disable-file"),
    ("disable-next-line TX106 zero on purpose",
     "'zero' is not a rule code (write TXnnn; a reason goes after ';')"),
    ("disable-next-line TX10", "'TX10' is not a rule code (write TXnnn; a reason goes after ';')"),
])
def test_a_directive_that_cannot_work_as_written_is_a_warning(directive, reason):
    found = [p for p in problems(XML.format(directive=directive)) if p.code == "TX005"]
    assert [(p.line, p.column, p.code, p.severity, p.message) for p in found] == [
        (6, 5, "TX005", "warning", reason)]


def test_a_misspelt_directive_silences_nothing():
    codes = {p.code for p in problems(XML.format(directive="disable-nextline TX106"))}
    assert codes == {"TX005", "TX106"}


def test_a_code_of_no_rule_is_named():
    found = problems(XML.format(directive="disable-next-line TX106, TX999"))
    assert [(p.code, p.message) for p in found] == [
        ("TX005", "suppression names 'TX999', which is no rule: see `txtool rules`")]


def test_a_valid_directive_with_a_reason_passes():
    assert check(XML.format(directive="disable-next-line TX106; zero on purpose")) == []


def test_tx004_can_be_ignored():
    assert check(XML.format(directive="disable-nextline TX106"), ignore=["TX005", "TX106"]) == []
