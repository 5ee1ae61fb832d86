"""Names from a file are printed as text by every command that prints them through rich, in
every colour mode: ``arm:warning:`` is not an emoji code, ``[bold]`` is not markup."""

from __future__ import annotations

import importlib.util
from pathlib import Path

import pytest

from tests.hardening.conftest import Run

ROOT = Path(__file__).resolve().parents[2]
NAME = "arm:warning:[bold]x:smile:"
ROBOT = (ROOT / "fixtures" / "demo_robot.urdf").read_text().replace(
    '<transmission name="shoulder_trans"', f'<transmission name="{NAME}"')
COLOURS = ["never", "always", "auto"]


@pytest.fixture
def robot(tmp_path: Path) -> str:
    (tmp_path / "arm.urdf").write_text(ROBOT)
    return "arm.urdf"


def assert_shown_as_text(code: int, out: str) -> None:
    assert code in (0, 1), out
    assert "arm:warning:" in out and ":smile:" in out, out
    assert "\N{WARNING SIGN}" not in out and "\N{SMILING FACE WITH OPEN MOUTH}" not in out


@pytest.mark.parametrize("colour", COLOURS)
@pytest.mark.parametrize("command", [["show"], ["show", "--effective"], ["roundtrip"]])
def test_show_and_roundtrip_print_names_as_text(run: Run, robot: str, command: list[str],
                                                colour: str):
    code, out, _ = run(*command, robot, "--color", colour)
    assert_shown_as_text(code, out)


def test_map_prints_names_as_text(run: Run, robot: str):
    code, out, _ = run("map", robot, "-t", NAME, "--to", "actuator", "--position", "0.1")
    assert "[bold]" in out.replace("\n", "").replace(" ", ""), out  # (the title wraps)
    assert_shown_as_text(code, out.replace("\n", "").replace(" ", ""))


@pytest.mark.skipif(importlib.util.find_spec("pinocchio") is None,
                    reason="simulate needs the 'sim' extra (pinocchio)")
@pytest.mark.parametrize("colour", COLOURS)
def test_simulate_prints_names_as_text(run: Run, robot: str, colour: str):
    code, out, _ = run("simulate", robot, "--duration", "0.2", "--color", colour)
    assert_shown_as_text(code, out)
