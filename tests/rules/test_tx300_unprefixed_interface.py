from __future__ import annotations

from tests.rules.helpers import check, fixed, problems, snippet
from txtool.rules import tx300_unprefixed_interface as rule

BEFORE = """
<robot name="r">
  <transmission name="t">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="j">
      <hardwareInterface>PositionJointInterface</hardwareInterface>
    </joint>
    <actuator name="m">
      <hardwareInterface> EffortJointInterface </hardwareInterface>
      <mechanicalReduction>1</mechanicalReduction>
    </actuator>
  </transmission>
</robot>
"""

AFTER = """
<robot name="r">
  <transmission name="t">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="j">
      <hardwareInterface>hardware_interface/PositionJointInterface</hardwareInterface>
    </joint>
    <actuator name="m">
      <hardwareInterface> hardware_interface/EffortJointInterface </hardwareInterface>
      <mechanicalReduction>1</mechanicalReduction>
    </actuator>
  </transmission>
</robot>
"""


def test_unprefixed_interface_warns_on_the_joint_only():
    # ros_control reads interfaces from joints only: transmission_interface_loader.cpp:152
    # @0a09467 takes the first joint's list; the actuator's is never looked up.
    found = problems(BEFORE, select=["TX300"])
    # its joint names no other interface: ros_control refuses the transmission (TX205's error)
    assert [(p.line, p.column, p.code, p.severity) for p in found] == [(5, 7, "TX300", "error")]
    assert found[0].fixable
    assert "'PositionJointInterface' of joint 'j' in transmission 't'" in found[0].message
    assert "write 'hardware_interface/PositionJointInterface'" in found[0].message


def test_prefixed_interfaces_pass():
    assert check(AFTER, select=["TX300"]) == []
    assert check(AFTER.replace("hardware_interface/EffortJointInterface", "EffortJointInterface"),
                 select=["TX300"]) == []  # an actuator's interface is never read


def test_fix_prepends_the_prefix_and_is_idempotent():
    text, first, second = fixed(rule, BEFORE)
    assert text == snippet(AFTER)
    assert (first, second) == (2, 0)  # the actuator's copy is prefixed too


def test_fix_keeps_xacro_expressions_verbatim():
    macro = """
    <robot xmlns:xacro="http://www.ros.org/wiki/xacro">
      <xacro:macro name="arm_trans" params="prefix">
        <transmission name="${prefix}_trans">
          <type>transmission_interface/SimpleTransmission</type>
          <joint name="${prefix}_joint">
            <hardwareInterface>VelocityJointInterface</hardwareInterface>
            <hardwareInterface>${extra_interface}</hardwareInterface>
          </joint>
          <actuator name="${prefix}_motor">
            <mechanicalReduction>${gear * 2}</mechanicalReduction>
          </actuator>
        </transmission>
      </xacro:macro>
    </robot>
    """
    expected = snippet(macro).replace(
        "<hardwareInterface>VelocityJointInterface",
        "<hardwareInterface>hardware_interface/VelocityJointInterface",
    )
    text, first, second = fixed(rule, macro)
    assert text == expected
    assert (first, second) == (1, 0)


def test_ros2_and_own_loader_families_are_left_alone():
    pr2 = BEFORE.replace(
        "transmission_interface/SimpleTransmission", "sr_mechanism_model/SimpleTransmission"
    )
    assert check(pr2, select=["TX300"]) == []
    assert fixed(rule, pr2)[1] == 0


def test_fix_on_real_robots_leaves_nothing_to_report():
    from tests.corpus import corpus_file

    for name in ("baxter__baxter.urdf", "open_manipulator__open_manipulator_x.gazebo.xacro"):
        text, first, second = fixed(rule, corpus_file(name).read_text())
        assert first > 0 and second == 0
        assert check(text, select=["TX300"], filename=name, no_xacro=True) == []
