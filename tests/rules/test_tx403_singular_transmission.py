from __future__ import annotations

from hypothesis import given, settings
from hypothesis import strategies as st

from tests.rules.helpers import check, problems
from txtool.dialects.read import read_source
from txtool.io.xmlio import Source, parse_bytes
from txtool.mechanics.linear import singular
from txtool.model.semantics import NotLoadable, effective

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
    assert [(p.line, p.column, p.code, p.severity) for p in found] == [(2, 3, "TX403", "error")]
    # A = [[1, 1], [1e-13, -1e-13]]: singular values sqrt(2) and sqrt(2)*1e-13.
    assert "condition number 1e+13" in found[0].message
    assert "transmission 'diff'" in found[0].message


def test_well_conditioned_differential_passes():
    assert check(ROS1.format(a1="50", a2="50"), select=["TX403"]) == []


def test_max_condition_option_tightens_the_check():
    xml = ROS1.format(a1="1", a2="0.001")  # condition number 1000
    assert check(xml, select=["TX403"]) == []
    assert check(xml, select=["TX403"], rules={"TX403": {"max-condition": 100}}) == [
        (2, 3, "TX403", "error")
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


@given(st.floats(allow_nan=True, allow_infinity=True), st.sampled_from(["ros1", "ros2"]))
@settings(max_examples=200, deadline=None)
def test_a_loadable_simple_transmission_is_never_singular(reduction, dialect):
    """Linting a simple transmission with any reduction never reports TX403.

    A 1x1 map that loads is one finite, non-zero number (the rule skips simple transmissions
    for that reason); one that does not load is TX105's or TX106's to report.
    """
    xml = (SIMPLE_ROS1 if dialect == "ros1" else SIMPLE_ROS2).format(n=repr(reduction))
    assert [p.code for p in problems(xml, select=["TX403"])] == []
    found = read_source(Source("r.urdf", xml.encode(), parse_bytes(xml.encode(), "r.urdf")))
    try:
        loaded = effective(found[0].transmission)
    except NotLoadable:
        return
    assert singular(loaded, max_condition=1.0000001) is None


SIMPLE_ROS1 = """<robot name="r"><transmission name="t">
  <type>transmission_interface/SimpleTransmission</type>
  <joint name="j"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
  </joint>
  <actuator name="m"><mechanicalReduction>{n}</mechanicalReduction></actuator>
</transmission></robot>"""
SIMPLE_ROS2 = """<robot name="r"><ros2_control name="hw" type="system">
  <joint name="j"><command_interface name="effort"/></joint>
  <transmission name="t"><plugin>transmission_interface/SimpleTransmission</plugin>
    <joint name="j" role="joint1"><mechanical_reduction>{n}</mechanical_reduction></joint>
    <actuator name="m" role="actuator1"/>
  </transmission>
</ros2_control></robot>"""
