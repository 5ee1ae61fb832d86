"""Exit statuses with unreadable inputs among readable ones, for every command that takes several
paths (validate, validate --fix/--diff, migrate --check/--diff/--write), in either order and
with worker processes: an input that cannot be read makes exit 2 whatever else happened, and
the readable files are still checked, fixed or diffed. And --fix's marks where migrate changes
a file but not a given finding."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from click.testing import CliRunner

from tests.lint.test_validate_fix import LEGACY, XACRO
from txtool.cli import cli
from txtool.lint.api import MIN_FILES_PER_WORKER

CLEAN = """<robot name="r">
  <joint name="j" type="revolute"><limit effort="1" velocity="1" lower="-1" upper="1"/></joint>
  <transmission name="t">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="j"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
    </joint>
    <actuator name="m"><mechanicalReduction>50</mechanicalReduction></actuator>
  </transmission>
</robot>
"""
UNREADABLE: dict[str, str | None] = {
    "missing": None,  # no such file
    "a link to nothing": "link",
}


def run(*args: str) -> tuple[int, str, str]:
    result = CliRunner().invoke(cli, list(args))
    if result.exception and not isinstance(result.exception, SystemExit):
        raise result.exception
    return result.exit_code, result.stdout, result.stderr


@pytest.fixture
def folder(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "legacy.urdf").write_text(LEGACY)
    (tmp_path / "clean.urdf").write_text(CLEAN)
    return tmp_path


def unreadable(folder: Path, kind: str) -> str:
    content = UNREADABLE[kind]
    if content == "link":
        (folder / "bad.urdf").symlink_to(folder / "gone.urdf")
    return "bad.urdf"


# a command and its status on the readable files alone
COMMANDS = [
    (["validate"], 1),
    (["validate", "--select", "TX106"], 0),  # nothing found in the readable files
    (["validate", "--exit-zero"], 0),
    (["validate", "--diff"], 1),
    (["migrate", "--check"], 1),
    (["migrate", "--diff"], 1),
]


@pytest.mark.parametrize("kind", UNREADABLE)
@pytest.mark.parametrize("first", [True, False], ids=["unreadable first", "unreadable last"])
@pytest.mark.parametrize(("command", "alone"), COMMANDS, ids=[" ".join(c) for c, _ in COMMANDS])
def test_an_unreadable_input_makes_exit_2_and_the_others_are_still_done(folder, command, alone,
                                                                          kind, first):
    assert run(*command, "legacy.urdf", "clean.urdf")[0] == alone
    bad = unreadable(folder, kind)
    paths = [bad, "legacy.urdf", "clean.urdf"] if first else ["legacy.urdf", "clean.urdf", bad]
    code, out, err = run(*command, *paths)
    assert code == 2, (out, err)
    assert "txtool: bad.urdf" in err
    if command == ["validate"]:
        assert "legacy.urdf:" in out and "TX302" in out
    if command[-1] == "--diff" or command[-1] == "--check":
        assert "would change legacy.urdf" in err
    if command[-1] == "--diff":
        assert out.startswith("--- a/legacy.urdf\n+++ b/legacy.urdf\n")
    assert (folder / "legacy.urdf").read_text() == LEGACY  # nothing written


@pytest.mark.parametrize("kind", UNREADABLE)
@pytest.mark.parametrize("command", [["validate", "--fix"], ["migrate", "--write"]],
                         ids=" ".join)
def test_fixes_are_written_and_the_status_is_2_with_an_unreadable_input(folder, command, kind):
    bad = unreadable(folder, kind)
    code, _, err = run(*command, "legacy.urdf", bad, "clean.urdf")
    assert code == 2 and "txtool: bad.urdf" in err
    fixed = (folder / "legacy.urdf").read_text()
    assert fixed != LEGACY and 'type="transmission_interface' not in fixed
    assert (folder / "clean.urdf").read_text() == CLEAN


def test_validate_with_workers_is_2_when_one_file_of_many_is_unreadable(folder):
    names = [f"r{i:02d}.urdf" for i in range(3 * MIN_FILES_PER_WORKER)]
    for name in names:
        (folder / name).write_text(CLEAN)
    names.insert(len(names) // 2, "missing.urdf")
    for jobs in ("1", "2"):
        code, out, err = run("validate", "-j", jobs, "--format", "json", *names)
        assert code == 2 and err == "txtool: missing.urdf: no such file\n"
        assert json.loads(out)["summary"]["files"] == len(names) - 1


def test_a_fix_that_changes_the_file_marks_only_the_findings_it_fixes(folder):
    """migrate adds the legacy ``type=`` attribute's <type> (TX302) but cannot prefix an
    interface that comes from ${iface} (TX300): the file changes, the TX300 finding is not
    marked fixable."""
    xacro = XACRO.replace('<transmission name="t">\n    <type>transmission_interface/'
                          'SimpleTransmission</type>',
                          '<transmission name="t" type="transmission_interface/'
                          'SimpleTransmission">')
    assert xacro != XACRO
    (folder / "m.urdf.xacro").write_text(xacro)
    code, out, _ = run("validate", "--format", "json", "m.urdf.xacro")
    assert code == 0  # two warnings
    marks = {p["code"]: p["fixable"] for p in json.loads(out)["problems"]}
    assert marks["TX302"] is True and marks["TX300"] is False
    code, out, _ = run("validate", "m.urdf.xacro")
    assert "TX302 [*]" in out and "TX300 [*]" not in out
    assert out.splitlines()[-1].endswith("; 1 fixable with `txtool validate --fix`.")
