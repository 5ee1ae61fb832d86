"""``roundtrip A --against B`` where B was written by BB's URDF exporter: what BB dropped.

The exporter (beam-bots/bb lib/bb/urdf/exporter.ex @330b7c6, build_transmission_elements/2)
writes a reduction other than 1.0 and nothing else; exporter_test.exs @330b7c6 checks that
``reversed? true`` alone exports no ``<transmission>``.
"""

from __future__ import annotations

import json
from pathlib import Path

from click.testing import CliRunner

from txtool.cli import cli

LINKS_AND_JOINTS = """
  <link name="base"/><link name="arm"/><link name="slider"/>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="arm"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="slide" type="prismatic"><parent link="arm"/><child link="slider"/>
    <limit lower="0" upper="0.2" effort="1" velocity="1"/></joint>"""
EFFORT = "<hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>"
ORIGINAL = f"""<robot name="r">{LINKS_AND_JOINTS}
  <transmission name="shoulder_trans"><type>transmission_interface/SimpleTransmission</type>
    <joint name="shoulder">{EFFORT}<offset>0.5</offset></joint>
    <actuator name="shoulder_motor"><mechanicalReduction>-50</mechanicalReduction></actuator>
  </transmission>
  <transmission name="slide_trans"><type>transmission_interface/SimpleTransmission</type>
    <joint name="slide">{EFFORT}</joint>
    <actuator name="slide_motor"><mechanicalReduction>-1</mechanicalReduction></actuator>
  </transmission>
</robot>
"""
# What BB's exporter writes for `reduction 50.0, offset 0.5 rad, reversed? true` on shoulder
# and `reduction 1.0, reversed? true` on slide (the second is not written at all).
FROM_BB = f"""<?xml version="1.0"?>
<robot name="MyApp.Robot">{LINKS_AND_JOINTS}
  <transmission name="shoulder_shoulder_motor_trans">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="shoulder"/>
    <actuator name="shoulder_motor"><mechanicalReduction>50</mechanicalReduction></actuator>
  </transmission>
</robot>
"""


def against(tmp_path: Path, a: str, b: str, *options: str) -> tuple[int, str]:
    (tmp_path / "a.urdf").write_text(a)
    (tmp_path / "b.urdf").write_text(b)
    result = CliRunner().invoke(
        cli, ["roundtrip", str(tmp_path / "a.urdf"), "--against", str(tmp_path / "b.urdf"),
              *options], catch_exceptions=False)
    return result.exit_code, result.stdout


BB_DROPPED = [
    "joint 'shoulder' (shoulder_trans): direction reversed lost: BB's URDF exporter drops "
    "'reversed?' (export with --bb-direction negative-reduction: a negative reduction "
    "survives)",
    "joint 'shoulder' (shoulder_trans): offset 0.5 lost: BB's URDF exporter writes no offset",
    "joint 'shoulder' (shoulder_trans): no <hardwareInterface>: BB's URDF exporter writes "
    "none, and ros_control skips a joint without one (TX110)",
    "joint 'slide' (slide_trans): no <transmission>: BB's URDF exporter writes none for a "
    "reduction of 1.0 (direction reversed lost)",
]


def test_what_bb_dropped_is_listed(tmp_path: Path) -> None:
    code, out = against(tmp_path, ORIGINAL, FROM_BB)
    assert code == 1
    assert [line.removeprefix("BB dropped: ") for line in out.splitlines()
            if line.startswith("BB dropped: ")] == BB_DROPPED
    code, out = against(tmp_path, ORIGINAL, FROM_BB, "--format", "json")
    assert code == 1
    assert json.loads(out)["bb_exporter_dropped"] == BB_DROPPED


def test_a_negative_reduction_survives_but_the_interface_does_not(tmp_path: Path) -> None:
    kept = FROM_BB.replace(">50<", ">-50<")
    code, out = against(tmp_path, ORIGINAL.replace("<offset>0.5</offset>", ""), kept,
                        "--format", "json")
    assert code == 1
    assert json.loads(out)["bb_exporter_dropped"] == [BB_DROPPED[2], BB_DROPPED[3]]


def test_a_file_not_written_by_bb_gets_no_bb_report(tmp_path: Path) -> None:
    code, out = against(tmp_path, ORIGINAL, ORIGINAL, "--format", "json")
    assert (code, json.loads(out)["bb_exporter_dropped"]) == (0, [])
