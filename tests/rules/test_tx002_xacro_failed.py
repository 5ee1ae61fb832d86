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


def test_a_missing_argument_is_an_info_where_it_is_used():
    # The launch file that reads the robot gives the argument (xacro robot.urdf.xacro
    # prefix:=left_): the file is not at fault, this run did not expand it.
    found = problems(XACRO.format(declaration="<!-- no xacro:arg -->"), filename="r.urdf.xacro", select=["TX002"])
    assert [(p.line, p.column, p.code, p.severity) for p in found] == [(3, 15, "TX002", "info")]
    assert found[0].message == ("not expanded, checked as written only: xacro: missing argument "
                                "'prefix' (give --xacro-arg prefix:=VALUE)")


def test_literal_transmissions_are_still_checked_after_a_failure():
    codes = check(XACRO.format(declaration="<!-- no xacro:arg -->"), filename="r.urdf.xacro", select=["TX002", "TX106"])
    assert codes == [(3, 15, "TX002", "info"), (7, 24, "TX106", "error")]


def test_a_configured_severity_makes_a_file_not_expanded_fail():
    codes = check(XACRO.format(declaration="<!-- no xacro:arg -->"), filename="r.urdf.xacro", select=["TX002"],
                  severity={"TX002": "error"})
    assert codes == [(3, 15, "TX002", "error")]


def test_an_undefined_property_is_an_error_of_the_file():
    found = problems(XACRO.format(declaration="<!-- no xacro:arg -->").replace("$(arg prefix)", "${prefix}"),
                     filename="r.urdf.xacro", select=["TX002"])
    assert [(p.line, p.column, p.code, p.severity) for p in found] == [(3, 15, "TX002", "error")]
    assert found[0].message == "xacro: name 'prefix' is not defined"


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
