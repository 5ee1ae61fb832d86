"""What txtool prints cannot be forged or garbled by the names it prints.

A transmission name may hold a newline (``&#10;``), a file name any byte but ``/``: the text
report escapes control characters, so every finding stays one line and no escape sequence
reaches the terminal. JSON, SARIF and GitHub output stay valid UTF-8 for file names that are
not. An error writing standard output is one line and exit 2.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from tests.conftest import neutral

ROOT = Path(__file__).resolve().parents[2]
# Read at import, before the suite's neutral environment (tests/conftest.py) applies.
ENV = {**neutral(os.environ), "PYTHONPATH": str(ROOT), "LC_ALL": "C.UTF-8"}
ZERO = """\
<robot name="arm">
  <transmission name="{name}">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="elbow">
      <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
    </joint>
    <actuator name="motor"><mechanicalReduction>0</mechanicalReduction></actuator>
  </transmission>
</robot>
"""
FORGED = "a&#10;robot.urdf:1:1: error TX999 forged: all clear&#133;"
RAW_NAME = b"arm\xff\x1b[2J\n.urdf"  # not UTF-8, an escape sequence, a newline


def txtool(*args: str, cwd: Path, stdout: object = subprocess.PIPE) -> tuple[int, bytes, str]:
    result = subprocess.run([sys.executable, "-m", "txtool", *args], cwd=cwd, env=ENV,
                            stdout=stdout, stderr=subprocess.PIPE, timeout=120)
    return result.returncode, result.stdout or b"", result.stderr.decode()


def zero_reduction(folder: Path, name: bytes = b"robot.urdf", trans: str = "arm_trans") -> None:
    with open(os.path.join(os.fsencode(folder), name), "w") as handle:
        handle.write(ZERO.format(name=trans))


def test_a_newline_in_a_transmission_name_cannot_forge_a_finding(tmp_path):
    zero_reduction(tmp_path, trans=FORGED)
    code, out, _ = txtool("validate", "robot.urdf", cwd=tmp_path)
    assert code == 1
    assert out.decode().splitlines() == [
        "robot.urdf:7:28: error TX106 zero-reduction: reduction of actuator 'motor' of "
        "transmission 'a\\nrobot.urdf:1:1: error TX999 forged: all clear\\x85' is zero: "
        "ros_control refuses it (\"Transmission reduction ratio cannot be zero\")",
        "Found 1 error in 1 file.",
    ]


@pytest.mark.parametrize("color", ["never", "always"])
def test_a_file_name_cannot_drive_the_terminal(tmp_path, color):
    zero_reduction(tmp_path, RAW_NAME)
    code, out, _ = txtool("validate", "--color", color, ".", cwd=tmp_path)
    assert code == 1
    lines = out.decode().splitlines()
    assert len(lines) == 2 and "arm\\xff\\x1b[2J\\n.urdf:7:28:" in lines[0]
    assert b"\x1b[2J" not in out and b"\xff" not in out


def test_json_keeps_a_file_name_that_is_not_utf8(tmp_path):
    zero_reduction(tmp_path, RAW_NAME)
    code, out, err = txtool("validate", "--format", "json", ".", cwd=tmp_path)
    assert (code, err) == (1, "")
    report = json.loads(out.decode("utf-8"))
    path = report["problems"][0]["path"]
    assert os.fsencode(path) == RAW_NAME  # the name's bytes, back from the report


def test_sarif_gives_a_file_name_that_is_not_utf8_as_a_percent_encoded_uri(tmp_path):
    zero_reduction(tmp_path, RAW_NAME)
    code, out, err = txtool("validate", "--format", "sarif", ".", cwd=tmp_path)
    assert (code, err) == (1, "")
    log = json.loads(out.decode("utf-8"))
    location = log["runs"][0]["results"][0]["locations"][0]["physicalLocation"]
    assert location["artifactLocation"] == {"uri": "arm%FF%1B%5B2J%0A.urdf",
                                            "uriBaseId": "%SRCROOT%"}


def test_github_annotations_stay_utf8_and_one_line(tmp_path):
    zero_reduction(tmp_path, RAW_NAME)
    code, out, err = txtool("validate", "--format", "github", ".", cwd=tmp_path)
    assert (code, err) == (1, "")
    [line] = out.decode("utf-8").splitlines()
    assert line.startswith("::error file=arm\\xff\\x1b[2J%0A.urdf,line=7,col=28,")


@pytest.mark.parametrize("args", [["show", "robot.urdf"], ["validate", "robot.urdf"],
                                  # (its zero reduction is refused for ros2_control too)
                                  ["convert", "robot.urdf", "--to", "ros2-p2", "--allow-lossy"],
                                  ["validate", "--format", "sarif", "robot.urdf"], ["rules"]])
def test_a_full_disk_on_standard_output_is_one_line_and_exit_2(tmp_path, args):
    if not os.path.exists("/dev/full"):
        pytest.skip("no /dev/full on this system")
    zero_reduction(tmp_path)
    with open("/dev/full", "wb") as full:
        code, _, err = txtool(*args, cwd=tmp_path, stdout=full)
    assert code == 2  # convert notes first that the input does not load
    assert err.endswith("txtool: cannot write standard output: No space left on device\n")


@pytest.mark.parametrize("args", [["rules"], ["validate", "robot.urdf"],
                                  ["show", "robot.urdf"]])
def test_a_closed_pipe_ends_quietly_with_sigpipes_exit_code(tmp_path, args):
    zero_reduction(tmp_path)
    process = subprocess.Popen([sys.executable, "-m", "txtool", *args], cwd=tmp_path,
                               env=ENV, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    process.stdout.close()  # type: ignore[union-attr]
    _, err = process.communicate(timeout=60)
    assert (process.returncode, err.decode()) == (141, "")


@pytest.mark.parametrize(("args", "shown"), [
    (["show", "pipe\x1b[2J\n.urdf"], "pipe\\x1b[2J\\n.urdf"),
    (["validate", "."], "pipe\\x1b[2J\\n.urdf"),  # found in the folder
])
def test_an_error_naming_a_file_stays_one_line(tmp_path, args, shown):
    os.mkfifo(os.path.join(os.fsencode(tmp_path), b"pipe\x1b[2J\n.urdf"))
    code, _, err = txtool(*args, cwd=tmp_path)
    assert code == 2
    assert err == (f"txtool: {shown}: is a named pipe (FIFO), not a regular file; txtool reads "
                   "only regular files (or '-')\n")


MARKUP_ROBOT = """<robot name="r">
  <transmission name="t[/]x[bold]">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="j[red]"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>
    <actuator name="m&#133;[2J"><mechanicalReduction>50</mechanicalReduction></actuator>
  </transmission>
</robot>
"""


@pytest.mark.parametrize("args", [("show",), ("show", "--effective"), ("show", "--actuator-limits"),
                                  ("roundtrip",)])
def test_brackets_and_c1_controls_in_names_are_shown_not_obeyed(tmp_path, args):
    """rich reads ``[/]`` as markup (it stopped ``show`` with an internal error) and the C1
    character U+0085 reaches a terminal unless escaped."""
    from click.testing import CliRunner

    from txtool.cli import cli

    robot = tmp_path / "r.urdf"
    robot.write_text(MARKUP_ROBOT)
    result = CliRunner().invoke(cli, [args[0], str(robot), *args[1:]])
    assert result.exit_code == 0, result.output
    assert "t[/]x[bold]" in result.stdout and "\x85" not in result.stdout
    if args != ("roundtrip",):
        assert "m\\x85[2J" in result.stdout
