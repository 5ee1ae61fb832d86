from __future__ import annotations

import pytest

from tests.rules.helpers import check, problems

IFACE = "<hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>"
ROS1 = f"""
<robot name="r">
  <transmission name="wrist">
    <type>transmission_interface/DifferentialTransmission</type>
    <joint name="a">{IFACE}<role>{{a}}</role></joint>
    <joint name="b">{IFACE}<role>{{b}}</role></joint>
    <actuator name="m1"><role>actuator1</role><mechanicalReduction>1</mechanicalReduction></actuator>
    <actuator name="m2"><role>actuator2</role><mechanicalReduction>1</mechanicalReduction></actuator>
  </transmission>
</robot>
"""


@pytest.mark.parametrize(
    ("a", "b", "where", "words"),
    [
        ("joint1", "joint1", (5, 99), "roles must differ"),
        ("joint1", "Joint2", (5, 99), "role 'Joint2', expected 'joint1' or 'joint2'"),
        ("joint1", "", (5, 99), "an empty <role>"),
    ],
)
def test_ros1_coupled_roles_fire_at_the_role(a, b, where, words):
    found = problems(ROS1.format(a=a, b=b), select=["TX107"])
    assert [(p.line, p.column, p.code, p.severity) for p in found] == [(*where, "TX107", "error")]
    assert words in found[0].message


def test_ros1_missing_role_fires_at_the_joint():
    xml = ROS1.format(a="joint1", b="joint2").replace("<role>joint2</role>", "")
    assert check(xml, select=["TX107"]) == [(5, 5, "TX107", "error")]


def test_ros1_valid_roles_in_any_order_pass():
    assert check(ROS1.format(a="joint2", b="joint1"), select=["TX107"]) == []


def test_ros1_simple_ignores_roles():
    xml = ROS1.format(a="x", b="y").replace("Differential", "Simple")
    assert check(xml, select=["TX107"]) == []


ROS2 = """
<robot name="r">
  <ros2_control name="hw" type="system">
    <joint name="j"/>
    <transmission name="t">
      <plugin>transmission_interface/SimpleTransmission</plugin>
      <actuator name="m"{role}/>
      <joint name="j" role="joint1"/>
    </transmission>
  </ros2_control>
</robot>
"""


def test_ros2_member_without_role_attribute_fires():
    found = problems(ROS2.format(role=""), select=["TX107"])
    assert [(p.line, p.column) for p in found] == [(6, 7)]
    assert "no attribute 'role' in 'actuator' tag" in found[0].message


def test_ros2_role_attribute_passes_whatever_its_value():
    assert check(ROS2.format(role=' role="anything"'), select=["TX107"]) == []
