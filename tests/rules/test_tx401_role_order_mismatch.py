from __future__ import annotations

from tests.rules.helpers import check, problems

COUPLED = """
<ros2_control name="hw" type="system">
  <joint name="foo_joint"><command_interface name="effort"/></joint>
  <joint name="bar_joint"><command_interface name="effort"/></joint>
  <transmission name="four_bar_trans">
    <plugin>transmission_interface/FourBarLinkageTransmission</plugin>
    {joints}
    <actuator name="a_actuator" role="actuator1"><mechanical_reduction>50</mechanical_reduction></actuator>
    <actuator name="b_actuator" role="actuator2"><mechanical_reduction>-50</mechanical_reduction></actuator>
  </transmission>
</ros2_control>
"""
BAR = '<joint name="bar_joint" role="{role}"><mechanical_reduction>-2</mechanical_reduction></joint>'
FOO = '<joint name="foo_joint" role="{role}"><mechanical_reduction>2</mechanical_reduction></joint>'


def test_the_converted_ros1_four_bar_keeps_bar_before_foo_and_fires():
    # Converted in XML order: ros2_control keeps -2 on bar (index 0 both in XML and by name)
    # but drives bar as joint1 although its role says joint2.
    joints = BAR.format(role="joint2") + FOO.format(role="joint1")
    found = problems(COUPLED.format(joints=joints), select=["TX401"])
    assert [(p.line, p.column, p.code, p.severity) for p in found] == [(6, 5, "TX401", "error")]
    assert "the joint roles (joint2, joint1) run against the XML and name order" in (
        found[0].message
    )
    assert found[0].message.endswith("drives 'bar_joint' as joint1, against its role")
    assert found[0].severity == "error"


def test_xml_order_against_name_order_fires_even_with_matching_roles():
    joints = FOO.format(role="joint1") + BAR.format(role="joint2")
    found = problems(COUPLED.format(joints=joints), select=["TX401"])
    assert [(p.line, p.column) for p in found] == [(6, 5)]
    assert "binds the joint reductions and offsets in XML order (foo_joint, bar_joint)" in (
        found[0].message
    )
    assert "the values written on 'foo_joint' land on 'bar_joint'" in found[0].message


def test_name_order_role_order_and_xml_order_agreeing_pass():
    joints = BAR.format(role="joint1") + FOO.format(role="joint2")
    assert check(COUPLED.format(joints=joints), select=["TX401"]) == []


def test_actuators_are_checked_on_their_own():
    joints = BAR.format(role="joint1") + FOO.format(role="joint2")
    xml = COUPLED.format(joints=joints).replace("a_actuator", "z_actuator")
    found = problems(xml, select=["TX401"])
    assert [(p.line, p.column) for p in found] == [(7, 5)]
    assert "actuator reductions in XML order (z_actuator, b_actuator)" in found[0].message


def test_ros1_is_left_to_tx404():
    xml = """
    <transmission name="t">
      <type>transmission_interface/FourBarLinkageTransmission</type>
      <joint name="bar_joint"><role>joint2</role></joint>
      <joint name="foo_joint"><role>joint1</role></joint>
      <actuator name="b"><role>actuator2</role><mechanicalReduction>1</mechanicalReduction></actuator>
      <actuator name="a"><role>actuator1</role><mechanicalReduction>1</mechanicalReduction></actuator>
    </transmission>
    """
    assert check(xml, select=["TX401"]) == []
