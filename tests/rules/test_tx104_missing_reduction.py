from __future__ import annotations

from tests.rules.helpers import check, problems

XML = """
<robot name="r">
  <transmission name="t">
    <type>transmission_interface/SimpleTransmission</type>
    {legacy}
    <joint name="j">
      <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
    </joint>
    <actuator name="m">{reduction}</actuator>
  </transmission>
</robot>
"""


def test_actuator_without_reduction_fires_at_the_actuator():
    found = problems(XML.format(legacy="", reduction=""), select=["TX104"])
    assert [(p.line, p.column, p.code, p.severity) for p in found] == [(8, 5, "TX104", "error")]
    assert "ros_control refuses the transmission" in found[0].message


def test_reduction_under_transmission_does_not_count():
    legacy = "<mechanicalReduction>50</mechanicalReduction>"
    found = problems(XML.format(legacy=legacy, reduction=""), select=["TX104"])
    assert [(p.line, p.column) for p in found] == [(8, 5)]
    assert "does not read the one under <transmission>" in found[0].message


def test_actuator_with_reduction_passes():
    reduction = "<mechanicalReduction>50</mechanicalReduction>"
    assert check(XML.format(legacy="", reduction=reduction), select=["TX104"]) == []


def test_ros2_actuator_needs_no_reduction():
    xml = """
    <robot name="r">
      <ros2_control name="hw" type="system">
        <joint name="j"/>
        <transmission name="t">
          <plugin>transmission_interface/SimpleTransmission</plugin>
          <actuator name="m" role="actuator1"/>
          <joint name="j" role="joint1"/>
        </transmission>
      </ros2_control>
    </robot>
    """
    assert check(xml, select=["TX104"]) == []
