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


# numpy is not a base dependency (it comes with the 'sim' extra): every other command runs
# where importing it fails, as in a base install.
NO_NUMPY = """
import sys
class Refuse:
    def find_spec(self, name, path=None, target=None):
        if name == "numpy" or name.startswith("numpy."):
            raise ModuleNotFoundError(f"No module named {name!r}", name=name)
sys.meta_path.insert(0, Refuse())
from txtool.cli import main
sys.argv = ["txtool", *sys.argv[1:]]
main()
"""

FIXTURES = __import__("pathlib").Path(__file__).resolve().parents[2] / "fixtures"


@pytest.mark.parametrize("args", [
    ["validate", "{demo}"],
    ["show", "{demo}", "--effective", "--actuator-limits", "--format", "json"],
    ["convert", "{demo}", "--to", "ros2-p2"],
    ["migrate", "--check", "--to", "ros2-p2", "{p2}"],
    ["migrate", "--diff", "--to", "ros2-p1", "{demo}"],
    ["roundtrip", "{demo}", "--against", "{p2}"],
    ["map", "{diff}", "-t", "wrist_trans", "--to", "joint", "--position", "3,5",
     "--format", "json"],
    ["map", "{four_bar}", "-t", "four_bar_trans", "--to", "actuator", "--effort", "1,2"],
    ["rules", "TX106"],
], ids=lambda args: " ".join(args[:2]))
def test_the_base_commands_need_no_numpy(args):
    names = {"demo": FIXTURES / "demo_robot.urdf", "p2": FIXTURES / "demo_robot.ros2-p2.urdf",
             "diff": FIXTURES / "differential_golden.urdf",
             "four_bar": FIXTURES / "four_bar.ros1.urdf"}
    done = subprocess.run([sys.executable, "-c", NO_NUMPY,
                           *(a.format(**{k: str(v) for k, v in names.items()}) for a in args)],
                          capture_output=True, text=True, timeout=120)
    converts = args[:2] == ["migrate", "--diff"]  # exit 1: it would change the file
    assert done.returncode == (1 if converts else 0), done.stderr
    assert "numpy" not in done.stderr


def test_the_probe_refuses_numpy():
    done = subprocess.run([sys.executable, "-c", NO_NUMPY.replace(
        "from txtool.cli import main", "import numpy  # noqa")],
        capture_output=True, text=True, timeout=120)
    assert done.returncode == 1 and "No module named 'numpy'" in done.stderr
EDITOR = ("pygls", "lsprotocol")  # the lsp extra: only `txtool lsp` loads it


@pytest.mark.parametrize("command", [["validate"], ["show", "--effective"],
                                     ["convert", "--to", "ros2-p2"], ["--help"]])
def test_only_the_language_server_loads_the_lsp_extra(tmp_path, command):
    robot = tmp_path / "robot.urdf"
    robot.write_text(BROKEN)
    paths = [] if command == ["--help"] else [str(robot)]  # --help lists `lsp` too
    result = subprocess.run([sys.executable, "-c", PROBE, *command, *paths],
                            capture_output=True, text=True, timeout=120)
    probe = json.loads(result.stderr.strip().splitlines()[-1])
    assert probe["code"] in (0, 1)
    assert [name for name in EDITOR if name in probe["loaded"]] == []
