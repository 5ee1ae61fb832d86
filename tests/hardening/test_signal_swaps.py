"""A signal that lands just as txtool swaps its own handlers: one line and ``128 + signal``.

txtool installs its handlers twice in a run: those that raise where the program is, as the
command starts, and those that end the process at once, once it has finished. Each test makes
``signal.signal`` send the process a signal right after one of those installs (the other
signal's handler is then still the previous one), in a fresh interpreter started as the
``txtool`` command.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
ENV = {**os.environ, "PYTHONPATH": str(ROOT)}
ENV.pop("TXTOOL_NO_XACRO", None)

PROGRAM = textwrap.dedent("""
    import os, signal, sys
    sys.argv = ["txtool", *sys.argv[1:]]  # as the console script: txtool's first handlers
    real = signal.signal
    seen = []

    def swapping(number, handler):
        previous = real(number, handler)
        seen.append((getattr(handler, "__name__", ""), number))
        if seen.count(seen[-1]) == {nth} and seen[-1] == ({handler!r}, {installed}):
            os.kill(os.getpid(), {sent})
        return previous

    signal.signal = swapping
    from txtool.cli import main
    main()
""")


def run(tmp_path: Path, handler: str, installed: int, nth: int, sent: int) -> \
        subprocess.CompletedProcess[str]:
    (tmp_path / "arm.urdf").write_bytes((ROOT / "fixtures" / "demo_robot.urdf").read_bytes())
    program = PROGRAM.format(handler=handler, installed=int(installed), nth=nth, sent=int(sent))
    return subprocess.run([sys.executable, "-c", program, "validate", "arm.urdf"],
                          cwd=tmp_path, env=ENV, capture_output=True, text=True, timeout=120)


@pytest.mark.parametrize(("handler", "installed", "nth", "sent", "code", "line"), [
    # as the command starts: SIGINT's handler is the new one, SIGTERM's still the first
    ("_on_signal", signal.SIGINT, 1, signal.SIGTERM, 143, "txtool: terminated"),
    ("_on_signal", signal.SIGINT, 1, signal.SIGINT, 130, "txtool: interrupted"),
    # both new: the signal is handled before the command's code is reached
    ("_on_signal", signal.SIGTERM, 1, signal.SIGINT, 130, "txtool: interrupted"),
    ("_on_signal", signal.SIGTERM, 1, signal.SIGTERM, 143, "txtool: terminated"),
    # once the command has finished: SIGINT ends at once, SIGTERM still raises
    ("_exit_now", signal.SIGINT, 2, signal.SIGTERM, 143, "txtool: terminated"),
    ("_exit_now", signal.SIGINT, 2, signal.SIGINT, 130, "txtool: interrupted"),
    ("_exit_now", signal.SIGTERM, 2, signal.SIGINT, 130, "txtool: interrupted"),
], ids=lambda value: getattr(value, "name", str(value)))
def test_a_signal_during_a_swap_of_handlers_is_one_line(tmp_path, handler, installed, nth,
                                                        sent, code, line):
    result = run(tmp_path, handler, installed, nth, sent)
    assert (result.returncode, result.stderr) == (code, line + "\n")
