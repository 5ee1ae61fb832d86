"""``txtool validate`` stays light: no pinocchio, yourdfpy, trimesh or numpy on its path."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

from tests.lint.conftest import BROKEN

HEAVY = ("pinocchio", "pin", "yourdfpy", "trimesh", "numpy", "scipy", "matplotlib", "dask",
         "distributed")
# Only what txtool loads counts, not what ran before it (coverage, when measuring subprocesses).
PROBE = """
import json, sys
before = set(sys.modules)
from txtool.cli import cli
try:
    cli.main(sys.argv[1:], prog_name="txtool", standalone_mode=True)
except SystemExit as exc:
    code = exc.code
loaded = sorted({name.split(".")[0] for name in set(sys.modules) - before})
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
    probe = run_validate(str(robot))  # expanded in the sandbox's child process
    assert probe["code"] == 1 and "xacro" not in probe["loaded"]
    assert [name for name in HEAVY if name in probe["loaded"]] == []
    probe = run_validate("--trust-xacro", str(robot))  # expanded here
    assert probe["code"] == 1 and "xacro" in probe["loaded"]
    assert [name for name in HEAVY if name in probe["loaded"]] == []


@pytest.mark.parametrize("output_format", ["text", "json", "github", "sarif"])
def test_validate_without_configuration_never_loads_pydantic(tmp_path, output_format):
    """pydantic costs more than linting a file: only a configuration with rule options needs
    it (the json report is written without it, see tests/lint/test_reporters.py)."""
    robot = tmp_path / "robot.urdf"
    robot.write_text(BROKEN)
    probe = subprocess.run(
        [sys.executable, "-c", PROBE, "validate", "--format", output_format, str(robot)],
        capture_output=True, text=True, timeout=120, cwd=tmp_path,
    )
    loaded = json.loads(probe.stderr.strip().splitlines()[-1])["loaded"]
    assert "pydantic" not in loaded


def test_many_files_are_shared_without_multiprocessing(tmp_path):
    """Forks share the files (txtool.lint.workers); multiprocessing's pool costs about 15 ms."""
    for index in range(80):
        (tmp_path / f"robot_{index:02d}.urdf").write_text(BROKEN)
    probe = run_validate("--jobs", "2", "--format", "json", str(tmp_path))
    assert probe["code"] == 1
    assert "multiprocessing" not in probe["loaded"] and "pydantic" not in probe["loaded"]


@pytest.mark.parametrize("output_format", ["text", "json"])
def test_roundtrip_of_a_robot_loads_neither_numpy_nor_rich_s_console(tmp_path, output_format):
    """Its equivalence check maps a few samples in plain floats, and a table to a pipe is
    written without rich (txtool.views.plain); numpy alone costs more than the whole run."""
    from tests.foundation.test_plain_table import ARM

    robot = tmp_path / "arm.urdf"
    robot.write_text(ARM)
    result = subprocess.run(
        [sys.executable, "-c", PROBE, "roundtrip", "--format", output_format, str(robot)],
        capture_output=True, text=True, timeout=120,
    )
    probe = json.loads(result.stderr.strip().splitlines()[-1])
    assert probe["code"] == 0
    assert [name for name in HEAVY if name in probe["loaded"]] == []
    assert "rich" not in probe["loaded"]
    # Nor the network stack that xml.sax.saxutils brings (urllib.request, http.client, ssl).
    assert [name for name in ("ssl", "http", "email", "urllib") if name in probe["loaded"]] == []
