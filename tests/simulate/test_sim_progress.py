"""A progress bar on stderr when it is a terminal and a run takes a while, nothing in a pipe;
the default duration that --help gives is what runs."""

from __future__ import annotations

import io
import re

import pytest
from click.testing import CliRunner
from rich.console import Console

from tests.simulate.robots import arm_ros1, write
from txtool.cli import cli
from txtool.simulation import app
from txtool.simulation.feasible import LONGEST_MOVE
from txtool.simulation.run import DEFAULTS, Options


def stderr_of(tmp_path, monkeypatch, terminal: bool, configs: tuple[str, ...] = ()) -> str:
    """What simulate writes on a stderr that is a terminal (or not), every run counted long."""
    monkeypatch.setattr(app, "SHOW_AFTER", 0.0)
    robot = write(tmp_path, "arm.urdf", arm_ros1())
    out, err = io.StringIO(), io.StringIO()
    runs, code = app.main(Options(robot=robot, configs=configs, duration=0.5),
                          console=Console(file=out, width=100),
                          err_console=Console(file=err, force_terminal=terminal, width=100))
    assert code == 0 and "PASS" in out.getvalue()
    return err.getvalue()


def test_a_terminal_shows_the_progress_of_the_run(tmp_path, monkeypatch):
    shown = stderr_of(tmp_path, monkeypatch, terminal=True)
    assert "simulating" in shown and "100%" in shown
    assert "\x1b[" in shown  # drawn, then taken away (transient)


def test_a_terminal_shows_the_progress_of_several_configs(tmp_path, monkeypatch):
    robot = str(tmp_path / "arm.urdf")
    shown = stderr_of(tmp_path, monkeypatch, terminal=True, configs=(robot, robot))
    assert "configs" in shown and "100%" in shown


def test_a_pipe_gets_no_progress(tmp_path, monkeypatch):
    assert stderr_of(tmp_path, monkeypatch, terminal=False) == ""


@pytest.fixture(scope="module")
def help_text() -> str:
    result = CliRunner().invoke(cli, ["simulate", "--help"], terminal_width=200)
    return " ".join(result.stdout.split())


def test_help_gives_the_default_duration_that_runs(tmp_path, help_text):
    assert (f"Default: at least {DEFAULTS['duration']:g} s, stretched (up to "
            f"{2 * LONGEST_MOVE:g} s) until the default motion is feasible") in help_text
    robot = write(tmp_path, "arm.urdf", arm_ros1())
    code, out = _run(robot)
    assert code == 0
    assert re.search(rf"\d+ steps of 0.001 s \({DEFAULTS['duration']:g} s\)", out)
    slow = write(tmp_path, "slow.urdf", arm_ros1().replace('effort="40" velocity="3"',
                                                           'effort="40" velocity="0.1"'))
    code, out = _run(slow)
    seconds = float(re.search(r"steps of 0.001 s \(([\d.]+) s\)", out).group(1))
    assert code == 0 and DEFAULTS["duration"] < seconds <= 2 * LONGEST_MOVE


def _run(robot: str) -> tuple[int, str]:
    result = CliRunner().invoke(cli, ["simulate", robot], catch_exceptions=False)
    return result.exit_code, result.stdout
