"""``show --effective`` as ros2_control's parser and loaders read a transmission, per ROS 2
distribution (hardware_interface/src/component_parser.cpp and lexical_casts.cpp @53b9999;
tests/oracle checks the same against the compiled code)."""

from __future__ import annotations

import pytest
from click.testing import CliRunner

from txtool.cli import cli
from txtool.dialects.read import read_source
from txtool.io.xmlio import Source, parse_bytes
from txtool.model.distro import Distro
from txtool.views.effective import bindings_of


def component(body: str, kind: str = "system", joints: tuple[str, ...] = ("j1", "j2")) -> str:
    declared = "".join(f'<joint name="{j}"><command_interface name="position"/></joint>'
                       for j in joints)
    return (f'<robot name="r">\n<ros2_control name="hw" type="{kind}">\n{declared}\n'
            f'{body}\n</ros2_control>\n</robot>\n')


def simple(joint: str, actuator: str = '<actuator name="m" role="actuator1"/>') -> str:
    return ('<transmission name="t"><plugin>transmission_interface/SimpleTransmission</plugin>'
            f"{joint}{actuator}</transmission>")


def bound(xml: str, distro: Distro | None = None):
    data = xml.encode()
    found = read_source(Source("r.urdf", data, parse_bytes(data, "r.urdf")))
    return bindings_of(found, distro)[0]


def show(tmp_path, xml: str) -> tuple[int, str]:
    path = tmp_path / "r.urdf"
    path.write_text(xml)
    result = CliRunner().invoke(cli, ["show", "--effective", str(path)], catch_exceptions=False)
    return result.exit_code, result.stdout


@pytest.mark.parametrize(("text", "humble", "jazzy"), [
    ("+-1", 1.0, -1.0),     # from_chars reads it after the one '+' is dropped
    ("1e-400", 0.0, 1.0),   # istringstream keeps the underflow (0 refuses to load), from_chars not
    ("0x10", 1.0, 1.0),     # neither reads hexadecimal: the default
])
def test_each_distribution_reads_its_own_number(text, humble, jazzy):
    xml = component(simple(
        f'<joint name="j1" role="joint1"><mechanical_reduction>{text}</mechanical_reduction>'
        "</joint>"))
    for distro, value in ((Distro.HUMBLE, humble), (Distro.JAZZY, jazzy),
                          (Distro.KILTED, jazzy), (Distro.ROLLING, jazzy)):
        b = bound(xml, distro)
        if value == 0.0:
            assert (b.loadable, b.reason) == (False, "reduction ratio cannot be zero")
        else:
            assert [s.joint_reduction for s in b.slots] == [value]


def test_show_effective_gives_both_readings_where_they_differ(tmp_path):
    xml = component(simple(
        '<joint name="j1" role="joint1"><mechanical_reduction>+-1</mechanical_reduction>'
        "</joint>"))
    code, out = show(tmp_path, xml)
    assert code == 0
    assert "  0   j1             -1   0 (default)   m          (not read)\n" in out
    assert ("note: ROS 2 distributions read the numbers differently: Humble binds #0 joint "
            "reduction 1\n    (default) offset 0 (default); Jazzy, Kilted and Rolling bind #0 "
            "joint reduction -1 offset 0\n    (default)\n") in out


def test_a_leading_comment_is_passed_over_on_ros2_only(tmp_path):
    ros2 = component(simple('<joint name="j1" role="joint1"><mechanical_reduction>'
                            "<!-- ratio -->50</mechanical_reduction></joint>"))
    assert [s.joint_reduction for s in bound(ros2).slots] == [50.0]
    ros1 = ('<robot name="r"><transmission name="t">'
            "<type>transmission_interface/SimpleTransmission</type>"
            '<joint name="j1"><hardwareInterface>hardware_interface/PositionJointInterface'
            '</hardwareInterface></joint><actuator name="m"><mechanicalReduction>'
            "<!-- ratio -->50</mechanicalReduction></actuator></transmission></robot>")
    b = bound(ros1)
    assert (b.loadable, b.reason) == (False, "'m' reduction '' is not a number")


def test_names_are_stripped_and_handles_sorted_by_the_stripped_names():
    members = ('<joint name=" zz " role="joint1"/><joint name="\taa" role="joint2"/>'
               '<actuator name="m1" role="actuator1"/><actuator name="m2" role="actuator2"/>')
    xml = component('<transmission name=" t "><plugin> transmission_interface/'
                    f'DifferentialTransmission </plugin>{members}</transmission>',
                    joints=("aa", "zz"))
    b = bound(xml)
    assert b.loadable
    assert [(s.joint, s.joint_parameters_of) for s in b.slots] == [("aa", "zz"), ("zz", "aa")]


@pytest.mark.parametrize(("member", "reason"), [
    ('<joint name="j1"><role>joint1</role></joint>',
     "a <joint> of transmission 't' has no role"),
    ('<joint name="j1" role="joint1" read_only="yes"/>',
     '<joint name="j1"> read_only="yes" is not true or false'),
    ('<joint role="joint1"/>', "a <joint> of transmission 't' has no name"),
])
def test_what_the_parser_throws_on_refuses_the_component(member, reason):
    b = bound(component(simple(member)))
    assert (b.loadable, b.reason) == (
        False, f"ros2_control's parser refuses the component: {reason}")


def test_read_only_is_stripped_before_parse_bool():
    b = bound(component(simple('<joint name="j1" role="joint1" read_only=" TRUE "/>')))
    assert b.loadable


def test_an_actuator_component_appends_actuator1(tmp_path):
    one = '<joint name="j1" role="joint1"><mechanical_reduction>3</mechanical_reduction></joint>'
    code, out = show(tmp_path, component(simple(one, ""), kind="actuator", joints=("j1",)))
    assert code == 0
    assert "  0   j1              3   0 (default)   actuator1   (not read)\n" in out
    assert ("note: ros2_control's parser appends actuator 'actuator1' (reduction 1, offset 0) "
            "to a transmission\n    of an actuator component\n") in out
    # a listed actuator beside the appended one: SimpleTransmission::configure refuses two names
    b = bound(component(simple(one), kind="actuator", joints=("j1",)))
    assert (b.loadable, b.added_actuators) == (False, ("actuator1",))
    assert b.reason == ("a simple transmission takes one actuator, found 'm', 'actuator1' "
                        "(configure: actuator names should be identical)")
