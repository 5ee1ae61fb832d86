from __future__ import annotations

from tests.rules.helpers import check, problems

XACRO = """
<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  {declaration}
  <link name="$(arg prefix)base"/>
  <transmission name="$(arg prefix)t">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="j"/>
    <actuator name="m"><mechanicalReduction>0</mechanicalReduction></actuator>
  </transmission>
</robot>
"""


def test_missing_argument_is_reported_where_it_is_used():
    found = problems(XACRO.format(declaration="<!-- no xacro:arg -->"), filename="r.urdf.xacro", select=["TX002"])
    assert [(p.line, p.column, p.code, p.severity) for p in found] == [(3, 15, "TX002", "error")]
    assert "missing argument 'prefix' (give --xacro-arg prefix:=VALUE)" in found[0].message


def test_literal_transmissions_are_still_checked_after_a_failure():
    codes = check(XACRO.format(declaration="<!-- no xacro:arg -->"), filename="r.urdf.xacro", select=["TX002", "TX106"])
    assert codes == [(3, 15, "TX002", "error"), (7, 24, "TX106", "error")]


def test_argument_given_in_the_configuration_expands():
    codes = check(XACRO.format(declaration="<!-- no xacro:arg -->"), filename="r.urdf.xacro", select=["TX002", "TX106"],
                  xacro_args={"prefix": "left_"})
    assert codes == [(7, 24, "TX106", "error")]


def test_argument_with_default_passes():
    assert check(XACRO.format(declaration='<xacro:arg name="prefix" default=""/>'), filename="r.xacro", select=["TX002"]) == []


INCLUDES = """
<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <link name="base"/>
    <xacro:include filename="{name}"/>
</robot>
"""


def test_a_missing_include_is_reported_at_the_include():
    found = problems(INCLUDES.format(name="parts/missing_wheel.xacro"), filename="r.urdf.xacro",
                     select=["TX002"])
    assert [(p.line, p.column, p.code, p.severity) for p in found] == [(3, 5, "TX002", "error")]
    assert "missing_wheel.xacro" in found[0].message
