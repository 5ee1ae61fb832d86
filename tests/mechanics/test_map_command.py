"""``txtool map`` through the CLI."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

from tests.corpus import corpus_file
from txtool.cli import cli
from txtool.mechanics.maps import from_parameters

FIXTURE = str(Path(__file__).parents[2] / "fixtures" / "differential_golden.urdf")


def run(*args: str) -> tuple[int, str, str]:
    result = CliRunner().invoke(cli, ["map", *args])
    return result.exit_code, result.stdout, result.stderr


def test_differential_golden_to_joint_text() -> None:
    code, out, err = run(FIXTURE, "-t", "wrist_trans", "--to", "joint", "--position", "3,5")
    assert (code, err) == (0, "")
    assert "transmission 'wrist_trans': actuator -> joint" in out
    row = next(line for line in out.splitlines() if "position" in line)
    assert [cell.strip() for cell in row.split("│")[1:4]] == ["position", "-2.0125", "4.06875"]
    assert "joint 'wrist_pitch'" in out and "joint 'wrist_roll'" in out


def test_differential_golden_json_both_ways() -> None:
    code, out, err = run(FIXTURE, "-t", "wrist_trans", "--to", "joint", "--position", "3,5",
                         "--velocity", "3,5", "--effort", "3,5", "--format", "json")
    assert (code, err) == (0, "")
    data = json.loads(out)
    assert list(data) == ["position", "velocity", "effort"]
    np.testing.assert_allclose(data["position"], [-2.0125, 4.06875], rtol=0, atol=1e-12)
    np.testing.assert_allclose(data["velocity"], [-0.0125, 0.06875], rtol=0, atol=1e-12)
    np.testing.assert_allclose(data["effort"], [140, 520], rtol=0, atol=1e-12)
    code, out, err = run(FIXTURE, "-t", "wrist_trans", "--to", "actuator",
                         "--position", "-2.0125,4.06875", "--effort", "140,520",
                         "--format", "json")
    assert (code, err) == (0, "")
    data = json.loads(out)
    assert list(data) == ["position", "effort"]
    np.testing.assert_allclose(data["position"], [3, 5], rtol=0, atol=1e-12)
    np.testing.assert_allclose(data["effort"], [3, 5], rtol=0, atol=1e-12)


def test_back_to_actuator_text_reads_3_and_5() -> None:
    code, out, _ = run(FIXTURE, "-t", "wrist_trans", "--to", "actuator", "--position",
                       "-2.0125,4.06875")
    assert code == 0
    row = next(line for line in out.splitlines() if "position" in line)
    assert [cell.strip() for cell in row.split("│")[1:4]] == ["position", "3", "5"]


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["-t", "nope", "--position", "1,2"],
         "no transmission named 'nope' (transmissions: 'wrist_trans')"),
        (["-t", "wrist_trans", "--position", "1"],
         "--position needs 2 value(s) for transmission 'wrist_trans', got 1"),
        (["-t", "wrist_trans", "--velocity", "1,two"], "--velocity: 'two' is not a number"),
        (["-t", "wrist_trans", "--effort", "1,nan"], "--effort: 'nan' is not a number"),
        (["-t", "wrist_trans"], "nothing to map: give --position, --velocity or --effort"),
    ],
)
def test_user_errors(args: list[str], message: str) -> None:
    code, out, err = run(FIXTURE, "--to", "actuator", *args)
    assert (code, out, err) == (2, "", f"txtool: {FIXTURE}: {message}\n")


def write(tmp_path: Path, body: str) -> str:
    path = tmp_path / "robot.urdf"
    path.write_text(f'<robot name="r">{body}</robot>')
    return str(path)


def test_custom_type_and_zero_reduction(tmp_path: Path) -> None:
    path = write(tmp_path, """
      <transmission name="odd"><type>acme/Wrist</type><joint name="j"/></transmission>
      <transmission name="zero"><type>transmission_interface/SimpleTransmission</type>
        <joint name="j"><hardwareInterface>hardware_interface/EffortJointInterface
        </hardwareInterface></joint>
        <actuator name="m"><mechanicalReduction>0</mechanicalReduction></actuator>
      </transmission>""")
    code, out, err = run(path, "-t", "odd", "--to", "actuator", "--position", "1")
    assert (code, out) == (2, "")
    assert err == (f"txtool: {path}: transmission 'odd' cannot be loaded: custom type "
                   f"'acme/Wrist' has no standard maths\n")
    code, out, err = run(path, "-t", "zero", "--to", "joint", "--position", "1")
    assert (code, out) == (2, "")
    assert err == (f"txtool: {path}: transmission 'zero' cannot be loaded: reduction ratio "
                   f"cannot be zero\n")


def test_missing_file() -> None:
    code, out, err = run("no/such.urdf", "-t", "x", "--to", "joint", "--position", "1")
    assert (code, out, err) == (2, "", "txtool: no/such.urdf: no such file\n")


ROS2_DIFF = """<ros2_control name="hw" type="system"><hardware><plugin>x/Y</plugin></hardware>
  <joint name="zeta"/><joint name="alpha"/>
  <transmission name="t"><plugin>transmission_interface/DifferentialTransmission</plugin>
    <actuator name="zeta_motor" {r1}><mechanical_reduction>10</mechanical_reduction></actuator>
    <actuator name="alpha_motor" {r2}><mechanical_reduction>-20</mechanical_reduction></actuator>
    <joint name="zeta" {j1}><mechanical_reduction>-2</mechanical_reduction>
      <offset>-2</offset></joint>
    <joint name="alpha" {j2}><mechanical_reduction>4</mechanical_reduction>
      <offset>4</offset></joint>
  </transmission></ros2_control>"""


@pytest.mark.parametrize("roles", [True, False])
def test_ros2_values_are_in_role_order_and_run_as_ros2_control_binds_them(
    tmp_path: Path, roles: bool
) -> None:
    attrs = dict(r1='role="actuator1"', r2='role="actuator2"', j1='role="joint1"',
                 j2='role="joint2"')
    if not roles:  # without roles, XML order stands in for role order
        attrs = dict.fromkeys(attrs, "")
    path = write(tmp_path, ROS2_DIFF.format(**attrs))
    code, out, err = run(path, "-t", "t", "--to", "joint", "--position", "3,5", "--format",
                         "json")
    assert (code, err) == (0, "")
    # ros2_control: parameters in XML order (zeta's first), handles by name: index 0 is alpha.
    tmap = from_parameters("t", "differential", (10, -20), (-2, 4), (-2, 4),
                           joints=("alpha", "zeta"), actuators=("alpha_motor", "zeta_motor"))
    by_index = tmap.actuator_to_joint("position", [5.0, 3.0])  # alpha_motor=5, zeta_motor=3
    # Printed in role order: zeta (joint1), alpha (joint2).
    np.testing.assert_allclose(json.loads(out)["position"], [by_index[1], by_index[0]],
                               rtol=0, atol=1e-12)
    # ... which is not what the same numbers give under ROS 1's role binding.
    assert not np.allclose(json.loads(out)["position"], [-2.0125, 4.06875])


def test_negative_values_without_equals_sign() -> None:
    code, out, _ = run(FIXTURE, "-t", "wrist_trans", "--to", "actuator", "--velocity",
                       "-0.0125,0.06875", "--format", "json")
    assert code == 0
    np.testing.assert_allclose(json.loads(out)["velocity"], [3, 5], rtol=0, atol=1e-12)


def test_effort_convention_follows_the_file_loader(tmp_path: Path) -> None:
    # The four-bar golden vector (ar 10,-20; jr -2,4; actuator efforts 3,5): ros_control's map
    # gives joint efforts (-60, -160), ros2_control's power-conserving one (-160, -400).
    path = write(tmp_path, """<transmission name="fb">
      <type>transmission_interface/FourBarLinkageTransmission</type>
      <actuator name="m1"><role>actuator1</role><mechanicalReduction>10</mechanicalReduction>
      </actuator><actuator name="m2"><role>actuator2</role>
      <mechanicalReduction>-20</mechanicalReduction></actuator>
      <joint name="j1"><role>joint1</role><mechanicalReduction>-2</mechanicalReduction>
      <offset>-2</offset><hardwareInterface>hardware_interface/EffortJointInterface
      </hardwareInterface></joint>
      <joint name="j2"><role>joint2</role><mechanicalReduction>4</mechanicalReduction>
      <offset>4</offset><hardwareInterface>hardware_interface/EffortJointInterface
      </hardwareInterface></joint></transmission>""")
    base = [path, "-t", "fb", "--to", "joint", "--effort", "3,5", "--format", "json"]
    assert run(*base) == (0, '{"effort": [-60.0, -160.0]}\n', "")
    assert run(*base, "--effort-convention", "ros1") == (0, '{"effort": [-60.0, -160.0]}\n', "")
    assert run(*base, "--effort-convention", "ros2") == (0, '{"effort": [-160.0, -400.0]}\n', "")


CORPUS_ROS1 = "ros_control__four_bar_linkage_transmission_loader_full.urdf"
CORPUS_ROS2 = "ros2_control_test_assets__minimal_robot_hardware_resources.urdf"


@pytest.mark.parametrize(("name", "transmission", "override", "efforts", "caption"), [
    # ar (50, -50), jr (2, -2) in both loader test robots; actuator efforts (1, 1). The ROS 1
    # robot lists bar_joint (role joint2) first, and ros_control fills its joint data in XML
    # order (joint_state_interface_provider.cpp:132 @133d768): bar_joint gets index 0, so the
    # columns (foo_joint, bar_joint, in role order) show index 1's value first.
    (CORPUS_ROS1, "four_bar_linkage_trans", None, ("300", "100"),
     "ros1 (ros_control's map, from the file's loader)"),
    (CORPUS_ROS1, "four_bar_linkage_trans", "ros2", ("100", "50"),
     "ros2 (ros2_control's map, from --effort-convention)"),
    (CORPUS_ROS2, "four_bar_transmission", None, ("50", "100"),
     "ros2 (ros2_control's map, from the file's loader)"),
    (CORPUS_ROS2, "four_bar_transmission", "ros1", ("100", "300"),
     "ros1 (ros_control's map, from --effort-convention)"),
])
def test_corpus_four_bars_map_efforts_as_their_loader(name, transmission, override, efforts,
                                                      caption) -> None:
    args = [str(corpus_file(name)), "-t", transmission, "--to", "joint", "--effort", "1,1"]
    code, out, err = run(*args, *(["--effort-convention", override] if override else []))
    assert (code, err) == (0, "")
    row = next(line for line in out.splitlines() if "effort" in line and "│" in line)
    assert tuple(cell.strip() for cell in row.split("│")[2:4]) == efforts
    assert out.splitlines()[-1] == f"effort convention: {caption}"


def test_command_module_does_not_import_numpy() -> None:
    code = "import sys, txtool.commands.map; print('numpy' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"
