from __future__ import annotations

from tests.rules.helpers import check, problems

ROBOT = """
<robot name="r">
  <link name="a"/>
  <link name="b"/>
  <joint name="mount" type="{kind}">
    <parent link="a"/><child link="b"/><limit lower="-1" upper="1" effort="1" velocity="1"/>
  </joint>
  <transmission name="t">
    <type>{type}</type>
    <joint name="mount">
      <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
    </joint>
    <actuator name="m"><mechanicalReduction>10</mechanicalReduction></actuator>
  </transmission>
</robot>
"""
SIMPLE = "transmission_interface/SimpleTransmission"


def test_transmission_on_a_fixed_joint_fires():
    found = problems(ROBOT.format(kind="fixed", type=SIMPLE), select=["TX201"])
    assert [(p.line, p.column, p.code, p.severity) for p in found] == [(9, 5, "TX201", "error")]
    assert "joint 'mount' of transmission 't' is a fixed joint" in found[0].message
    assert found[0].severity == "error"


def test_transmission_on_a_revolute_joint_passes():
    assert check(ROBOT.format(kind="revolute", type=SIMPLE), select=["TX201"]) == []


def test_custom_types_may_name_fixed_joints():
    xml = ROBOT.format(kind="fixed", type="franka_hw/FrankaModelInterface")
    assert check(xml, select=["TX201"]) == []


def test_ros2_transmission_on_a_fixed_joint_fires():
    xml = """
    <robot name="r">
      <link name="a"/>
      <link name="b"/>
      <joint name="mount" type="fixed"><parent link="a"/><child link="b"/></joint>
      <ros2_control name="hw" type="system">
        <joint name="mount"><command_interface name="position"/></joint>
        <transmission name="t">
          <plugin>transmission_interface/SimpleTransmission</plugin>
          <joint name="mount" role="joint1"/>
        </transmission>
      </ros2_control>
    </robot>
    """
    found = problems(xml, select=["TX201"])
    assert [(p.line, p.column, p.code, p.severity) for p in found] == [(9, 7, "TX201", "error")]
    assert "Fixed joints do not make sense in ros2_control" in found[0].message
