"""The terminal as users meet it: table widths on a terminal and in a pipe, the progress bar of
a long validate run, help and rule texts without reStructuredText markup, and no "No problems"
beside a failure.

A terminal is a real pseudo-terminal (``pty``) of a chosen size, the program run as a user runs
it; a pipe is a pipe.
"""

from __future__ import annotations

import fcntl
import os
import pty
import re
import struct
import subprocess
import sys
import tempfile
import termios
from pathlib import Path

import pytest
from click.testing import CliRunner

from txtool.cli import COMMAND_MODULES, cli

ROOT = Path(__file__).resolve().parents[2]
DEMO = "fixtures/demo_robot.urdf"  # run from ROOT
ANSI = re.compile(r"\x1b\[[0-9;?]*[A-Za-z]")


def _environment(**extra: str) -> dict[str, str]:
    env = {name: value for name, value in os.environ.items()
           if name not in ("COLUMNS", "LINES", "NO_COLOR", "FORCE_COLOR", "TTY_COMPATIBLE",
                           "GITHUB_ACTIONS")}
    return {**env, "PYTHONPATH": str(ROOT), "TERM": "xterm-256color", **extra}


def _terminal(columns: int, lines: int = 40) -> tuple[int, int]:
    master, slave = pty.openpty()
    fcntl.ioctl(slave, termios.TIOCSWINSZ, struct.pack("HHHH", lines, columns, 0, 0))
    return master, slave


def _read_all(master: int) -> str:
    chunks = []
    while True:
        try:
            chunk = os.read(master, 65536)
        except OSError:  # EIO: the program closed the terminal
            break
        if not chunk:
            break
        chunks.append(chunk)
    os.close(master)
    return b"".join(chunks).decode("utf-8").replace("\r\n", "\n")


def in_terminal(*args: str, columns: int, python: str | None = None,
                stdout_too: bool = True, **env: str) -> tuple[int, str, str]:
    """Run ``txtool ARGS`` (or ``python -c PYTHON``) with stderr, and stdout unless
    ``stdout_too`` is false, on a terminal ``columns`` wide: (exit code, stdout, terminal)."""
    master, slave = _terminal(columns)
    command = [sys.executable, "-c", python] if python else [sys.executable, "-m", "txtool",
                                                             *args]
    with tempfile.TemporaryFile() as piped:  # a file: a pipe left unread would fill up
        process = subprocess.Popen(command, stdin=subprocess.DEVNULL,
                                   stdout=slave if stdout_too else piped, stderr=slave,
                                   env=_environment(**env), cwd=ROOT)
        os.close(slave)
        screen = _read_all(master)
        code = process.wait(timeout=120)
        piped.seek(0)
        out = piped.read().decode()
    return code, out, screen


def in_pipe(*args: str, **env: str) -> tuple[int, str, str]:
    done = subprocess.run([sys.executable, "-m", "txtool", *args], capture_output=True,
                          text=True, env=_environment(**env), cwd=ROOT, timeout=120)
    return done.returncode, done.stdout, done.stderr


def widest(text: str) -> int:
    return max(len(line.rstrip()) for line in ANSI.sub("", text).splitlines())


# --- widths ---------------------------------------------------------------------------------

def test_a_table_on_a_narrow_terminal_fits_its_width():
    code, _, screen = in_terminal("show", DEMO, columns=100)
    assert code == 0 and widest(screen) == 100
    assert "shoulder" in ANSI.sub("", screen)


@pytest.mark.parametrize("color", ["auto", "never"])
def test_a_table_on_a_wide_terminal_is_not_wrapped_at_80(color):
    """--color never (TERM=dumb for rich) once forced rich's 80 columns on any terminal."""
    _, piped, _ = in_pipe("show", DEMO, COLUMNS="200")  # the same layout
    code, _, screen = in_terminal("show", DEMO, "--color", color, columns=200)
    assert code == 0 and widest(screen) == widest(piped) > 120
    shown = [line.rstrip() for line in ANSI.sub("", screen).splitlines()]
    assert shown == [line.rstrip() for line in piped.splitlines()]
    assert ("\x1b[" in screen) == (color == "auto")


def test_in_a_pipe_tables_are_140_columns_or_columns_when_set():
    code, out, err = in_pipe("show", DEMO)
    assert (code, err) == (0, "")
    assert len(out.splitlines()[0]) == widest(out) == 143  # the table whole, the title as wide
    code, narrow, _ = in_pipe("show", DEMO, COLUMNS="72")
    assert code == 0 and widest(narrow) == 72
    code, out, _ = in_pipe("roundtrip", DEMO, COLUMNS="72")  # the plain layout too
    assert code == 0 and widest(out) <= 72 and "…" in out


def test_in_a_pipe_a_wide_table_is_laid_out_whole(tmp_path):
    """Nothing to fit in a pipe: a table wider than 140 columns keeps its cells whole (up to
    400 columns, where a title padded to the width would grow absurd)."""
    demo = (ROOT / DEMO).read_text()
    wide = tmp_path / "wide.urdf"
    wide.write_text(demo.replace("shoulder_trans", "shoulder_" + "x" * 100))
    code, out, _ = in_pipe("show", str(wide))
    assert code == 0 and "…" not in out and "shoulder_" + "x" * 100 in out
    assert 200 < widest(out) < 400 and len({len(line) for line in out.splitlines()}) == 1
    huge = tmp_path / "huge.urdf"
    huge.write_text(demo.replace("shoulder_trans", "shoulder_" + "x" * 500))
    code, out, _ = in_pipe("show", str(huge))
    assert code == 0 and widest(out) == 400 and "…" in out
    code, out, _ = in_pipe("roundtrip", str(wide))
    assert code == 0 and "…" not in out and 140 < widest(out) < 400
    code, out, _ = in_pipe("roundtrip", str(wide), "--against", DEMO)
    assert code == 0 and "…" not in out and 140 < widest(out) < 400


def test_output_size_reads_the_terminal_and_columns(monkeypatch):
    from txtool.views.plain import PIPE_WIDTH, output_size

    monkeypatch.delenv("COLUMNS", raising=False)
    master, slave = _terminal(123, 33)
    with open(slave, "w") as terminal:
        assert output_size(terminal) == (123, 33)
        monkeypatch.setenv("COLUMNS", "90")
        assert output_size(terminal) == (90, 33)
        monkeypatch.setenv("COLUMNS", "wide")
        assert output_size(terminal) == (123, 33)
    os.close(master)
    monkeypatch.delenv("COLUMNS")
    master, slave = _terminal(0, 0)  # a terminal that gives no size (a serial line, say)
    with open(slave, "w") as terminal:
        assert output_size(terminal) == (PIPE_WIDTH, 25)
    os.close(master)
    with open(os.devnull, "w") as file:
        assert output_size(file) == (PIPE_WIDTH, 25)
    closed = open(os.devnull, "w")  # noqa: SIM115
    closed.close()
    assert output_size(closed) == (PIPE_WIDTH, 25)  # isatty() raises ValueError


# --- progress -------------------------------------------------------------------------------

# validate of 40 files at one process, each made to take 30 ms, the bar's delay at 0 s.
SLOW_VALIDATE = """
import sys, time
import txtool.commands.progress as progress
import txtool.lint.api as api
progress.DELAY = {delay}
check = api.lint_file
def slow(*args, **kwargs):
    time.sleep(0.03)
    return check(*args, **kwargs)
api.lint_file = slow
sys.argv = ["txtool", "validate", "-j", "{jobs}", {folder!r}]
from txtool.cli import main
main()
"""


@pytest.fixture
def many(tmp_path) -> str:
    from tests.lint.conftest import CLEAN

    for index in range(40):
        (tmp_path / f"robot{index:02}.urdf").write_text(CLEAN)
    return str(tmp_path)


def test_a_long_validate_shows_progress_on_the_terminal_and_erases_it(many):
    code, out, screen = in_terminal(columns=100, stdout_too=False,
                                    python=SLOW_VALIDATE.format(delay=0, folder=many, jobs=1))
    assert (code, out) == (0, "No problems in 40 files.\n")
    plain = ANSI.sub("", screen)
    assert "checking" in plain and "1/40 files" in plain and "40/40 files" in plain
    assert "39/40" in plain and "40/40 files" not in plain.split("39/40")[0]
    assert screen.endswith("\x1b[2K")  # the bar's line erased: nothing is left on the screen


def test_the_bar_is_drawn_when_worker_processes_share_the_files(tmp_path):
    """End to end with ``-j 2`` (that the count moves before the workers' results arrive is
    tests/lint/test_parallel.py's)."""
    from tests.lint.conftest import CLEAN

    for index in range(80):
        (tmp_path / f"robot{index:02}.urdf").write_text(CLEAN)
    code, out, screen = in_terminal(columns=100, stdout_too=False,
                                    python=SLOW_VALIDATE.format(delay=0, folder=str(tmp_path),
                                                                jobs=2))
    assert (code, out) == (0, "No problems in 80 files.\n")
    steps = {int(n) for n in re.findall(r"(\d+)/80 files", ANSI.sub("", screen))}
    assert 80 in steps and len(steps - {80}) >= 5


def test_a_short_validate_draws_no_bar(many):
    code, out, screen = in_terminal(columns=100, stdout_too=False,
                                    python=SLOW_VALIDATE.format(delay=60, folder=many, jobs=1))
    assert (code, out, screen) == (0, "No problems in 40 files.\n", "")


def test_no_progress_in_a_pipe_or_on_a_dumb_terminal(many):
    script = SLOW_VALIDATE.format(delay=0, folder=many, jobs=1)
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                          env=_environment(), cwd=ROOT, timeout=120)
    assert (done.returncode, done.stdout, done.stderr) == (0, "No problems in 40 files.\n", "")
    code, out, screen = in_terminal(columns=100, stdout_too=False, python=script, TERM="dumb")
    assert (code, out, screen) == (0, "No problems in 40 files.\n", "")


def test_file_progress_draws_only_on_a_terminal(monkeypatch):
    import io

    from txtool.commands import progress

    monkeypatch.setenv("TERM", "xterm")
    with progress.file_progress(io.StringIO()) as report:
        assert report is None
    with progress.file_progress(object()) as report:  # type: ignore[arg-type]
        assert report is None  # no isatty at all
    master, slave = _terminal(80)
    with open(slave, "w") as terminal:
        monkeypatch.setenv("TERM", "dumb")
        with progress.file_progress(terminal) as report:
            assert report is None  # cannot redraw a line
        monkeypatch.setenv("TERM", "xterm")
    os.close(master)
    master, slave = _terminal(80)
    monkeypatch.setattr(progress, "DELAY", 0.0)
    with open(slave, "w") as terminal, progress.file_progress(terminal) as report:
        assert report is not None
        report(2, 2)  # the last file: too late to start a bar
        report(1, 3)
        report(2, 3)
    assert "2/3 files" in ANSI.sub("", _read_all(master))


# --- no reStructuredText markup -------------------------------------------------------------

RST = re.compile(r"``|:[a-z]+:`|^\s*\.\. [a-z-]+::|::$", re.MULTILINE)


def _help(*words: str) -> str:
    result = CliRunner().invoke(cli, [*words, "--help"], terminal_width=100)
    assert result.exit_code == 0, result.output
    return result.output


def test_no_help_page_shows_restructuredtext_markup():
    pages = {"txtool": _help()}
    pages.update({name: _help(name) for name in COMMAND_MODULES})
    assert {name: RST.findall(text) for name, text in pages.items() if RST.search(text)} == {}
    assert "(--list says what each describes)" in pages["schema"]


def test_no_rule_text_shows_restructuredtext_markup():
    import json

    from txtool.rules import all_rules

    rules = CliRunner().invoke(cli, ["rules"])
    assert rules.exit_code == 0 and not RST.search(rules.output)
    assert "no <ros2_control> element" in rules.output  # TX007's summary, ``...`` taken off
    for code in all_rules():
        shown = CliRunner().invoke(cli, ["rules", code])
        assert shown.exit_code == 0 and not RST.search(shown.output), code
        [as_json] = json.loads(CliRunner().invoke(cli, ["rules", code, "--format", "json"]).output)
        assert not RST.search(as_json["summary"]) and not RST.search(as_json["doc"]), code
        markdown = as_json["markdown"]
        assert markdown.startswith(f"# {code} ") and not re.search("(?<!`)``(?!`)", markdown)


# --- "No problems" is never printed beside a failure ----------------------------------------

def test_a_missing_file_is_a_failure_not_no_problems(validate, tmp_path):
    missing = str(tmp_path / "missing.urdf")
    assert validate(missing) == (2, "1 file could not be read; nothing was checked.\n",
                                 f"txtool: {missing}: no such file\n")
    code, out, _ = validate("--statistics", missing)
    assert (code, out) == (2, "1 file could not be read; nothing was checked.\n")


def test_a_clean_file_beside_an_unreadable_one(validate, tmp_path):
    from tests.lint.conftest import CLEAN

    clean = tmp_path / "clean.urdf"
    clean.write_text(CLEAN)
    code, out, err = validate(str(clean), str(tmp_path / "missing.urdf"))
    assert (code, out) == (2, "1 file could not be read; no findings in the 1 file read.\n")
    assert err.endswith("missing.urdf: no such file\n")
    assert validate(str(clean)) == (0, "No problems in 1 file.\n", "")  # a success says so


def test_the_coloured_summary_of_a_failure_is_not_green(validate, tmp_path):
    code, out, _ = validate("--color", "always", str(tmp_path / "missing.urdf"))
    assert code == 2 and "could not be read" in out
    assert "\x1b[32m" not in out and "\x1b[1m" in out
    from tests.lint.conftest import CLEAN

    (tmp_path / "clean.urdf").write_text(CLEAN)
    code, out, _ = validate("--color", "always", str(tmp_path / "clean.urdf"))
    assert code == 0 and "\x1b[32mNo problems in 1 file." in out


def test_an_empty_folder_or_an_unexpanded_file_prints_no_summary_of_success(validate,
                                                                           tmp_path):
    (tmp_path / "empty").mkdir()
    code, out, err = validate(str(tmp_path / "empty"))
    assert (code, out) == (2, "") and "no .urdf, .xacro or robot .xml file" in err
    robot = tmp_path / "arm.urdf.xacro"
    robot.write_text('<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
                     '<link name="$(arg prefix)base"/></robot>')
    code, out, _ = validate(str(robot))
    assert code == 0 and "No problems" not in out
    assert out.endswith("Found 1 info in 1 file; 1 file not expanded (TX002).\n")


BROKEN_DEMO = "fixtures/broken_robot.urdf"


@pytest.mark.parametrize(("columns", "color"), [(80, "auto"), (120, "auto"), (80, "never")])
def test_findings_on_a_terminal_wrap_to_its_width(columns, color):
    """Each finding on the lines it needs, the next ones indented; in a pipe, one a line."""
    code, piped, _ = in_pipe("validate", BROKEN_DEMO)
    findings = piped.splitlines()[:-1]
    assert code == 1 and any(len(line) > 120 for line in findings)
    code, _, screen = in_terminal("validate", BROKEN_DEMO, "--color", color, columns=columns)
    shown = ANSI.sub("", screen).splitlines()
    assert code == 1 and widest(screen) <= columns
    starts = [line for line in shown if not line.startswith(" ")]
    assert [line.split(": ")[0] for line in starts[:-1]] == [
        line.split(": ")[0] for line in findings]
    assert " ".join(" ".join(line.split()) for line in shown[:-1]) == " ".join(
        " ".join(line.split()) for line in findings)


@pytest.mark.parametrize("command", [("show", DEMO), ("show", DEMO, "--actuator-limits")])
def test_a_table_wider_than_the_terminal_folds_to_one_record_a_row(command):
    """At 80 columns rich cut every cell of the table to a few letters."""
    code, _, screen = in_terminal(*command, columns=80)
    text = ANSI.sub("", screen)
    assert code == 0 and widest(screen) <= 80 and "…" not in text
    assert "transmission  shoulder_trans:60" in text
    assert "member        actuator wrist_right_motor" in text
    assert "interfaces    EffortJointInterface" in text
    code, _, screen = in_terminal(*command, columns=200)
    assert code == 0 and "┃ transmission" in ANSI.sub("", screen)  # the table, where it fits
