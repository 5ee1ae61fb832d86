from __future__ import annotations

from tests.rules.helpers import check, problems

ROBOT = """
<robot name="r">
  <link name="palm"/>
  <link name="left"/>
  <link name="right"/>
  <joint name="finger_left" type="prismatic">
    <parent link="palm"/><child link="left"/>
    <limit lower="0" upper="0.04" effort="10" velocity="0.1"/>
  </joint>
  <joint name="finger_right" type="prismatic">
    <parent link="palm"/><child link="right"/>
    <limit lower="0" upper="0.04" effort="10" velocity="0.1"/>
    <mimic joint="finger_left" multiplier="1"/>
  </joint>
  <transmission name="t">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="{joint}">
      <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
    </joint>
    <actuator name="m"><mechanicalReduction>1</mechanicalReduction></actuator>
  </transmission>
</robot>
"""


def test_transmission_on_a_mimic_joint_warns():
    found = problems(ROBOT.format(joint="finger_right"), select=["TX202"])
    assert [(p.line, p.column, p.code, p.severity) for p in found] == [(16, 5, "TX202", "warning")]
    assert "joint 'finger_right' of transmission 't' mimics 'finger_left'" in found[0].message
    assert found[0].severity == "warning"


def test_transmission_on_the_leader_passes():
    assert check(ROBOT.format(joint="finger_left"), select=["TX202"]) == []
