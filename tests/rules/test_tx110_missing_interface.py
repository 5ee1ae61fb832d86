from __future__ import annotations

from tests.rules.helpers import check, problems

XML = """
<robot name="r">
  <transmission name="t">
    <type>{type}</type>
    <joint name="j">{joint}</joint>
    <actuator name="m">
      <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
      <mechanicalReduction>1</mechanicalReduction>
    </actuator>
  </transmission>
</robot>
"""
STANDARD = "transmission_interface/SimpleTransmission"


def test_joint_without_interface_fires_at_the_joint():
    found = problems(XML.format(type=STANDARD, joint=""), select=["TX110"])
    assert [(p.line, p.column, p.code, p.severity) for p in found] == [(4, 5, "TX110", "error")]
    assert "(only its actuator names one): ros_control skips the joint" in found[0].message


def test_empty_interface_fires():
    xml = XML.format(type=STANDARD, joint="<hardwareInterface> </hardwareInterface>")
    assert "an empty <hardwareInterface>" in problems(xml, select=["TX110"])[0].message


def test_joint_with_interface_passes():
    joint = "<hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>"
    assert check(XML.format(type=STANDARD, joint=joint), select=["TX110"]) == []


def test_families_with_their_own_loader_are_not_checked():
    xml = XML.format(type="pr2_mechanism_model/SimpleTransmission", joint="")
    assert check(xml, select=["TX110"]) == []
