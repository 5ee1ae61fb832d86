"""Ctrl-C and SIGTERM: one line, exit 130 or 143, and nothing half-written left behind.

Each test runs the real entry point (``txtool.cli.main``) in a fresh interpreter. A write is
made to wait (its ``fsync`` blocks after leaving a mark) so that the signal lands while the
temporary file exists; without a handler SIGTERM kills the process there and leaves it.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
DEMO = (ROOT / "fixtures" / "demo_robot.urdf").read_bytes()
ENV = {**os.environ, "PYTHONPATH": str(ROOT)}
ENV.pop("TXTOOL_NO_XACRO", None)


def program(sabotage: str) -> str:
    return textwrap.dedent(sabotage) + textwrap.dedent("""
        import sys
        from txtool.cli import main
        sys.argv = ["txtool", *sys.argv[1:]]
        main()
    """)


def txtool_with(sabotage: str, *args: str, cwd: Path) -> tuple[int, str, str]:
    result = subprocess.run([sys.executable, "-c", program(sabotage), *args], cwd=cwd,
                            capture_output=True, text=True, timeout=120, env=ENV)
    return result.returncode, result.stdout, result.stderr


SLOW_FSYNC = """
import os, time
real_fsync = os.fsync

def fsync(handle):
    open("writing", "w").close()  # the temporary file exists and holds the data
    time.sleep(60)
    real_fsync(handle)

os.fsync = fsync
"""


@pytest.mark.parametrize(("number", "code", "line"), [
    (signal.SIGTERM, 143, "txtool: terminated\n"),
    (signal.SIGINT, 130, "txtool: interrupted\n"),
])
@pytest.mark.parametrize("command", [
    ["convert", "demo.urdf", "--to", "ros2-p2", "-o", "out.urdf"],
    ["convert", "demo.urdf", "--to", "ros2-p2", "-o", "demo.urdf", "--write"],
    ["migrate", "--write", "--to", "ros2-p2", "--allow-lossy", "demo.urdf"],
])
def test_a_signal_during_a_write_leaves_no_temporary_file(tmp_path, command, number, code,
                                                           line):
    (tmp_path / "demo.urdf").write_bytes(DEMO)
    (tmp_path / "out.urdf").write_bytes(b"<robot name='previous'/>\n")
    before = {p.name: p.read_bytes() for p in tmp_path.iterdir()}
    process = subprocess.Popen([sys.executable, "-c", program(SLOW_FSYNC), *command],
                               cwd=tmp_path, env=ENV, stdout=subprocess.PIPE,
                               stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + 60
    while not (tmp_path / "writing").exists():
        assert process.poll() is None and time.monotonic() < deadline, process.communicate()
        time.sleep(0.02)
    assert [p.name for p in tmp_path.iterdir() if p.name.startswith(".txtool-")]
    process.send_signal(number)
    out, err = process.communicate(timeout=60)
    (tmp_path / "writing").unlink()
    assert (process.returncode, out, err) == (code, "", line)
    assert {p.name: p.read_bytes() for p in tmp_path.iterdir()} == before


# Ctrl-C before any command runs: while the modules load, and while click builds --help.
EARLY = {
    "importing click": """
        import sys

        class Trap:
            def find_spec(self, name, path=None, target=None):
                if name == "click":
                    raise KeyboardInterrupt
                return None

        sys.meta_path.insert(0, Trap())
    """,
    "loading a command": """
        import os, signal, sys

        class Trap:
            def find_spec(self, name, path=None, target=None):
                if name == "txtool.commands.convert":
                    os.kill(os.getpid(), signal.SIGINT)
                return None

        sys.meta_path.insert(0, Trap())
    """,
}


@pytest.mark.parametrize("moment", EARLY)
def test_an_early_ctrl_c_is_one_line_and_exit_130(tmp_path, moment):
    assert txtool_with(EARLY[moment], "--help", cwd=tmp_path) == (
        130, "", "txtool: interrupted\n")


def test_a_library_that_turns_ctrl_c_into_an_error_still_exits_130(tmp_path):
    """Some imports catch the interrupt and raise their own error: not an internal error."""
    sabotage = """
        import os, signal
        import txtool.dialects.read

        def read_source(source, **options):
            try:
                os.kill(os.getpid(), signal.SIGINT)
            except BaseException:
                raise ImportError("module failed to load") from None

        txtool.dialects.read.read_source = read_source
    """
    (tmp_path / "demo.urdf").write_bytes(DEMO)
    assert txtool_with(sabotage, "show", "demo.urdf", cwd=tmp_path) == (
        130, "", "txtool: interrupted\n")
