"""``convert --to bb``: Beam Bots actuators with their transmissions, nested in the joint.

BB (beam-bots/bb, PR #110 squash 23b6bde) puts ``transmission`` inside an ``actuator`` inside
the ``joint`` (lib/bb/dsl.ex:209-247, :274-282). The offset is an angle on revolute and
continuous joints and a length on prismatic ones (lib/bb/dsl/validate_limit_units_transformer.ex
:92-106). ``motor = sign * reduction * (joint - offset)`` with ``sign = -1`` when ``reversed?``
(lib/bb/transmission.ex:46-47, :84-85).
"""

from __future__ import annotations

import re
from pathlib import Path

from click.testing import CliRunner
from hypothesis import given, settings
from hypothesis import strategies as st

from txtool.cli import cli
from txtool.io.xmlio import Source, parse_bytes
from txtool.transform.bb.actuators import DIRECTIONS, decimal_text, elixir_float
from txtool.transform.bb.export import export_bb

LINKS = """<link name="base"/><link name="arm"/><link name="slider"/><link name="rim"/>"""
JOINTS = """
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="arm"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="slide" type="prismatic"><parent link="arm"/><child link="slider"/>
    <limit lower="0" upper="0.2" effort="1" velocity="1"/></joint>
  <joint name="wheel" type="continuous"><parent link="arm"/><child link="rim"/></joint>"""


def robot(body: str, joints: str = JOINTS, links: str = LINKS) -> str:
    return f'<robot name="r">{links}{joints}\n{body}\n</robot>\n'


def ros1(name: str, joint: str, actuator: str, reduction: str, offset: str | None = None,
         joint_extra: str = "") -> str:
    off = f"<offset>{offset}</offset>" if offset is not None else ""
    return f"""<transmission name="{name}"><type>transmission_interface/SimpleTransmission</type>
      <joint name="{joint}"><hardwareInterface>hardware_interface/EffortJointInterface
      </hardwareInterface>{off}{joint_extra}</joint>
      <actuator name="{actuator}"><mechanicalReduction>{reduction}</mechanicalReduction>
      </actuator></transmission>"""


def ros2(body: str) -> str:
    return f"""<ros2_control name="hw" type="system"><hardware><plugin>x/Y</plugin></hardware>
      <joint name="shoulder"/>{body}</ros2_control>"""


def convert(tmp_path: Path, xml: str, *options: str) -> tuple[int, str, str]:
    path = tmp_path / "robot.urdf"
    path.write_text(xml)
    result = CliRunner().invoke(cli, ["convert", str(path), "--to", "bb", *options],
                                catch_exceptions=False)
    return result.exit_code, result.stdout, result.stderr


THREE = "".join([
    ros1("shoulder_trans", "shoulder", "shoulder_motor", "101"),
    ros1("slide_trans", "slide", "slide_motor", "-12.5", "0.01"),
    ros1("wheel_trans", "wheel", "wheel_motor", "-1", "0.5"),
])


def test_each_actuator_holds_its_transmission_inside_its_joint(tmp_path: Path) -> None:
    code, out, err = convert(tmp_path, robot(THREE))
    assert code == 0
    assert out == """\
# Merge each actuator into the joint of that name in your BB robot's topology.
joint :shoulder do
  # transmission 'shoulder_trans'
  actuator :shoulder_motor, Driver do
    transmission do
      reduction 101.0
    end
  end
end

joint :slide do
  # transmission 'slide_trans'
  actuator :slide_motor, Driver do
    transmission do
      reduction 12.5
      offset ~u(0.01 meter)
      reversed? true
    end
  end
end

joint :wheel do
  # transmission 'wheel_trans'
  actuator :wheel_motor, Driver do
    transmission do
      reduction 1.0
      offset ~u(0.5 radian)
      reversed? true
    end
  end
end
"""
    assert err == (
        "note: 'Driver' stands for your actuator module (BB's URDF importer cannot choose one "
        "either)\n"
        "note: direction: slide, wheel run reversed, written as 'reversed? true'; BB's URDF "
        "exporter drops it (--bb-direction negative-reduction writes a negative reduction, which "
        "it keeps)\n")


def test_negative_reduction_direction_keeps_the_sign_and_says_so(tmp_path: Path) -> None:
    code, out, err = convert(tmp_path, robot(THREE), "--bb-direction", "negative-reduction")
    assert code == 0
    assert "reversed?" not in out
    assert "      reduction -12.5\n      offset ~u(0.01 meter)\n" in out
    assert "      reduction -1.0\n      offset ~u(0.5 radian)\n" in out
    assert "      reduction 101.0\n" in out
    assert ("note: direction: slide, wheel run reversed, written as a negative reduction (BB's "
            "URDF exporter keeps it; 'reversed?' it would drop)\n") in err


def test_two_actuators_of_one_joint_share_its_block(tmp_path: Path) -> None:
    body = ros1("a", "shoulder", "m1", "2") + ros1("b", "shoulder", "m2", "3")
    code, out, _ = convert(tmp_path, robot(body))
    assert code == 0
    assert out.count("joint :shoulder do") == 1
    assert "  actuator :m1, Driver do" in out and "  actuator :m2, Driver do" in out


def test_identity_transmission_is_a_bare_actuator(tmp_path: Path) -> None:
    code, out, _ = convert(tmp_path, robot(ros1("t", "shoulder", "m", "1")))
    assert code == 0
    assert out.endswith("joint :shoulder do\n"
                        "  # transmission 't': reduction 1, no offset, nothing to declare\n"
                        "  actuator :m, Driver\n"
                        "end\n")


def test_ros2_reduction_and_offset_come_from_the_joint(tmp_path: Path) -> None:
    body = ros2("""<transmission name="t"><plugin>transmission_interface/SimpleTransmission
      </plugin><actuator name="m" role="actuator1"/>
      <joint name="shoulder" role="joint1"><mechanical_reduction>-3</mechanical_reduction>
      <offset>-0.25</offset></joint></transmission>""")
    code, out, _ = convert(tmp_path, robot(body))
    assert code == 0
    assert ("    transmission do\n      reduction 3.0\n      offset ~u(-0.25 radian)\n"
            "      reversed? true\n    end\n") in out


def test_names_follow_bb_importer(tmp_path: Path) -> None:
    """lib/bb/urdf/importer.ex @64ab268: atom_name/1 (:485-493) and the ``_joint`` rename of a
    joint that shares a link's name (:137-173)."""
    links = '<link name="base"/><link name="arm"/><link name="hand"/>'
    joints = """<joint name="weird-name.1" type="revolute"><parent link="base"/>
        <child link="arm"/></joint>
      <joint name="arm" type="revolute"><parent link="arm"/><child link="hand"/></joint>"""
    body = ros1("t1", "weird-name.1", "2nd motor", "5") + ros1("t2", "arm", "arm.motor", "7")
    code, out, _ = convert(tmp_path, robot(body, joints, links))
    assert code == 0
    assert """\
joint :weird_name_1 do
  # transmission 't1' (joint 'weird-name.1', actuator '2nd motor')
  actuator :_2nd_motor, Driver do""" in out
    assert """\
joint :arm_joint do
  # transmission 't2' (joint 'arm', actuator 'arm.motor')
  actuator :arm_motor, Driver do""" in out


def test_number_literals() -> None:
    # reduction is typed float in BB (lib/bb/dsl.ex:226-232): 50 must be written 50.0
    assert [elixir_float(v) for v in (50.0, -3.0, 0.5, 1e-05, 1.5e20, 325.949)] == [
        "50.0", "-3.0", "0.5", "1.0e-05", "1.5e20", "325.949"]
    # inside ~u(...) plain decimals, as BB's importer writes them
    assert [decimal_text(v) for v in (0.5, -0.25, 1e-05, 2.0, 1.5e20)] == [
        "0.5", "-0.25", "0.00001", "2", "150000000000000000000"]


def test_bb_options_need_the_bb_target(tmp_path: Path) -> None:
    path = tmp_path / "robot.urdf"
    path.write_text(robot(THREE))
    result = CliRunner().invoke(cli, ["convert", str(path), "--to", "ros1", "--bb-topology"])
    assert (result.exit_code, result.stdout, result.stderr) == (
        2, "", "txtool: --bb-direction and --bb-topology apply to --to bb only\n")


def test_bb_output_never_replaces_the_input(tmp_path: Path) -> None:
    path = tmp_path / "robot.urdf"
    path.write_text(robot(THREE))
    result = CliRunner().invoke(cli, ["convert", str(path), "--to", "bb", "-o", str(path),
                                      "--write"])
    assert (result.exit_code, result.stderr) == (
        2, f"txtool: {path}: is the input file; --to bb writes Elixir, not a robot\n")
    assert path.read_text() == robot(THREE)


NONZERO = st.floats(min_value=1e-6, max_value=1e6).flatmap(
    lambda v: st.sampled_from((v, -v)))


@settings(max_examples=60, deadline=None)
@given(n=NONZERO, o=st.floats(min_value=-10, max_value=10, allow_subnormal=False), direction=st.sampled_from(DIRECTIONS))
def test_the_bb_block_moves_the_motor_as_ros_does(n: float, o: float, direction) -> None:
    """Read back, BB's ``sign * reduction * (joint - offset)`` (lib/bb/transmission.ex:46-47)
    equals ros_control's ``n * (joint - offset)`` exactly, in either direction form."""
    xml = robot(ros1("t", "shoulder", "m", repr(n), repr(o))).encode()
    text = export_bb(Source("r.urdf", xml, parse_bytes(xml, "r.urdf")), direction=direction).text
    found = re.search(r"^ +reduction (\S+)$", text, re.M)
    r = float(found.group(1)) if found else 1.0  # a bare actuator: identity
    found = re.search(r"^ +offset ~u\((\S+) radian\)$", text, re.M)
    off = float(found.group(1)) if found else 0.0
    sign = -1.0 if "reversed? true" in text else 1.0
    if direction == "reversed":
        assert r > 0 and (sign < 0) == (n < 0)
    else:
        assert sign == 1.0 and (r < 0) == (n < 0)
    for joint in (-1.0, 0.3, 2.0):
        assert sign * r * (joint - off) == n * (joint - o)
