from __future__ import annotations

from tests.rules.helpers import check, fixed, problems, snippet
from txtool.rules import tx301_interface_on_actuator as rule

BEFORE = """
<robot name="rrbot">
  <transmission name="tran1">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="joint1"/>
    <actuator name="motor1">
      <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
      <mechanicalReduction>1</mechanicalReduction>
    </actuator>
  </transmission>
</robot>
"""

AFTER = """
<robot name="rrbot">
  <transmission name="tran1">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="joint1">
      <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
    </joint>
    <actuator name="motor1">
      <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
      <mechanicalReduction>1</mechanicalReduction>
    </actuator>
  </transmission>
</robot>
"""


def test_interface_only_on_the_actuator_warns_at_the_joint():
    found = problems(BEFORE, select=["TX301"])
    assert [(p.line, p.column, p.code, p.severity) for p in found] == [(4, 5, "TX301", "warning")]
    assert "joint 'joint1' of transmission 'tran1' has no <hardwareInterface>" in found[0].message
    assert "only actuator 'motor1' has" in found[0].message
    assert found[0].severity == "warning" and found[0].fixable


def test_interface_on_the_joint_passes():
    assert check(AFTER, select=["TX301"]) == []


def test_fix_copies_the_interface_into_the_joint_and_is_idempotent():
    text, first, second = fixed(rule, BEFORE)
    assert text == snippet(AFTER)
    assert (first, second) == (1, 0)


def test_fix_inserts_before_existing_joint_children_with_tabs():
    before = (
        "<robot name=\"r\">\n"
        "\t<transmission name=\"t\">\n"
        "\t\t<type>transmission_interface/SimpleTransmission</type>\n"
        "\t\t<joint name=\"j\">\n"
        "\t\t\t<offset>0.5</offset>\n"
        "\t\t</joint>\n"
        "\t\t<actuator name=\"m\">\n"
        "\t\t\t<hardwareInterface>hardware_interface/PositionJointInterface</hardwareInterface>\n"
        "\t\t\t<hardwareInterface>hardware_interface/JointStateInterface</hardwareInterface>\n"
        "\t\t\t<mechanicalReduction>1</mechanicalReduction>\n"
        "\t\t</actuator>\n"
        "\t</transmission>\n"
        "</robot>\n"
    )
    after = before.replace(
        "\t\t\t<offset>0.5</offset>\n",
        "\t\t\t<hardwareInterface>hardware_interface/PositionJointInterface</hardwareInterface>\n"
        "\t\t\t<hardwareInterface>hardware_interface/JointStateInterface</hardwareInterface>\n"
        "\t\t\t<offset>0.5</offset>\n",
    )
    text, first, second = fixed(rule, before)
    assert text == after
    assert (first, second) == (1, 0)


def test_fix_on_unexpanded_xacro_keeps_expressions():
    macro = """
    <robot xmlns:xacro="http://www.ros.org/wiki/xacro">
      <xacro:macro name="trans" params="n hw">
        <transmission name="tran${n}">
          <type>transmission_interface/SimpleTransmission</type>
          <joint name="joint${n}"/>
          <actuator name="motor${n}">
            <hardwareInterface>hardware_interface/${hw}</hardwareInterface>
            <mechanicalReduction>${ratio}</mechanicalReduction>
          </actuator>
        </transmission>
      </xacro:macro>
    </robot>
    """
    expected = snippet(macro).replace(
        '<joint name="joint${n}"/>',
        '<joint name="joint${n}">\n'
        "        <hardwareInterface>hardware_interface/${hw}</hardwareInterface>\n"
        "      </joint>",
    )
    text, first, second = fixed(rule, macro)
    assert text == expected
    assert (first, second) == (1, 0)


def test_actuators_that_disagree_are_reported_but_not_fixed():
    xml = """
    <transmission name="t">
      <type>transmission_interface/DifferentialTransmission</type>
      <joint name="a"><role>joint1</role></joint>
      <joint name="b"><role>joint2</role></joint>
      <actuator name="m1"><role>actuator1</role><mechanicalReduction>1</mechanicalReduction>
        <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></actuator>
      <actuator name="m2"><role>actuator2</role><mechanicalReduction>1</mechanicalReduction>
        <hardwareInterface>hardware_interface/PositionJointInterface</hardwareInterface></actuator>
    </transmission>
    """
    assert check(xml, select=["TX301"]) == [(3, 3, "TX301", "warning"), (4, 3, "TX301", "warning")]
    text, first, _ = fixed(rule, xml)
    assert (text, first) == (snippet(xml), 0)


def test_fix_on_the_2013_rrbot_leaves_nothing_to_report():
    from tests.corpus import corpus_file

    name = "gazebo_ros_demos__rrbot_2013_hydro.xacro"
    text, first, second = fixed(rule, corpus_file(name).read_text())
    assert (first, second) == (1, 0)
    assert check(text, select=["TX301", "TX110"], filename=name, no_xacro=True) == []
