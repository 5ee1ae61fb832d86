"""``txtool demo`` end to end: every step of the tour, in order, with what it shows."""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
from functools import cache
from pathlib import Path

import pytest
from click.testing import CliRunner

from tests.text_tables import table_rows
from txtool.cli import cli

ROOT = Path(__file__).resolve().parents[2]
STEPS = [
    "txtool show fixtures/demo_robot.urdf",
    "txtool convert fixtures/demo_robot.urdf --to ros2-p2",
    "txtool convert fixtures/demo_robot.urdf --to ros2-p1",
    "txtool roundtrip fixtures/demo_robot.urdf",
    "txtool validate fixtures/demo_robot.urdf",
    "txtool validate fixtures/broken_robot.urdf",
    "txtool simulate fixtures/demo_robot.urdf",
    "txtool simulate fixtures/demo_robot.urdf --candidate <'shoulder_trans' reversed>",
    "done",
]
RULE = re.compile(r"^─+ (.+?) ─+$")


def sections(out: str) -> dict[str, str]:
    """The demo's output split at its headings (rich rules): {heading: body}."""
    found: dict[str, str] = {}
    heading = None
    for line in out.splitlines():
        match = RULE.match(line.strip())
        if match:
            heading = match.group(1)
            found[heading] = ""
        elif heading is not None:
            found[heading] += line + "\n"
    return found


@cache
def demo_output() -> tuple[int, str, str]:
    """``txtool demo`` run once from the repository root (the demo's paths are relative)."""
    cwd = os.getcwd()
    os.chdir(ROOT)
    try:
        result = CliRunner().invoke(cli, ["demo"], catch_exceptions=False)
    finally:
        os.chdir(cwd)
    return result.exit_code, result.stdout, result.stderr


def test_demo_runs_every_step_in_order():
    code, out, err = demo_output()
    assert (code, err) == (0, "")
    assert list(sections(out)) == STEPS


def test_demo_from_the_installed_command():
    """What a user types after ``pip install -e .``: the console script, in a pipe."""
    script = shutil.which("txtool")
    command = [script] if script else [sys.executable, "-m", "txtool"]
    done = subprocess.run([*command, "demo"], cwd=ROOT, capture_output=True, text=True,
                          timeout=300, env={**os.environ, "PYTHONPATH": str(ROOT)})
    assert (done.returncode, done.stderr) == (0, "")
    assert list(sections(done.stdout)) == STEPS


def _show(body: str) -> None:
    rows = table_rows(body, "the demo arm's ROS 1 transmissions")
    shoulder = rows[0]
    assert shoulder["transmission"].startswith("shoulder_trans:")
    assert (shoulder["dialect"], shoulder["type"]) == ("ros1", "SimpleTransmission")
    assert (shoulder["member"], shoulder["offset"]) == ("joint shoulder", "0.1")
    assert (rows[1]["member"], rows[1]["reduction"]) == ("actuator shoulder_motor", "-100")
    assert rows[2]["transmission"].startswith("wrist_trans:")
    assert rows[2]["type"] == "DifferentialTransmission"


def _convert(target: str):
    def check(body: str) -> None:
        rows = table_rows(body, f"converted to {target} (lossless: yes)")
        assert {r["dialect"] for r in rows if r["dialect"]} == {target}
        shoulder = [r for r in rows if r["member"] == "joint shoulder"]
        assert [(r["role"], r["reduction"], r["offset"]) for r in shoulder] == [
            ("joint1", "-100", "0.1")]  # ROS 2 keeps the simple reduction on the joint
        assert body.rstrip().endswith("and back to ros1: same transmissions")
    return check


def _roundtrip(body: str) -> None:
    lines = body.strip().splitlines()
    assert len(lines) == 8  # two transmissions, four cycles
    for line in lines:
        assert line.endswith("kept: reduction, offset, direction, roles, interfaces; "
                             "drives the actuators the same: yes"), line
    assert {line.split()[0] for line in lines} == {"shoulder_trans", "wrist_trans"}


def _validate_clean(body: str) -> None:
    assert body.strip() == "0 finding(s)"


def _validate_broken(body: str) -> None:
    findings = re.findall(r"^fixtures/broken_robot\.urdf:(\d+):\d+: (\w+) (TX\d+)", body, re.M)
    assert findings == [("37", "error", "TX303"), ("45", "error", "TX105"),
                        ("50", "error", "TX113"), ("52", "error", "TX200")]
    assert body.rstrip().endswith("4 finding(s)")


def _simulate(body: str) -> None:
    assert "PASS: largest tracking error" in body
    assert {"shoulder_motor", "wrist_left_motor", "wrist_right_motor"} <= set(body.split())


def _simulate_reversed(body: str) -> None:
    assert "with 'shoulder_trans' reversed: FAIL: joint 'shoulder'" in body


CHECKS = {
    STEPS[0]: _show,
    STEPS[1]: _convert("ros2-p2"),
    STEPS[2]: _convert("ros2-p1"),
    STEPS[3]: _roundtrip,
    STEPS[4]: _validate_clean,
    STEPS[5]: _validate_broken,
    STEPS[6]: _simulate,
    STEPS[7]: _simulate_reversed,
}


@pytest.mark.parametrize("step", list(CHECKS))
def test_demo_step_shows_its_result(step):
    _, out, _ = demo_output()
    body = sections(out).get(step)
    assert body is not None, f"the demo skipped {step!r}"
    CHECKS[step](body)


def test_demo_copy_lays_out_the_documentation_examples(tmp_path):
    examples = Path(__file__).resolve().parents[2] / "fixtures" / "examples"
    target = tmp_path / "try"
    result = CliRunner().invoke(cli, ["demo", "--copy", str(target)])
    assert result.exit_code == 0, result.output
    assert result.output.startswith(f"wrote 14 files into {target}: ")
    assert (target / "robot.urdf").read_bytes() == (examples / "robot.urdf").read_bytes()
    assert (target / "fixtures" / "demo_robot.urdf").is_file()
    assert (target / ".txtool.toml").read_text().startswith("# The documentation's examples.")

    again = CliRunner().invoke(cli, ["demo", "--copy", str(target)])
    assert again.exit_code == 2
    assert again.output.endswith(": exists; nothing written (choose an empty folder)\n")

    a_file = tmp_path / "file"
    a_file.write_text("x")
    refused = CliRunner().invoke(cli, ["demo", "--copy", str(a_file)])
    assert (refused.exit_code, refused.output) == (2, f"txtool: {a_file}: not a folder\n")


def test_the_copied_folder_passes_its_own_validate(tmp_path, monkeypatch):
    """Its examples that hold mistakes on purpose (and the security example) are excluded by
    the folder's configuration; named, they are still checked, as the documentation does."""
    target = tmp_path / "try"
    assert CliRunner().invoke(cli, ["demo", "--copy", str(target)]).exit_code == 0
    monkeypatch.chdir(target)
    monkeypatch.delenv("GITHUB_ACTIONS", raising=False)
    walked = CliRunner().invoke(cli, ["validate", "."])
    assert (walked.exit_code, walked.output) == (0, "No problems in 5 files.\n")
    named = CliRunner().invoke(cli, ["validate", "fixtures/broken_robot.urdf"])
    assert named.exit_code == 1 and named.output.endswith("Found 4 errors in 1 file.\n")


def test_every_demo_heading_is_a_command_that_runs_in_the_copied_folder(tmp_path):
    """The headings but simulate's (its candidate is made by the demo) and the closing one."""
    target = tmp_path / "try"
    assert CliRunner().invoke(cli, ["demo", "--copy", str(target)]).exit_code == 0
    _, out, _ = demo_output()
    assert out.splitlines()[0].startswith("Each heading below is the command")
    env = {**os.environ, "PATH": f"{Path(sys.executable).parent}{os.pathsep}{os.environ['PATH']}"}
    for step in STEPS:
        if not step.startswith(("txtool show", "txtool convert", "txtool roundtrip",
                                "txtool validate")):
            continue
        done = subprocess.run(step.split(), cwd=target, env=env, capture_output=True, text=True,
                              timeout=120)
        # (a conversion names the placeholder hardware plugin of the block it generates)
        said = done.stderr.splitlines()
        assert done.returncode in (0, 1) and all(line.startswith("warning: ") for line in said), step
