from __future__ import annotations

from tests.rules.helpers import check, problems

ROS1 = """
<robot name="r">
  <transmission name="diff">
    <type>transmission_interface/DifferentialTransmission</type>
    <joint name="j1"><role>joint1</role>
      <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>
    <joint name="j2"><role>joint2</role>
      <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>
    <actuator name="a1"><role>actuator1</role><mechanicalReduction>{a1}</mechanicalReduction></actuator>
    <actuator name="a2"><role>actuator2</role><mechanicalReduction>{a2}</mechanicalReduction></actuator>
  </transmission>
</robot>
"""


def test_badly_conditioned_differential_fires_with_its_condition_number():
    found = problems(ROS1.format(a1="1", a2="1e-13"), select=["TX403"])
    assert [(p.line, p.column, p.code) for p in found] == [(2, 3, "TX403")]
    # A = [[1, 1], [1e-13, -1e-13]]: singular values sqrt(2) and sqrt(2)*1e-13.
    assert "condition number 1e+13" in found[0].message
    assert "transmission 'diff'" in found[0].message


def test_well_conditioned_differential_passes():
    assert check(ROS1.format(a1="50", a2="50"), select=["TX403"]) == []


def test_max_condition_option_tightens_the_check():
    xml = ROS1.format(a1="1", a2="0.001")  # condition number 1000
    assert check(xml, select=["TX403"]) == []
    assert check(xml, select=["TX403"], rules={"TX403": {"max-condition": 100}}) == [
        (2, 3, "TX403")
    ]


def test_zero_reduction_is_left_to_tx106():
    assert check(ROS1.format(a1="0", a2="1"), select=["TX403"]) == []


def test_ros2_four_bar_with_an_underflowing_determinant_fires():
    xml = """
    <ros2_control name="hw" type="system">
      <joint name="a"><command_interface name="position"/></joint>
      <joint name="b"><command_interface name="position"/></joint>
      <transmission name="t">
        <plugin>transmission_interface/FourBarLinkageTransmission</plugin>
        <actuator name="m1" role="actuator1"><mechanical_reduction>1e-200</mechanical_reduction></actuator>
        <actuator name="m2" role="actuator2"><mechanical_reduction>1e-200</mechanical_reduction></actuator>
        <joint name="a" role="joint1"/>
        <joint name="b" role="joint2"/>
      </transmission>
    </ros2_control>
    """
    found = problems(xml, select=["TX403"])
    assert [(p.line, p.column) for p in found] == [(4, 3)]
    assert "determinant 0" in found[0].message
