"""The pre-commit hook definition points at the validate command for URDF and xacro files."""

from __future__ import annotations

import shlex
from pathlib import Path

import yaml
from click.testing import CliRunner

from txtool.cli import cli

HOOKS = Path(__file__).resolve().parents[2] / ".pre-commit-hooks.yaml"


def test_hook_runs_txtool_validate_on_urdf_and_xacro_files():
    (hook,) = yaml.safe_load(HOOKS.read_text())
    assert hook["id"] == "txtool-validate"
    assert hook["entry"] == "txtool validate"
    assert hook["language"] == "python"
    assert hook["types_or"] == ["urdf", "xacro"]


def test_hook_entry_accepts_the_staged_files_as_arguments(tmp_path):
    (hook,) = yaml.safe_load(HOOKS.read_text())
    program, *args = shlex.split(hook["entry"])
    robot = tmp_path / "robot.urdf"
    robot.write_text('<robot name="r"><transmission name="t"/></robot>\n')
    result = CliRunner().invoke(cli, [*args, str(robot), str(robot)])
    assert program == "txtool"
    assert (result.exit_code, result.stdout.splitlines()[-1]) == (1, "Found 1 error in 1 file.")
