"""Every test starts from the same environment, whatever shell or CI runner started pytest.

txtool reads ``GITHUB_ACTIONS`` (validate's default format), ``GITHUB_WORKSPACE`` (what the
github format's paths are relative to), ``TXTOOL_NO_XACRO`` (no
expansion), ``NO_COLOR``/``FORCE_COLOR``/``TERM`` (colour) and the ROS package paths
(``$(find pkg)``); rich reads ``COLUMNS``/``LINES`` (table width). A GitHub runner sets
``GITHUB_ACTIONS=true`` and ``GITHUB_WORKSPACE`` (action.yml's script reads ``GITHUB_OUTPUT``
and ``RUNNER_OS`` too), README recommends ``TXTOOL_NO_XACRO=1`` for CI and a sourced ROS shell
sets the package paths, so without this fixture the suite's results would depend on where it
runs. Tests that need one of these set it themselves with ``monkeypatch``.
"""

from __future__ import annotations

import contextlib
import os
import sys
from collections.abc import Iterator

import pytest
from hypothesis import settings

# Property tests draw the same examples on every run and every clone unless asked otherwise: a
# test suite that fails on one machine and passes on the next says nothing. Exploration with
# fresh examples is a separate step (.ci/run): TXTOOL_HYPOTHESIS=random, with
# --hypothesis-seed=SEED to draw again what one run drew.
HYPOTHESIS_PROFILE = "TXTOOL_HYPOTHESIS"
settings.register_profile("derandomized", derandomize=True, database=None, print_blob=True)
settings.register_profile("random", derandomize=False, database=None, print_blob=True)
settings.load_profile(os.environ.get(HYPOTHESIS_PROFILE) or "derandomized")

@contextlib.contextmanager
def untraced() -> Iterator[None]:
    """The block without the line tracer that measures coverage (.ci/run) in this thread, for
    a test that measures the work or the time of a large input: the tracer's cost would be part
    of the time measured, and the large input takes no path that the test's smaller ones, run
    traced, do not. Without a tracer, nothing changes."""
    tracer = sys.gettrace()
    sys.settrace(None)
    try:
        yield
    finally:
        sys.settrace(tracer)  # coverage's tracer installs itself the fast way again at once


# Variables the test suite itself reads: they steer the tests, not txtool.
SUITE_CONTROLS = frozenset({"TXTOOL_REQUIRE_CORPUS", "TXTOOL_UPDATE_GOLDEN", "TXTOOL_ORACLE",
                            HYPOTHESIS_PROFILE})
CLEARED = (
    "GITHUB_ACTIONS",
    "GITHUB_WORKSPACE",  # the github format's paths are relative to it
    "GITHUB_OUTPUT",  # action.yml's script appends its exit code there
    "GITHUB_STEP_SUMMARY",
    "RUNNER_OS",  # part of action.yml's cache key
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


def neutral(environ: dict[str, str] | os._Environ[str]) -> dict[str, str]:
    """A copy of ``environ`` without what :func:`cleared_names` names: for an environment
    copied when a test module is imported, before :func:`neutral_environment` runs."""
    cleared = set(cleared_names(environ))
    return {name: value for name, value in environ.items() if name not in cleared}


@pytest.fixture(autouse=True)
def neutral_environment(monkeypatch: pytest.MonkeyPatch) -> None:
    for name in cleared_names(os.environ):
        monkeypatch.delenv(name, raising=False)
        # A library that sets the process's environment below os.environ (ncurses exports
        # COLUMNS and LINES, say) would still pass it to the programs the tests start.
        os.unsetenv(name)
