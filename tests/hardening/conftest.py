"""The hardening tests' way of running the command line (in this process, in a fresh folder)
and the repository the xacro tests expand in."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import pytest
from click.testing import CliRunner

from txtool.cli import cli
from txtool.io.packages import packages_below

Run = Callable[..., tuple[int, str, str]]


@pytest.fixture
def run(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Run:
    """``txtool ARGS`` run in ``tmp_path``: (exit code, stdout, stderr)."""
    monkeypatch.chdir(tmp_path)

    def invoke(*args: str) -> tuple[int, str, str]:
        result = CliRunner().invoke(cli, list(args), catch_exceptions=False)
        return result.exit_code, result.stdout, result.stderr

    return invoke


@pytest.fixture
def repo(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """A repository, the working folder, with no package path and no xacro setting from the
    environment (a test module may define its own)."""
    root = tmp_path / "repo"
    (root / ".git").mkdir(parents=True)
    monkeypatch.chdir(root)
    for name in ("ROS_PACKAGE_PATH", "AMENT_PREFIX_PATH", "CMAKE_PREFIX_PATH", "TXTOOL_NO_XACRO",
                 "TXTOOL_XACRO_TIMEOUT", "TXTOOL_XACRO_MEMORY_MB"):
        monkeypatch.delenv(name, raising=False)
    packages_below.cache_clear()
    return root
