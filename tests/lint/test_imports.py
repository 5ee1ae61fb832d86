"""``txtool validate`` stays light: no pinocchio, yourdfpy, trimesh or numpy on its path."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

from tests.lint.conftest import BROKEN

HEAVY = ("pinocchio", "pin", "yourdfpy", "trimesh", "numpy", "scipy", "matplotlib")
PROBE = """
import json, sys
from txtool.cli import cli
try:
    cli.main(sys.argv[1:], prog_name="txtool", standalone_mode=True)
except SystemExit as exc:
    code = exc.code
loaded = sorted({name.split(".")[0] for name in sys.modules})
print(json.dumps({"code": code, "loaded": loaded}), file=sys.stderr)
"""


def run_validate(*args: str) -> dict:
    result = subprocess.run(
        [sys.executable, "-c", PROBE, "validate", *args],
        capture_output=True, text=True, timeout=120,
    )
    return json.loads(result.stderr.strip().splitlines()[-1])


@pytest.mark.parametrize("output_format", ["text", "json", "sarif", "github"])
def test_validate_imports_nothing_heavy(tmp_path, output_format):
    robot = tmp_path / "robot.urdf"
    robot.write_text(BROKEN)
    probe = run_validate("--format", output_format, "--color", "always", str(robot))
    assert probe["code"] == 1
    assert [name for name in HEAVY if name in probe["loaded"]] == []


def test_validate_of_xacro_imports_nothing_heavy(tmp_path):
    robot = tmp_path / "robot.urdf.xacro"
    robot.write_text(BROKEN.replace("<robot", '<robot xmlns:xacro="http://www.ros.org/wiki/xacro"'))
    probe = run_validate(str(robot))
    assert probe["code"] == 1 and "xacro" in probe["loaded"]
    assert [name for name in HEAVY if name in probe["loaded"]] == []


@pytest.mark.parametrize("output_format", ["text", "github", "sarif"])
def test_validate_without_configuration_never_builds_pydantic_models(tmp_path, output_format):
    """pydantic's model machinery costs more than linting a file: only a configuration with
    rule options and the json format (validated against its schema) need it."""
    robot = tmp_path / "robot.urdf"
    robot.write_text(BROKEN)
    probe = subprocess.run(
        [sys.executable, "-c", PROBE.replace('name.split(".")[0]', "name"), "validate",
         "--format", output_format, str(robot)],
        capture_output=True, text=True, timeout=120, cwd=tmp_path,
    )
    loaded = json.loads(probe.stderr.strip().splitlines()[-1])["loaded"]
    assert "pydantic.main" not in loaded and "pydantic.fields" not in loaded
