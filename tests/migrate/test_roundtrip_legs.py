"""roundtrip converts each text once per dialect: a first leg serves every group that starts
with it, and a last leg whose text was already converted to the same dialect is not run
again. The rows are those of converting every cycle in full."""

from __future__ import annotations

import json
import os
from pathlib import Path

import pytest
from click.testing import CliRunner

from tests.corpus import corpus_file
from txtool.cli import cli
from txtool.io.load import load
from txtool.transform import roundtrip as module
from txtool.transform.roundtrip import roundtrip

FIXTURES = Path(__file__).resolve().parents[2] / "fixtures"
MIXED = """<robot name="r">
  <joint name="a" type="revolute"><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="b" type="revolute"><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <transmission name="ta">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="a"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
    </joint>
    <actuator name="ma"><mechanicalReduction>-7</mechanicalReduction></actuator>
  </transmission>
  <ros2_control name="s" type="system">
    <hardware><plugin>mock_components/GenericSystem</plugin></hardware>
    <joint name="b"><command_interface name="effort"/><state_interface name="position"/></joint>
    <transmission name="tb">
      <plugin>transmission_interface/SimpleTransmission</plugin>
      <joint name="b" role="joint1"><offset>0.5</offset></joint>
      <actuator name="mb" role="actuator1"><mechanical_reduction>3</mechanical_reduction></actuator>
    </transmission>
  </ros2_control>
</robot>
"""


def counted(monkeypatch: pytest.MonkeyPatch) -> list[str]:
    """The target of every conversion roundtrip makes from now on."""
    targets: list[str] = []
    convert = module.convert_source

    def spy(source, target, **options):
        targets.append(target)
        return convert(source, target, **options)

    monkeypatch.setattr(module, "convert_source", spy)
    return targets


def in_full(monkeypatch: pytest.MonkeyPatch) -> None:
    """Every text looks new: each cycle converts all its legs."""

    monkeypatch.setattr(module, "_digest", lambda data: os.urandom(16))


@pytest.mark.parametrize("path", [
    FIXTURES / "demo_robot.urdf", FIXTURES / "demo_robot.ros2-p1.urdf", "MIXED",
    FIXTURES / "examples" / "arm.urdf.xacro",
    "ros_control__transmission_interface_loader_bidirectional_valid.urdf",
], ids=lambda p: getattr(p, "name", p))
def test_the_rows_are_those_of_every_cycle_converted_in_full(
        path: Path | str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    if path == "MIXED":
        path = tmp_path / "mixed.urdf"
        path.write_text(MIXED)
    elif isinstance(path, str):
        path = corpus_file(path)
    short = roundtrip(load(str(path)), consume=True)
    in_full(monkeypatch)
    full = roundtrip(load(str(path)))
    assert short.rows and short.to_json() == full.to_json()


def test_a_ros1_robot_needs_six_conversions(monkeypatch: pytest.MonkeyPatch) -> None:
    """ros1 -> ros2-p1 -> ros2-p2 writes what ros1 -> ros2-p2 wrote (and the other way), so
    its last leg is the one ros1 -> ros2-p2 -> ros1 takes: 2 first legs and 4 more."""
    targets = counted(monkeypatch)
    report = roundtrip(load(str(FIXTURES / "demo_robot.urdf")))
    assert sorted(targets) == ["ros1", "ros1", "ros2-p1", "ros2-p1", "ros2-p2", "ros2-p2"]
    assert len(report.rows) == 4 * 2 and report.ok


def test_a_mixed_document_converts_each_first_leg_once(tmp_path: Path,
                                                       monkeypatch: pytest.MonkeyPatch) -> None:
    path = tmp_path / "mixed.urdf"
    path.write_text(MIXED)
    firsts: list[str] = []
    convert = module.convert_source

    def spy(source, target, **options):
        if source.data == MIXED.encode():
            firsts.append(target)
        return convert(source, target, **options)

    monkeypatch.setattr(module, "convert_source", spy)
    report = roundtrip(load(str(path)))
    assert firsts == ["ros2-p1", "ros2-p2", "ros1"]  # ros2-p1 serves both groups
    assert {row.cycle[0] for row in report.rows} == {"ros1", "ros2-p2"}


def test_consume_gives_up_the_tree_and_nothing_else(tmp_path: Path) -> None:
    source = load(str(FIXTURES / "demo_robot.urdf"))
    kept = roundtrip(load(str(FIXTURES / "demo_robot.urdf")))
    assert roundtrip(source, consume=True).to_json() == kept.to_json()
    assert source.tree.getroot().tag == "consumed"


def test_originals_a_document_carries_are_judged_as_convert_writes_them(tmp_path: Path) -> None:
    """Going back to ROS 1, the originals ``--reversible`` carried are written as their bytes
    (the four-bar's members in their original order, which ros_control binds otherwise): the
    cycle through ROS 1 judges what ``convert`` writes."""
    runner = CliRunner()
    carried, back = tmp_path / "four_bar.ros2-p1.urdf", tmp_path / "four_bar.back.urdf"
    written = runner.invoke(cli, ["convert", "--to", "ros2-p1", "--reversible", "--allow-lossy",
                                  str(FIXTURES / "four_bar.ros1.urdf")])
    carried.write_bytes(written.stdout_bytes)
    back.write_bytes(runner.invoke(cli, ["convert", "--to", "ros1", "--allow-lossy",
                                         str(carried)]).stdout_bytes)
    against = runner.invoke(cli, ["roundtrip", "--format", "json", str(carried),
                                  "--against", str(back)])
    cycles = runner.invoke(cli, ["roundtrip", "--format", "json", str(carried)])
    (row,) = json.loads(against.stdout)["transmissions"]
    first = next(c for c in json.loads(cycles.stdout)["cycles"]
                 if c["cycle"] == ["ros2-p1", "ros1", "ros2-p1"])
    assert (written.exit_code, against.exit_code, cycles.exit_code) == (0, 1, 1)
    assert row["status"] == "differs" and first["equivalent"] == f"no: {row['reason']}"
