from __future__ import annotations

from tests.rules.helpers import check, fixed, problems, snippet
from txtool.rules import tx302_legacy_type_attribute as rule

LEGACY = """
<robot name="diffbot">
  <transmission name="wheel_left_trans" type="SimpleTransmission">
    <actuator name="wheel_left_motor"/>
    <joint name="wheel_left"/>
    <mechanicalReduction>1</mechanicalReduction>
    <motorTorqueConstant>1</motorTorqueConstant>
  </transmission>
</robot>
"""

LEGACY_FIXED = """
<robot name="diffbot">
  <transmission name="wheel_left_trans">
    <type>transmission_interface/SimpleTransmission</type>
    <actuator name="wheel_left_motor">
      <mechanicalReduction>1</mechanicalReduction>
    </actuator>
    <joint name="wheel_left"/>
    <motorTorqueConstant>1</motorTorqueConstant>
  </transmission>
</robot>
"""


def test_legacy_attribute_warns_at_the_transmission():
    found = problems(LEGACY, select=["TX302"])
    assert [(p.line, p.column, p.code, p.severity) for p in found] == [(2, 3, "TX302", "warning")]
    assert "legacy type=\"SimpleTransmission\" attribute" in found[0].message
    assert "No type element found" in found[0].message
    assert found[0].severity == "warning" and found[0].fixable


def test_type_element_passes():
    assert check(LEGACY_FIXED, select=["TX302"]) == []


def test_fix_writes_the_type_element_and_moves_the_reduction():
    text, first, second = fixed(rule, LEGACY)
    assert text == snippet(LEGACY_FIXED)
    assert (first, second) == (1, 0)


def test_fix_accepts_the_prefixed_simple_type_in_the_attribute():
    xml = LEGACY.replace('type="SimpleTransmission"',
                         'type="transmission_interface/SimpleTransmission"')
    assert fixed(rule, xml)[0] == snippet(LEGACY_FIXED)


HYBRID = (
    "<robot name=\"husky\">\n"
    "\t<transmission name=\"wheel_trans\" type=\"SimpleTransmission\">\n"
    "\t\t<type>transmission_interface/SimpleTransmission</type>\n"
    "\t\t<actuator name=\"wheel_motor\">\n"
    "\t\t\t<mechanicalReduction>1</mechanicalReduction>\n"
    "\t\t</actuator>\n"
    "\t\t<joint name=\"wheel\">\n"
    "\t\t\t<hardwareInterface>hardware_interface/VelocityJointInterface</hardwareInterface>\n"
    "\t\t</joint>\n"
    "\t</transmission>\n"
    "</robot>\n"
)


def test_hybrid_notes_that_the_attribute_is_ignored():
    # TransmissionParser::parse (transmission_parser.cpp) reads the <type> child only: the
    # attribute is read by nothing, an info
    found = problems(HYBRID, select=["TX302"])
    assert [(p.line, p.column, p.severity) for p in found] == [(2, 2, "info")]
    assert "attribute beside its <type> element: ros_control ignores" in found[0].message


def test_fix_removes_the_attribute_of_a_hybrid():
    text, first, second = fixed(rule, HYBRID)
    assert text == HYBRID.replace(' type="SimpleTransmission"', "")
    assert (first, second) == (1, 0)


PR2_MACRO = """
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="caster" params="suffix reflect">
    <transmission type="{type}" name="${suffix}_trans">
      <actuator name="${suffix}_motor"/>
      <joint name="${suffix}_joint"/>
      <mechanicalReduction>${reflect * 624/35 * 80/18}</mechanicalReduction>
    </transmission>
  </xacro:macro>
</robot>
"""


def test_custom_attribute_types_are_reported_not_fixed():
    xml = PR2_MACRO.replace("{type}", "pr2_mechanism_model/SimpleTransmission")
    found = problems(xml, select=["TX302"], filename="base.transmission.xacro")
    assert [(p.line, p.column) for p in found] == [(3, 5)]
    assert "a custom type, port it by hand" in found[0].message
    assert found[0].fixable is False  # the fix leaves custom types alone
    text, first, _ = fixed(rule, xml)
    assert (text, first) == (snippet(xml), 0)


def test_fix_on_unexpanded_xacro_keeps_expressions():
    xml = PR2_MACRO.replace("{type}", "SimpleTransmission")
    expected = snippet(
        """
        <robot xmlns:xacro="http://www.ros.org/wiki/xacro">
          <xacro:macro name="caster" params="suffix reflect">
            <transmission name="${suffix}_trans">
              <type>transmission_interface/SimpleTransmission</type>
              <actuator name="${suffix}_motor">
                <mechanicalReduction>${reflect * 624/35 * 80/18}</mechanicalReduction>
              </actuator>
              <joint name="${suffix}_joint"/>
            </transmission>
          </xacro:macro>
        </robot>
        """
    )
    text, first, second = fixed(rule, xml)
    assert text == expected
    assert (first, second) == (1, 0)


def test_ros2_transmissions_are_not_checked():
    xml = """
    <ros2_control name="hw" type="system">
      <joint name="j"><command_interface name="position"/></joint>
      <transmission name="t" type="SimpleTransmission">
        <plugin>transmission_interface/SimpleTransmission</plugin>
        <joint name="j" role="joint1"/>
      </transmission>
    </ros2_control>
    """
    assert check(xml, select=["TX302"]) == []


def test_fix_on_real_robots():
    from tests.corpus import corpus_file

    expected = {
        "ros2_control_test_assets__diffbot_urdf.urdf": (2, []),
        "husky__wheel.urdf.xacro": (1, []),
        "urdf_sim_tutorial__12-gripper.urdf.xacro": (2, []),
        "pr2__base.transmission.xacro": (0, [(6, 5, "TX302", "warning"), (15, 5, "TX302", "warning")]),
    }
    for name, (fixes, remaining) in expected.items():
        text, first, second = fixed(rule, corpus_file(name).read_text())
        assert (first, second) == (fixes, 0), name
        assert check(text, select=["TX302"], filename=name, no_xacro=True) == remaining, name
