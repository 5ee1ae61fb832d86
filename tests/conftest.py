"""Every test starts from the same environment, whatever shell or CI runner started pytest.

txtool reads ``GITHUB_ACTIONS`` (validate's default format), ``TXTOOL_NO_XACRO`` (no
expansion), ``NO_COLOR``/``FORCE_COLOR``/``TERM`` (colour) and the ROS package paths
(``$(find pkg)``); rich reads ``COLUMNS``/``LINES`` (table width). A GitHub runner sets
``GITHUB_ACTIONS=true``, README recommends ``TXTOOL_NO_XACRO=1`` for CI and a sourced ROS shell
sets the package paths, so without this fixture the suite's results would depend on where it
runs. Tests that need one of these set it themselves with ``monkeypatch``.
"""

from __future__ import annotations

import os

import pytest

# Variables the test suite itself reads: they steer the tests, not txtool.
SUITE_CONTROLS = frozenset({"TXTOOL_REQUIRE_CORPUS", "TXTOOL_UPDATE_GOLDEN", "TXTOOL_ORACLE"})
CLEARED = (
    "GITHUB_ACTIONS",
    "NO_COLOR",
    "FORCE_COLOR",
    "CLICOLOR",
    "CLICOLOR_FORCE",
    "TERM",
    "COLUMNS",
    "LINES",
    "TTY_COMPATIBLE",
    "TTY_INTERACTIVE",
    "AMENT_PREFIX_PATH",
    "ROS_PACKAGE_PATH",
    "CMAKE_PREFIX_PATH",
)


def cleared_names(environ: dict[str, str] | os._Environ[str]) -> list[str]:
    """The variables of ``environ`` that a test must not inherit."""
    own = [name for name in environ if name.startswith("TXTOOL_") and name not in SUITE_CONTROLS]
    return [*CLEARED, *own]


@pytest.fixture(autouse=True)
def neutral_environment(monkeypatch: pytest.MonkeyPatch) -> None:
    for name in cleared_names(os.environ):
        monkeypatch.delenv(name, raising=False)
