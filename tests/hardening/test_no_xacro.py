"""``--no-xacro``, ``TXTOOL_NO_XACRO=1`` and ``no-xacro = true``: xacro never runs.

The robot below changes visibly when xacro expands it: its ``$(find ...)`` include fails, a
property supplies a reduction and a macro call produces a transmission. Read as written, the
file has the macro's template transmission and ``${ratio}`` as text.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import textwrap
from collections.abc import Callable
from pathlib import Path

import pytest
from click.testing import CliRunner

from txtool.cli import cli
from txtool.io import xacro as xacro_support

# Named, not the default placeholder (which a written conversion points out): what these
# tests check is elsewhere.
MOCK = "mock_components/GenericSystem"

ROBOT = """\
<?xml version="1.0"?>
<robot name="arm" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="ratio" value="50"/>
  <xacro:include filename="$(find arm_description)/urdf/extra.xacro"/>
  <link name="base"/>
  <link name="upper"/>
  <joint name="elbow" type="revolute">
    <parent link="base"/><child link="upper"/>
    <limit lower="-1" upper="1" effort="10" velocity="2"/>
  </joint>
  <xacro:macro name="simple_trans" params="joint">
    <transmission name="${joint}_trans">
      <type>transmission_interface/SimpleTransmission</type>
      <joint name="${joint}">
        <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
      </joint>
      <actuator name="${joint}_motor"><mechanicalReduction>7</mechanicalReduction></actuator>
    </transmission>
  </xacro:macro>
  <xacro:simple_trans joint="wrist"/>
  <transmission name="elbow_trans">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="elbow">
      <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
    </joint>
    <actuator name="elbow_motor"><mechanicalReduction>${ratio}</mechanicalReduction></actuator>
  </transmission>
</robot>
"""
AS_WRITTEN = ["${joint}_trans", "elbow_trans"]
OFF = ("(--no-xacro, TXTOOL_NO_XACRO or no-xacro in the configuration); "
       "expand it with xacro first")

Run = Callable[..., tuple[int, str, str]]


@pytest.fixture
def robot(tmp_path: Path) -> Path:
    path = tmp_path / "urdf" / "arm.urdf.xacro"
    path.parent.mkdir()
    path.write_text(ROBOT)
    return path


@pytest.fixture
def run(monkeypatch: pytest.MonkeyPatch) -> Run:
    """Run ``txtool ARGS`` in-process; (exit code, stdout, stderr)."""
    monkeypatch.delenv("TXTOOL_NO_XACRO", raising=False)
    monkeypatch.delenv("GITHUB_ACTIONS", raising=False)

    def invoke(*args: str) -> tuple[int, str, str]:
        result = CliRunner().invoke(cli, list(args), catch_exceptions=False)
        return result.exit_code, result.stdout, result.stderr

    return invoke


@pytest.fixture
def xacro_forbidden(monkeypatch: pytest.MonkeyPatch) -> None:
    def expand(*args: object) -> None:
        raise AssertionError("xacro ran")

    monkeypatch.setattr(xacro_support, "expand_xacro", expand)


def _write(path: Path, text: str) -> None:
    path.write_text(textwrap.dedent(text))


@pytest.fixture(params=["flag", "environment", "pyproject", "txtool-toml"])
def off(request, robot: Path, monkeypatch: pytest.MonkeyPatch, run: Run,
        xacro_forbidden: None) -> tuple[str, ...]:
    """Turn xacro off one of the four ways; returns the options to add to the command."""
    if request.param == "flag":
        return ("--no-xacro",)
    if request.param == "environment":
        monkeypatch.setenv("TXTOOL_NO_XACRO", "1")
    elif request.param == "pyproject":  # found upward, as validate finds it
        _write(robot.parent.parent / "pyproject.toml", """\
            [project]
            name = "arm"

            [tool.txtool]
            no-xacro = true
            """)
    else:
        _write(robot.parent / ".txtool.toml", "no-xacro = true\n")
    return ()


def _names(out: str) -> list[str]:
    return [t["name"] for t in json.loads(out)["transmissions"]]


def test_expansion_has_a_visible_effect(run, robot, monkeypatch):
    for variable in ("AMENT_PREFIX_PATH", "ROS_PACKAGE_PATH", "CMAKE_PREFIX_PATH"):
        monkeypatch.delenv(variable, raising=False)
    assert run("show", str(robot)) == (2, "", (
        f"txtool: {robot}:1: xacro: package 'arm_description' not found (looked in: "
        "AMENT_PREFIX_PATH (unset); ROS_PACKAGE_PATH (unset); CMAKE_PREFIX_PATH (unset)); "
        "give --pkg-dir DIR or --pkg-path arm_description:=DIR\n"))


def test_show_lists_the_transmissions_as_written(run, robot, off):
    code, out, err = run("show", "--format", "json", *off, str(robot))
    assert (code, err) == (0, "")
    assert _names(out) == AS_WRITTEN
    elbow = json.loads(out)["transmissions"][1]["actuators"][0]
    assert elbow["mechanical_reduction"] == {"value": None, "text": "${ratio}"}


def test_convert_converts_the_source_as_written(run, robot, off):
    code, out, err = run("convert", "--to", "ros2-p2", "--hardware-plugin", MOCK, *off, str(robot))
    assert code == 0
    assert err == ("note: transmission 'elbow_trans': xacro expressions are carried verbatim; "
                   "check the expanded result\n")
    assert '<xacro:include filename="$(find arm_description)/urdf/extra.xacro"/>' in out
    assert '<xacro:simple_trans joint="wrist"/>' in out
    assert "<mechanical_reduction>${ratio}</mechanical_reduction>" in out
    assert '<transmission name="${joint}_trans">' in out


def test_roundtrip_reads_the_file_as_written(run, robot, off):
    code, out, err = run("roundtrip", "--format", "json", *off, str(robot))
    assert (code, err) == (0, "")
    assert sorted({row["transmission"] for row in json.loads(out)["cycles"]}) == AS_WRITTEN


def test_roundtrip_against_a_xacro_file_reads_it_as_written(run, robot, off):
    code, out, err = run("roundtrip", "--format", "json", *off, str(robot), "--against",
                         str(robot))
    assert (code, err) == (1, "")  # ${ratio} is no number until xacro evaluates it
    assert [(row["a"], row["status"]) for row in json.loads(out)["transmissions"]] == [
        ("${joint}_trans", "equivalent"), ("elbow_trans", "not loadable")]


def test_map_refuses_a_xacro_file(run, robot, off):
    assert run("map", *off, str(robot), "-t", "elbow_trans", "--to", "actuator",
               "--position", "1") == (
        2, "", f"txtool: {robot}: map needs the xacro expansion, and xacro is off {OFF}\n")


def test_simulate_refuses_a_xacro_robot(run, robot, off):
    assert run("simulate", *off, str(robot)) == (
        2, "", f"txtool: {robot}: simulate needs the xacro expansion, and xacro is off {OFF}\n")


def test_simulate_refuses_a_xacro_candidate(run, robot, tmp_path):
    plain = Path(__file__).resolve().parents[2] / "fixtures" / "demo_robot.urdf"
    assert run("simulate", "--no-xacro", str(plain), "--candidate", str(robot)) == (
        2, "", f"txtool: {robot}: simulate needs the xacro expansion, and xacro is off {OFF}\n")


@pytest.mark.parametrize("command", [
    ("show", "--format", "json"), ("convert", "--to", "ros2-p2", "--hardware-plugin", MOCK), ("roundtrip", "--format", "json"),
    ("map", "-t", "elbow_trans", "--to", "actuator", "--position", "1"),
])
def test_config_names_the_configuration_of_every_command(run, robot, tmp_path, xacro_forbidden,
                                                         command):
    pinned = tmp_path / "ci.toml"  # not where the search would look
    pinned.write_text("no-xacro = true\n")
    assert run(*command, "--config", str(pinned), str(robot)) == run(
        *command, "--no-xacro", str(robot))


def test_validate_checks_the_file_as_written(run, robot, off):
    assert run("validate", *off, str(robot)) == (0, "No problems in 1 file.\n", "")


def test_migrate_never_expands_and_accepts_the_flag(run, robot, xacro_forbidden):
    expected = (0, "", "nothing to do (1 file(s) checked)\n")
    assert run("migrate", "--check", str(robot)) == expected
    assert run("migrate", "--check", "--no-xacro", str(robot)) == expected


def test_a_configuration_cannot_turn_xacro_back_on(run, robot, monkeypatch, xacro_forbidden):
    _write(robot.parent / ".txtool.toml", "no-xacro = false\n")
    code, out, _ = run("show", "--format", "json", "--no-xacro", str(robot))
    assert (code, _names(out)) == (0, AS_WRITTEN)
    monkeypatch.setenv("TXTOOL_NO_XACRO", "1")
    code, out, _ = run("show", "--format", "json", str(robot))
    assert (code, _names(out)) == (0, AS_WRITTEN)
    assert run("validate", str(robot)) == (0, "No problems in 1 file.\n", "")


def test_an_environment_of_0_does_not_override_the_configuration(run, robot, monkeypatch,
                                                                 xacro_forbidden):
    _write(robot.parent / ".txtool.toml", "no-xacro = true\n")
    monkeypatch.setenv("TXTOOL_NO_XACRO", "0")
    code, out, _ = run("show", "--format", "json", str(robot))
    assert (code, _names(out)) == (0, AS_WRITTEN)


@pytest.mark.parametrize("command", [["show"], ["validate"], ["migrate", "--check"]])
@pytest.mark.parametrize("value", ["ture", "", "  "])
def test_an_unclear_environment_value_is_an_error(run, robot, monkeypatch, command, value):
    """An empty value (``TXTOOL_NO_XACRO=``, a CI variable that was never set) is not "off"."""
    monkeypatch.setenv("TXTOOL_NO_XACRO", value)
    assert run(*command, str(robot)) == (2, "", (
        "txtool: TXTOOL_NO_XACRO: expected 1 or 0 (or true/false, yes/no, on/off), "
        f"got {value!r}\n"))


def test_the_configuration_of_the_input_applies_not_the_working_folder(run, robot, tmp_path,
                                                                      monkeypatch):
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    _write(elsewhere / ".txtool.toml", "no-xacro = true\n")
    monkeypatch.chdir(elsewhere)
    code, _, err = run("show", str(robot))
    assert code == 2 and "package 'arm_description' not found" in err


def test_a_bad_configuration_is_one_line_and_exit_2(run, robot):
    _write(robot.parent / ".txtool.toml", 'no-xacro = "sometimes"\n')
    code, out, err = run("show", str(robot))
    assert (code, out) == (2, "")
    assert err.startswith(f"txtool: {robot.parent / '.txtool.toml'}: key 'no-xacro': ")
    assert err.count("\n") == 1


def test_simulate_parameters_in_pyproject_do_not_upset_the_configuration(run, robot):
    _write(robot.parent / "pyproject.toml", """\
        [tool.txtool]
        no-xacro = true

        [tool.txtool.simulate]
        bandwidth = 25.0
        """)
    code, out, err = run("show", "--format", "json", str(robot))
    assert (code, err, _names(out)) == (0, "", AS_WRITTEN)
    assert run("validate", str(robot)) == (0, "No problems in 1 file.\n", "")


def test_a_ci_runner_environment_keeps_xacro_from_being_imported(robot, tmp_path):
    probe = textwrap.dedent("""\
        import atexit, sys
        atexit.register(lambda: print("xacro imported:", "xacro" in sys.modules))
        from txtool.cli import main
        main()
        """)
    env = {**os.environ, "TXTOOL_NO_XACRO": "1"}
    for args in (["show", "--format", "json"], ["validate"], ["roundtrip", "--format", "json"],
                 ["convert", "--to", "ros1"]):
        done = subprocess.run([sys.executable, "-c", probe, *args, str(robot)], cwd=tmp_path,
                              env=env, capture_output=True, text=True)
        assert done.returncode == 0, (args, done.stderr)
        assert done.stdout.endswith("xacro imported: False\n"), args
        if args[0] == "show":
            assert _names(done.stdout.rsplit("xacro imported", 1)[0]) == AS_WRITTEN
