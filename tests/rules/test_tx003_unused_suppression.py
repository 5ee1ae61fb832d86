from __future__ import annotations

from tests.rules.helpers import check, problems

XML = """
<robot name="r">
  <transmission name="t">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="j"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
    </joint>
    <!-- txtool: disable-next-line {codes} -->
    <actuator name="m"><mechanicalReduction>{value}</mechanicalReduction></actuator>
  </transmission>
</robot>
"""


def test_suppression_that_silences_nothing_is_an_info():
    found = problems(XML.format(codes="TX106", value="50"))
    assert [(p.line, p.column, p.code, p.severity) for p in found] == [(6, 5, "TX003", "info")]
    assert "'disable-next-line TX106' silences nothing" in found[0].message


def test_used_suppression_passes_and_silences():
    assert check(XML.format(codes="TX106", value="0")) == []


def test_only_the_unused_code_of_a_list_is_reported():
    found = problems(XML.format(codes="TX105, TX106", value="0"))
    assert [(p.code, "TX105" in p.message) for p in found] == [("TX003", True)]


def test_codes_that_are_not_selected_are_not_reported():
    assert check(XML.format(codes="TX106", value="50"), ignore=["TX106"]) == []
