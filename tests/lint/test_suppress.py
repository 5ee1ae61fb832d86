"""Inline suppressions written as XML comments."""

from __future__ import annotations

from tests.rules.helpers import check
from txtool.lint.suppress import parse

XML = """
<robot name="r">
  {file}
  <transmission name="t">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="j"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
    </joint>
    {next}
    <actuator name="m"><mechanicalReduction>0</mechanicalReduction></actuator>{same}
  </transmission>
</robot>
"""


def fill(file: str = "", next: str = "", same: str = "") -> str:
    return XML.format(file=file, next=next, same=same)


def test_unsuppressed_finding_is_reported():
    assert check(fill(), select=["TX106"]) == [(8, 24, "TX106", "error")]


def test_disable_next_line():
    assert check(fill(next="<!-- txtool: disable-next-line TX106 -->")) == []


def test_disable_next_line_of_another_code_does_not_silence():
    found = check(fill(next="<!-- txtool: disable-next-line TX105 -->"))
    assert found == [(7, 5, "TX003", "info"), (8, 24, "TX106", "error")]


def test_disable_line_and_a_reason():
    same = "<!-- txtool: disable-line TX106; zero on purpose, not TX105 -->"
    assert check(fill(same=same)) == []


def test_disable_file_with_several_codes():
    assert check(fill(file="<!-- txtool: disable-file TX105, TX106 -->"), ignore=["TX003"]) == []


def test_directive_without_codes_silences_everything_on_its_line():
    assert check(fill(next="<!-- txtool: disable-next-line -->")) == []


def test_ordinary_comments_are_not_directives():
    assert check(fill(next="<!-- txtool disable TX106 -->"), select=["TX106"]) == [
        (8, 24, "TX106", "error")
    ]


def test_parse_positions_of_a_multiline_directive():
    data = b'<robot>\n  <!-- txtool: disable-next-line\n       TX105 TX106 -->\n  <x/>\n</robot>'
    (directive,) = parse(data).directives
    assert (directive.line, directive.column, directive.target) == (2, 3, 4)
    assert directive.codes == {"TX105", "TX106"}
