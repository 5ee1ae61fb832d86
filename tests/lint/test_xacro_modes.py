"""Which tree the rules see for xacro files, and where their findings point."""

from __future__ import annotations

from pathlib import Path

from tests.rules.helpers import problems, snippet
from txtool.io.load import load
from txtool.lint.api import lint_source
from txtool.lint.config import resolve
from txtool.lint.problem import Note

MACRO = """
<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="tr" params="n r">
    <transmission name="${{n}}_t">
      <type>transmission_interface/SimpleTransmission</type>
      <joint name="${{n}}"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>
      <actuator name="${{n}}_m"><mechanicalReduction>${{r}}</mechanicalReduction></actuator>
    </transmission>
  </xacro:macro>
  {calls}
</robot>
"""


def test_expanded_findings_point_at_the_argument_of_the_call_the_macro_related():
    """The mistake is the call's argument ``r="0"``: the finding is there, the macro's line
    that used it related ("in expansion of macro ...")."""
    xml = MACRO.format(calls='<xacro:tr n="a" r="0"/>\n  <xacro:tr n="b" r="50"/>')
    found = problems(xml, filename="r.urdf.xacro", select=["TX106"])
    assert [(p.line, p.column) for p in found] == [(9, 19)]
    assert "actuator 'a_m' of transmission 'a_t'" in found[0].message
    [note] = found[0].related
    assert note == Note(found[0].path, 6, 31,
                        "in expansion of macro 'tr' defined at r.urdf.xacro:2")


def test_a_macro_library_is_checked_as_written_with_exact_positions():
    xml = MACRO.format(calls="").replace("${r}", "0")
    found = problems(xml, filename="lib.xacro", select=["TX106"])
    assert [(p.line, p.column) for p in found] == [(6, 31)]
    assert "after xacro expansion" not in found[0].message
    assert "actuator '${n}_m'" in found[0].message


def test_a_file_that_calls_its_macros_is_checked_on_the_expansion_only():
    xml = MACRO.format(calls='<xacro:tr n="a" r="50"/>').replace("${r}", "0")
    found = problems(xml, filename="r.urdf.xacro", select=["TX106"])
    assert [(p.line, "a_m" in p.message) for p in found] == [(6, True)]


def test_no_xacro_checks_the_literal_file(tmp_path):
    xml = MACRO.format(calls='<xacro:tr n="a" r="0"/>')
    assert problems(xml, filename="r.urdf.xacro", select=["TX106"], no_xacro=True) == []


def test_lint_source_for_callers_with_a_loaded_source(tmp_path):
    path = tmp_path / "r.urdf.xacro"
    path.write_text(snippet(MACRO.format(calls='<xacro:tr n="a" r="0"/>')))
    source = load(str(path))
    found = lint_source(source)
    assert [(p.line, p.code, p.severity, p.name) for p in found] == [
        (9, "TX106", "error", "zero-reduction")
    ]
    assert lint_source(source, resolve(None)) == found
    assert lint_source(load(str(path), expand=False)) == []  # ${r} is unknown as written


LIBRARY = """<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="tr" params="n r">
    <transmission name="${n}_t">
      <type>transmission_interface/SimpleTransmission</type>
      <joint name="${n}"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>
      <actuator name="${n}_m"><mechanicalReduction>${r}</mechanicalReduction></actuator>
    </transmission>
  </xacro:macro>
</robot>
"""


def lint_with_library(tmp_path, calls: str) -> list:
    (tmp_path / "lib.xacro").write_text(LIBRARY)
    robot = tmp_path / "robot.urdf.xacro"
    robot.write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:include filename="lib.xacro"/>\n'
        '  <link name="base"/>\n'
        f"{calls}"
        "</robot>\n"
    )
    return lint_source(load(str(robot)), resolve(None))


def test_a_transmission_made_by_an_included_macro_points_at_its_call(tmp_path):
    found = lint_with_library(
        tmp_path, '  <xacro:tr n="left" r="50"/>\n  <xacro:tr n="right" r="0"/>\n'
    )
    zero = [p for p in found if p.code == "TX106"]
    assert [(p.line, p.column) for p in zero] == [(5, 23)]  # r="0"
    assert "'right_m'" in zero[0].message
    [note] = zero[0].related  # where the macro uses it, in the file that defines it
    assert (Path(note.path).name, note.line, note.column, note.message) == (
        "lib.xacro", 6, 31, "in expansion of macro 'tr' defined at lib.xacro:2")


def test_a_call_under_a_conditional_is_found_in_it(tmp_path):
    found = lint_with_library(
        tmp_path,
        '  <xacro:tr n="up" r="50"/>\n'
        '  <link name="tip"/>\n'
        '  <xacro:if value="true">\n'
        '    <xacro:tr n="down" r="0"/>\n'
        "  </xacro:if>\n",
    )
    zero = [p for p in found if p.code == "TX106"]
    assert [(p.line, p.column) for p in zero] == [(7, 24)]  # r="0"


def test_calls_inside_a_literal_element_are_found_one_level_down(tmp_path):
    found = lint_with_library(
        tmp_path,
        '  <xacro:tr n="first" r="0"/>\n'
        '  <ros2_control name="arm" type="system">\n'
        '    <hardware><plugin>mock_components/GenericSystem</plugin></hardware>\n'
        '    <joint name="first"><command_interface name="effort"/></joint>\n'
        '    <xacro:tr n="second" r="0"/>\n'
        "  </ros2_control>\n",
    )
    assert [(p.line, p.column) for p in found if p.code == "TX106"] == [(4, 23)]
    inside = [p for p in found if "second" in p.message]
    assert inside and {p.line for p in inside} == {8}  # the call, or its argument


def test_of_fifty_calls_the_two_with_wrong_arguments_are_marked(tmp_path):
    """Each finding at the argument of its call, none on the macro's lines."""
    calls = "\n".join(
        f'  <xacro:tr n="j{i}" r="{0 if i == 17 else 50}"/>' for i in range(50))
    path = tmp_path / "fifty.urdf.xacro"
    path.write_text(snippet(MACRO.format(calls=calls)))
    found = lint_source(load(str(path)))
    first_call = 9  # after the macro's eight lines
    assert [(p.line, p.column, p.code) for p in found] == [(first_call + 17, 21, "TX106")]
    assert "'j17_m'" in found[0].message
