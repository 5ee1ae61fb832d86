from __future__ import annotations

from tests.rules.helpers import check, problems

ROS1 = """
<robot name="r">
  <transmission{name}>
    <type>transmission_interface/SimpleTransmission</type>
    <joint{joint}><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
    </joint>
    <actuator name="m"><mechanicalReduction>1</mechanicalReduction></actuator>
  </transmission>
</robot>
"""


def test_transmission_without_name_fires_at_the_transmission():
    xml = ROS1.format(name="", joint=' name="j"')
    assert check(xml, select=["TX100"]) == [(2, 3, "TX100", "error")]
    assert "ros_control skips it" in problems(xml, select=["TX100"])[0].message


def test_empty_joint_name_fires_at_the_joint():
    xml = ROS1.format(name=' name="t"', joint=' name=""')
    found = problems(xml, select=["TX100"])
    assert [(p.line, p.column, p.code, p.severity) for p in found] == [(4, 5, "TX100", "error")]
    assert "skips this joint" in found[0].message


def test_ros2_missing_actuator_name_says_the_parser_throws():
    xml = """
    <robot name="r">
      <ros2_control name="hw" type="system">
        <joint name="j"/>
        <transmission name="t">
          <plugin>transmission_interface/SimpleTransmission</plugin>
          <actuator role="actuator1"/>
          <joint name="j" role="joint1"/>
        </transmission>
      </ros2_control>
    </robot>
    """
    found = problems(xml, select=["TX100"])
    assert [(p.line, p.column) for p in found] == [(6, 7)]
    assert "no attribute 'name' in 'actuator' tag" in found[0].message


def test_named_transmission_and_members_pass():
    assert check(ROS1.format(name=' name="t"', joint=' name="j"'), select=["TX100"]) == []
