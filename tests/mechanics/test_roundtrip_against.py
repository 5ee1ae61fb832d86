"""``txtool roundtrip A --against B``: each file's efforts through its own loader's maths."""

from __future__ import annotations

import json
from pathlib import Path

from click.testing import CliRunner

from txtool.cli import cli

# ar (50, -50), jr (2, -2), off (0.5, -0.5); a_joint is joint1 by role, XML order and name.
ROS1 = """<robot name="r"><transmission name="fb">
  <type>transmission_interface/FourBarLinkageTransmission</type>
  <joint name="a_joint"><role>joint1</role><offset>0.5</offset>
    <mechanicalReduction>2</mechanicalReduction>
    <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>
  <joint name="b_joint"><role>joint2</role><offset>-0.5</offset>
    <mechanicalReduction>-2</mechanicalReduction>
    <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>
  <actuator name="a_motor"><role>actuator1</role><mechanicalReduction>50</mechanicalReduction>
  </actuator>
  <actuator name="b_motor"><role>actuator2</role><mechanicalReduction>-50</mechanicalReduction>
  </actuator></transmission></robot>"""

ROS2 = """<robot name="r"><ros2_control name="hw" type="system">
  <joint name="a_joint"><command_interface name="effort"/></joint>
  <joint name="b_joint"><command_interface name="effort"/></joint>
  <transmission name="fb"><plugin>transmission_interface/FourBarLinkageTransmission</plugin>
    <joint name="a_joint" role="joint1"><mechanical_reduction>2</mechanical_reduction>
      <offset>0.5</offset></joint>
    <joint name="b_joint" role="joint2"><mechanical_reduction>-2</mechanical_reduction>
      <offset>-0.5</offset></joint>
    <actuator name="a_motor" role="actuator1"><mechanical_reduction>50</mechanical_reduction>
    </actuator>
    <actuator name="b_motor" role="actuator2"><mechanical_reduction>-50</mechanical_reduction>
    </actuator></transmission></ros2_control></robot>"""


def run(*args: str) -> tuple[int, str, str]:
    result = CliRunner().invoke(cli, ["roundtrip", *args])
    return result.exit_code, result.stdout, result.stderr


def pair(tmp_path: Path) -> tuple[str, str]:
    (tmp_path / "a.urdf").write_text(ROS1)
    (tmp_path / "b.urdf").write_text(ROS2)
    return str(tmp_path / "a.urdf"), str(tmp_path / "b.urdf")


def test_by_default_a_ros1_four_bar_and_its_ros2_twin_differ_in_effort(tmp_path):
    a, b = pair(tmp_path)
    code, out, err = run(a, "--against", b, "--format", "json")
    assert (code, err) == (1, "")
    (row,) = json.loads(out)["transmissions"]
    assert row["status"] == "differs"
    assert row["differences"]["position"] == row["differences"]["velocity"] == 0.0
    assert row["reason"].startswith("actuator 'b_motor' effort differs by ")


def test_one_convention_for_both_files_makes_them_equivalent(tmp_path):
    a, b = pair(tmp_path)
    for convention in ("ros1", "ros2"):
        code, out, err = run(a, "--against", b, "--effort-convention", convention,
                             "--format", "json")
        assert (code, err) == (0, "")
        assert json.loads(out)["ok"] is True


def test_effort_convention_needs_against(tmp_path):
    a, _ = pair(tmp_path)
    assert run(a, "--effort-convention", "ros2") == (
        2, "", "txtool: --effort-convention applies to --against only\n")


def test_text_says_which_effort_maps_ran(tmp_path):
    a, b = pair(tmp_path)
    code, out, err = run(a, "--against", b)
    assert (code, err) == (1, "")
    assert out.splitlines()[-1] == "efforts: each file through its own loader's maps"
    code, out, err = run(a, "--against", b, "--effort-convention", "ros1")
    assert (code, err) == (0, "")
    assert out.splitlines()[-1] == "efforts: ros1 maps for both (--effort-convention)"
