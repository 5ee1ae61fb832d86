from __future__ import annotations

import pytest

from tests.rules.helpers import check, problems

ROS1 = """
<robot name="r">
  <transmission name="t">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="j">
      <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
      <offset>{offset}</offset>
    </joint>
    <actuator name="m"><mechanicalReduction>{reduction}</mechanicalReduction></actuator>
  </transmission>
</robot>
"""
ROS2 = """
<robot name="r">
  <ros2_control name="hw" type="system">
    <joint name="j"/>
    <transmission name="t">
      <plugin>transmission_interface/SimpleTransmission</plugin>
      <joint name="j" role="joint1">
        <mechanical_reduction>{reduction}</mechanical_reduction>
        <offset>{offset}</offset>
      </joint>
    </transmission>
  </ros2_control>
</robot>
"""


def test_ros1_word_reduction_fires_at_the_element():
    found = problems(ROS1.format(offset="0", reduction="fifty"), select=["TX105"])
    assert [(p.line, p.column, p.code, p.severity) for p in found] == [(8, 24, "TX105", "error")]
    assert "'fifty', not a number: ros_control refuses" in found[0].message


def test_ros1_trailing_junk_loads_so_tx105_stays_silent():
    # std::stod takes the valid prefix: transmission_loader.cpp:60 @63b6afd (TX111 warns).
    assert check(ROS1.format(offset="0", reduction="50abc"), select=["TX105"]) == []


@pytest.mark.parametrize("reduction", ["1.8e308", "-1e309", "1e-400", "1e-310"])
def test_ros1_out_of_range_is_refused_not_mapped_to_inf(reduction):
    # std::stod throws std::out_of_range on ERANGE; the loader catches std::logic_error and
    # refuses: transmission_loader.cpp:60-65 @63b6afd.
    found = problems(ROS1.format(offset="0", reduction=reduction), select=["TX105"])
    assert check(ROS1.format(offset="0", reduction=reduction), select=["TX105"]) == [
        (8, 24, "TX105", "error")
    ]
    assert "out of the range of a double" in found[0].message
    assert "refuses the transmission" in found[0].message
    assert "inf" not in found[0].message


@pytest.mark.parametrize(
    "reduction",
    ["\u0665\u0660", "\u00a050", "\u200350", "", "<!-- fifty -->50"],
    ids=["arabic-indic-digits", "no-break-space", "em-space", "empty", "comment-first"],
)
def test_ros1_text_python_reads_but_cpp_does_not_is_refused(reduction):
    # Python's float() accepts Arabic-Indic digits and strips Unicode spaces; strtod does not.
    # A comment first leaves GetText() null: std::string(nullptr) throws std::logic_error.
    found = problems(ROS1.format(offset="0", reduction=reduction), select=["TX105"])
    assert [(p.code, p.severity) for p in found] == [("TX105", "error")]
    assert "not a number: ros_control refuses the transmission" in found[0].message


def test_ros1_hexadecimal_is_a_number_for_stod():
    assert check(ROS1.format(offset="0", reduction="0x10"), select=["TX105", "TX106"]) == []


def test_ros1_zero_prefix_is_zero_for_tx106():
    assert check(ROS1.format(offset="0", reduction="0abc"), select=["TX105", "TX106"]) == [
        (8, 24, "TX106", "error")
    ]


def test_ros1_inf_offset_fires():
    found = problems(ROS1.format(offset="inf", reduction="50"), select=["TX105"])
    assert [(p.line, p.column) for p in found] == [(6, 7)]
    assert "inf or nan" in found[0].message


@pytest.mark.parametrize(
    ("reduction", "offset", "where", "default"),
    # an empty element is read as absent: a warning (tests/rules/test_loader_accepts.py)
    [("fifty", "0", (7, 9), "1.0"), ("2", "nan", (8, 9), "0.0")],
)
def test_ros2_invalid_numbers_say_the_silent_default(reduction, offset, where, default):
    found = problems(ROS2.format(reduction=reduction, offset=offset), select=["TX105"])
    assert [(p.line, p.column) for p in found] == [where]
    assert f"ros2_control silently uses {default}" in found[0].message


def test_ros2_trailing_junk_is_not_accepted():
    assert check(ROS2.format(reduction="50abc", offset="0"), select=["TX105"]) == [(7, 9, "TX105", "error")]


def test_plain_numbers_pass():
    assert check(ROS1.format(offset="-0.5", reduction=" 1e2 "), select=["TX105"]) == []
    assert check(ROS2.format(reduction="+325.949", offset="0.0"), select=["TX105"]) == []


def test_ignored_values_are_not_checked():
    # ros_control's SimpleTransmission never reads a joint reduction.
    xml = ROS1.format(offset="0", reduction="50").replace(
        "<offset>", "<mechanicalReduction>fifty</mechanicalReduction><offset>"
    )
    assert check(xml, select=["TX105"]) == []


def test_literal_xacro_expressions_are_unknown():
    xml = """
    <robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
      <xacro:macro name="tr" params="n">
        <transmission name="${n}_t">
          <type>transmission_interface/SimpleTransmission</type>
          <joint name="${n}"><hardwareInterface>EffortJointInterface</hardwareInterface></joint>
          <actuator name="${n}_m"><mechanicalReduction>${r * 2}</mechanicalReduction></actuator>
        </transmission>
      </xacro:macro>
    </robot>
    """
    assert check(xml, filename="lib.xacro", select=["TX105"]) == []


@pytest.mark.parametrize(
    "reduction",
    ["\u0665\u0660", "\u00a050", "5_0", "0x10", "1.8e308", "inf", "50abc"],
)
def test_ros2_reads_the_whole_stripped_text_or_uses_the_default(reduction):
    # component_parser.cpp:134-161 @157446a, lexical_casts.cpp:28-52 @146eb98: the whole text
    # in the classic locale, failure returns the default.
    found = problems(ROS2.format(reduction=reduction, offset="0"), select=["TX105"])
    assert [(p.code, p.severity) for p in found] == [("TX105", "error")]
    assert "ros2_control silently uses 1.0" in found[0].message


def test_ros2_surrounding_c_whitespace_is_stripped():
    assert check(ROS2.format(reduction="\n   50\t ", offset="+0.5"), select=["TX105"]) == []


def test_ros2_reads_the_text_after_a_leading_comment():
    # tinyxml2 9's GetText() passes over leading comments, so the parser reads "fifty" and
    # uses the default instead of going on to the next element (component_parser.cpp:161-188
    # get_parameter_value_or @53b9999; tests/oracle compares it with the compiled parser).
    xml = ROS2.format(reduction="<!-- x -->fifty", offset="0").replace(
        "</mechanical_reduction>", "</mechanical_reduction><mechanical_reduction>4"
        "</mechanical_reduction>", 1)
    assert check(xml, select=["TX105"]) == [(7, 9, "TX105", "error")]
    assert check(ROS2.format(reduction="<!-- ratio --> 50", offset="<!-- rad -->0.5"),
                 select=["TX105"]) == []


def test_ros2_skips_an_element_whose_text_is_only_a_comment():
    xml = ROS2.format(reduction="<!-- x -->", offset="0").replace(
        "</mechanical_reduction>", "</mechanical_reduction><mechanical_reduction>4"
        "</mechanical_reduction>", 1)
    assert check(xml, select=["TX105"]) == []


@pytest.mark.parametrize(("field", "text", "humble", "jazzy"), [
    ("reduction", "+-1", "silently uses 1.0", "reads -1"),
    ("offset", "1e-400", "reads 0", "silently uses 0.0"),
])
def test_ros2_a_number_distributions_read_differently_is_a_warning(field, text, humble, jazzy):
    xml = ROS2.format(**{"reduction": "2", "offset": "0", field: text})
    found = problems(xml, select=["TX105"])
    assert [(p.line, p.severity) for p in found] == [(7 if field == "reduction" else 8,
                                                      "warning")]
    assert found[0].message.endswith(
        f"is '{text}', read differently by ROS 2 distributions: Humble's ros2_control "
        f"{humble}, Jazzy's and later {jazzy}")


def test_ros2_a_reduction_humble_reads_as_zero_is_left_to_tx106():
    xml = ROS2.format(reduction="1e-400", offset="0")
    assert check(xml, select=["TX105", "TX106"]) == [(7, 9, "TX106", "warning")]
    # from Jazzy on the text is no number: the silent default is TX105's
    assert check(xml, select=["TX105", "TX106"], **{"ros-distro": "jazzy"}) == [
        (7, 9, "TX105", "error")]


def test_ros2_whitespace_only_element_has_no_text_so_the_next_one_is_read():
    # tinyxml2 keeps no whitespace-only text node: GetText() is null and the parser goes on to
    # the next <mechanical_reduction> (component_parser.cpp:145-146 @157446a).
    xml = ROS2.format(reduction="  ", offset="0").replace(
        "</mechanical_reduction>", "</mechanical_reduction><mechanical_reduction>4"
        "</mechanical_reduction>", 1)
    assert check(xml, select=["TX105"]) == []


def test_ros1_whitespace_only_element_is_refused_as_empty():
    found = problems(ROS1.format(offset="0", reduction="   "), select=["TX105"])
    assert [(p.code, p.severity) for p in found] == [("TX105", "error")]
    assert "is empty, not a number" in found[0].message


@pytest.mark.parametrize(("distro", "shown"), [
    (None, "warning TX105"),  # Humble falls back to 0.0, Jazzy reads -1: it depends
    ("humble", "error TX105"),
    ("jazzy", None),  # from_chars after the one '+' lexical_casts.cpp drops: -1
])
def test_a_stated_distribution_decides_a_number_read_differently(tmp_path, distro, shown):
    from click.testing import CliRunner

    from txtool.cli import cli

    robot = tmp_path / "robot.urdf"
    robot.write_text(
        '<robot name="r"><link name="a"/><link name="b"/><joint name="j" type="revolute">'
        '<parent link="a"/><child link="b"/><limit effort="1" velocity="1" lower="-1" '
        'upper="1"/></joint><ros2_control name="s" type="system"><hardware><plugin>'
        'mock_components/GenericSystem</plugin></hardware><joint name="j">'
        '<command_interface name="position"/></joint><transmission name="t"><plugin>'
        'transmission_interface/SimpleTransmission</plugin><actuator name="m" role="actuator1"/>'
        '<joint name="j" role="joint1"><offset>+-1</offset></joint></transmission>'
        "</ros2_control></robot>")
    args = ["validate", "--select", "TX105", str(robot)]
    if distro:
        args += ["--ros-distro", distro]
    out = CliRunner().invoke(cli, args).stdout
    found = [line for line in out.splitlines() if "TX105" in line]
    assert [shown in line for line in found] == ([True] if shown else []), out
