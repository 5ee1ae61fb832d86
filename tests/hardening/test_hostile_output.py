"""What a pull request names cannot forge output, drive the terminal or crash a command.

A file name may hold a newline followed by ``::error file=...`` (a forged GitHub annotation in
the CI log), a transmission name ``[/]`` or ``[bold red]`` (rich markup); the environment may
ask for ASCII output, close standard input or remove the working folder. Every text from a
file goes through one function (:func:`txtool.io.printable.printable`) on its way out, and
each of these ends in output or in one line, never in an internal error.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import tempfile
from collections.abc import Callable
from pathlib import Path

import pytest
from click.testing import CliRunner

from tests.conftest import neutral
from tests.hardening.test_atomic_writes import DEMO
from txtool.cli import cli

ROOT = Path(__file__).resolve().parents[2]
# Read at import, before the suite's neutral environment (tests/conftest.py) applies.
ENV = {**neutral(os.environ), "PYTHONPATH": str(ROOT)}
FORGED_NAME = "evil\n::error file=ok.urdf,line=1::forged.urdf"
Run = Callable[..., tuple[int, str, str]]




def txtool(*args: str, cwd: Path, env: dict[str, str] | None = None,
           stdin_closed: bool = False) -> tuple[int, str, str]:
    command = [sys.executable, "-m", "txtool", *args]
    if stdin_closed:  # as `txtool ... <&-` in a shell
        command = ["bash", "-c", 'exec "$@" <&-', "txtool", *command]
    result = subprocess.run(command, capture_output=True, cwd=cwd, env={**ENV, **(env or {})},
                            timeout=120)
    return (result.returncode, result.stdout.decode("utf-8", "replace"),
            result.stderr.decode("utf-8", "replace"))


def _no_forged_line(text: str) -> None:
    assert not [line for line in text.splitlines() if line.startswith("::")], text


@pytest.mark.parametrize("mode", ["--check", "--diff", "--write"])
def test_migrate_prints_a_hostile_file_name_on_one_line(run, tmp_path, mode):
    (tmp_path / FORGED_NAME).write_bytes(DEMO)
    code, out, err = run("migrate", mode, "--to", "ros2-p2", ".")
    assert code == (0 if mode == "--write" else 1)
    escaped = "./evil\\n::error file=ok.urdf,line=1::forged.urdf"
    verb = {"--write": "changed", "--check": "would change", "--diff": "would change"}[mode]
    assert f"{verb} {escaped} (2 transmission(s) to ros2-p2)\n" in err
    _no_forged_line(err)
    _no_forged_line(out)
    if mode == "--diff":
        named = escaped.removeprefix("./")  # a diff names a walked file as git does
        assert out.startswith(f"--- a/{named}\n+++ b/{named}\n")


HOSTILE_NAMES = """\
<robot name="arm">
  <link name="base"/>
  <transmission name="[/]t&#10;::error file=ok.urdf::forged [bold red]loud">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="elbow"><hardwareInterface>EffortJointInterface</hardwareInterface></joint>
    <actuator name="m&#10;::warning::[link=https://example.com]x">
      <hardwareInterface>EffortJointInterface</hardwareInterface>
      <mechanicalReduction>50</mechanicalReduction>
    </actuator>
  </transmission>
</robot>
"""
# ros2_control binds reductions in XML order (m10 first), ros_control by role (m2 first): a
# round trip through ROS 1 changes behaviour, and says so in a line naming the transmission.
ROLE_ORDER = """\
<robot name="r">
  <ros2_control name="hw" type="system">
    <joint name="elbow"><command_interface name="position"/></joint>
    <joint name="wrist"><command_interface name="position"/></joint>
    <transmission name="[/]t&#10;::error file=ok.urdf::forged [bold red]loud">
      <plugin>transmission_interface/DifferentialTransmission</plugin>
      <actuator name="m10" role="actuator2"><mechanical_reduction>10</mechanical_reduction></actuator>
      <actuator name="m2" role="actuator1"><mechanical_reduction>20</mechanical_reduction></actuator>
      <joint name="elbow" role="joint1"/>
      <joint name="wrist" role="joint2"/>
    </transmission>
  </ros2_control>
</robot>
"""
ESCAPED = "[/]t\\n::error file=ok.urdf::forged [bold red]loud"


def test_roundtrip_prints_markup_in_a_name_as_written(run, tmp_path):
    (tmp_path / "role_order.urdf").write_text(ROLE_ORDER)
    code, out, err = run("roundtrip", "role_order.urdf")
    assert (code, err) == (1, "")
    assert f"{ESCAPED} (ros2-p2 → ros1 → ros2-p2): actuator 'm2' position differs by" in out
    _no_forged_line(out)


def test_show_effective_keeps_each_name_on_its_line(run, tmp_path):
    (tmp_path / FORGED_NAME).write_text(HOSTILE_NAMES)
    code, out, err = run("show", FORGED_NAME, "--effective")
    assert (code, err) == (0, "")
    assert out.startswith("evil\\n::error file=ok.urdf,line=1::forged.urdf\n")
    assert f"{ESCAPED} (line 3): SimpleTransmission" in out
    _no_forged_line(out)


def test_convert_notes_keep_each_name_on_its_line(run, tmp_path):
    (tmp_path / "arm.urdf").write_text(HOSTILE_NAMES)
    code, _, err = run("convert", "arm.urdf", "--to", "ros2-p2")
    assert code == 0
    assert "actuator 'm\\n::warning::[link=https://example.com]x'" in err
    _no_forged_line(err)


NON_ASCII = DEMO.replace(b'"wrist_trans"', "\"poignet_é→\"".encode())


@pytest.mark.parametrize("args", [["show"], ["roundtrip"], ["show", "--effective"],
                                  ["validate"]])
def test_an_ascii_output_escapes_what_it_cannot_hold(tmp_path, args):
    (tmp_path / "bras_é.urdf").write_bytes(NON_ASCII)
    code, out, err = txtool(*args, "bras_é.urdf", cwd=tmp_path,
                            env={"PYTHONIOENCODING": "ascii", "COLUMNS": "200"})
    assert (code, err) == (0, "")
    if args in (["show"], ["roundtrip"]):  # rich tables: the name and the arrows escaped
        assert "bras_\\xe9.urdf" in out and "poignet_\\xe9\\u2192" in out


def test_standard_input_closed_is_one_line(tmp_path):
    for command in (["validate", "-"], ["show", "-"], ["convert", "-", "--to", "ros1"]):
        code, out, err = txtool(*command, cwd=tmp_path, stdin_closed=True)
        summary = "1 file could not be read; nothing was checked.\n"
        assert (code, out) == (2, summary if command[0] == "validate" else ""), err
        assert err.endswith("txtool: -: standard input is closed; nothing to read\n"), err
        assert "internal error" not in err


@pytest.mark.parametrize("args", [["validate"], ["validate", "."], ["show", "robot.urdf"],
                                  ["migrate", "--check", "."]])
def test_a_deleted_working_folder_is_one_line(tmp_path, monkeypatch, args):
    gone = tmp_path / "gone"
    gone.mkdir()
    monkeypatch.chdir(gone)
    gone.rmdir()
    result = CliRunner().invoke(cli, args)
    assert (result.exit_code, result.stdout, result.stderr) == (2, "", (
        "txtool: the working folder cannot be used (no such file or directory; was it "
        "deleted?): change to an existing folder\n"))


NOBODY = 65534


@pytest.mark.skipif(os.geteuid() != 0, reason="needs root, to act as another user")
@pytest.mark.parametrize("args", [["validate"], ["show"], ["migrate", "--check"],
                                  ["convert", "--to", "ros2-p2"]])
def test_a_file_in_a_folder_the_user_cannot_read_is_one_line(args):
    """The folder named on the command line holds the robot but cannot be listed or entered
    by the user running txtool: the configuration lookup there is refused by the system."""
    shared = Path(tempfile.mkdtemp(prefix="txtool-shared-"))
    try:
        shared.chmod(0o777)
        (shared / "locked").mkdir()
        (shared / "locked" / "robot.urdf").write_bytes(DEMO)
        (shared / "locked").chmod(0o700)
        target = str(shared / "locked" / "robot.urdf")
        (shared / "open").mkdir()
        (shared / "open" / "robot.urdf").write_bytes(DEMO)
        # Loads every module the fork will need (in another folder: nothing found is cached).
        CliRunner().invoke(cli, [*args, str(shared / "open" / "robot.urdf")])
        reader, writer = os.pipe()
        pid = os.fork()
        if pid == 0:  # pragma: no cover (runs in the fork)
            outcome = b""
            try:
                os.setgroups([])
                os.setgid(NOBODY)
                os.setuid(NOBODY)
                os.chdir(shared)
                result = CliRunner().invoke(cli, [*args, target])
                outcome = f"{result.exit_code}\0{result.stdout}\0{result.stderr}".encode()
            finally:
                os.write(writer, outcome)
                os._exit(0)
        os.close(writer)
        with os.fdopen(reader, "rb") as stream:
            code, out, err = stream.read().decode().split("\0")
        os.waitpid(pid, 0)
    finally:
        shutil.rmtree(shared)
    first = err.splitlines()[0]
    assert code == "2" and first.startswith(f"txtool: {shared}/locked"), err
    assert first.endswith(": permission denied") and "internal error" not in err + out


def test_simulate_keeps_each_joint_name_on_its_line(run, tmp_path):
    forged = b'name="sh&#10;::error file=ok.urdf::forged[/]"'
    (tmp_path / "robot.urdf").write_bytes(DEMO.replace(b'name="shoulder"', forged))
    code, out, err = run("simulate", "robot.urdf", "--duration", "0.2")
    assert code in (0, 1) and "internal error" not in err
    assert "sh\\n::error file=ok.urdf::forged[/]" in out
    _no_forged_line(out)
