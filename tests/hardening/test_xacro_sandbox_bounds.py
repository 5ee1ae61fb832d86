"""The sandbox's own bounds as tables, through its worker: output bytes at and past the bound,
the memory bound shared by 0, negative and several processes, and one worker reused across
files (what one file's request sets must not reach the next).
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from click.testing import CliRunner

from tests.hardening.hostile_inputs import xacro_robot as robot
from txtool.cli import cli
from txtool.io.xacro import expand_text
from txtool.io.xacro_guard import XacroGuard
from txtool.io.xacro_sandbox import MAX_OUTPUT, XacroLimit, expand_in_sandbox, sharing
from txtool.io.xmlio import XacroError, XacroOptions

SECRET = "s3cr3t-2e90"


def sandboxed(path: Path, options: XacroOptions | None = None) -> str:
    """The expansion in the worker, or what stopped it, as one line."""
    try:
        return expand_in_sandbox(str(path), path.name, options or XacroOptions())
    except (XacroLimit, XacroError) as exc:
        return f"stopped: {exc}"


# -- output: the expanded text may be MAX_OUTPUT bytes, not one more ----------------------------

COPIES = 64


def copied(size: int, pad: int) -> str:
    """``COPIES`` copies of a text of ``size`` bytes (one string, copied by macro calls: little
    memory and work), and ``pad`` bytes more."""
    return robot('<xacro:macro name="m" params=""><t>' + "_" * size + "</t></xacro:macro>"
                 + "<xacro:m/>" * COPIES + "<p>" + "_" * pad + "</p>")


def test_the_output_at_and_past_its_bound(repo):
    path = repo / "robot.urdf.xacro"
    path.write_text(copied(10, 1))  # the bytes around the copies, measured once
    options = XacroOptions()
    around = len(expand_text(str(path), path.name, options,
                             XacroGuard(str(path), options, {})).encode()) - COPIES * 10 - 1
    size = (MAX_OUTPUT - around) // COPIES
    pad = MAX_OUTPUT - around - COPIES * size
    path.write_text(copied(size, pad))
    assert len(sandboxed(path).encode()) == MAX_OUTPUT
    path.write_text(copied(size, pad + 1))
    assert sandboxed(path) == (f"stopped: robot.urdf.xacro: xacro: expansion exceeded "
                               f"{MAX_OUTPUT} bytes of output (a safety limit)")


# -- memory: each of N processes has its share, never under the least a worker needs ------------

# Twenty copies of a megabyte of text, each a string of its own: more than 64 MiB, well
# within 128 (and 256) MiB.
LARGE = robot('<xacro:macro name="m" params=""><t>' + "_" * 1_000_000 + "</t></xacro:macro>"
              + "<xacro:m/>" * 20)


OK = "ok"


@pytest.fixture(scope="module")
def fresh_worker(tmp_path_factory: pytest.TempPathFactory) -> None:
    """A limit retires the worker: the next file starts one with a small heap (an earlier
    file's large expansion may have left the last one's address space grown)."""
    path = tmp_path_factory.mktemp("loop") / "loop.urdf.xacro"
    path.write_text(robot('<xacro:macro name="loop" params=""><xacro:loop/></xacro:macro>'
                          "<xacro:loop/>"))
    assert "Python's recursion limit" in sandboxed(path)


@pytest.mark.parametrize(("processes", "expected"), [
    (0, OK), (-1, OK), (2, OK),
    (4, "64 MiB of memory"),  # a quarter of 256
    (8, "64 MiB of memory"),  # an eighth is under 64 MiB: the least a worker needs
])
def test_the_memory_bound_shared_by_n_processes(repo, monkeypatch, fresh_worker, processes,
                                                 expected):
    monkeypatch.setenv("TXTOOL_XACRO_MEMORY_MB", "256")
    path = repo / "large.urdf.xacro"
    path.write_text(LARGE)
    with sharing(processes):
        text = sandboxed(path)
    assert text.startswith("<?xml") if expected == OK else (
        text.startswith("stopped: large.urdf.xacro: xacro: expansion exceeded " + expected)), \
        text[:200]
    if expected != OK:  # the bound is whole again once the processes are done
        assert sandboxed(path).startswith("<?xml")


def test_an_attribute_past_the_memory_bound_is_the_memory_limit(repo, monkeypatch):
    """expat says it ran out of memory as a syntax error: the bound's, not the file's."""
    monkeypatch.setenv("TXTOOL_XACRO_MEMORY_MB", "64")
    path = repo / "wide.urdf.xacro"
    path.write_text(robot(f"<t a='{'_' * (8 << 20)}'/>"))
    assert sandboxed(path) == ("stopped: wide.urdf.xacro: xacro: expansion exceeded 64 MiB of "
                               "memory (a safety limit)")


# -- one worker, many files: the package variables are the parent's at each request -------------

def package_under(variable: str, root: Path) -> str:
    """A package 'evil' where ``variable`` finds it; the variable's value."""
    share = root / "share"
    folder = share / "evil"
    folder.mkdir(parents=True)
    (folder / "package.xml").write_text("<package><name>evil</name></package>\n")
    (folder / "secret.xacro").write_text(robot(f'<link name="{SECRET}"/>'))
    index = share / "ament_index" / "resource_index" / "packages"
    index.mkdir(parents=True)
    (index / "evil").write_text("")
    return str(share if variable == "ROS_PACKAGE_PATH" else root)


@pytest.mark.parametrize("variable", ["AMENT_PREFIX_PATH", "ROS_PACKAGE_PATH",
                                      "CMAKE_PREFIX_PATH"])
def test_a_package_variable_reaches_the_request_it_is_set_for_only(repo, monkeypatch, variable):
    value = package_under(variable, repo.parent / "prefix")
    path = repo / "robot.urdf.xacro"
    path.write_text(robot('<xacro:include filename="$(find evil)/secret.xacro"/>'))
    monkeypatch.setenv(variable, value)
    assert SECRET in sandboxed(path)
    monkeypatch.delenv(variable)
    text = sandboxed(path)  # the same worker, the next file
    assert text.startswith("stopped: robot.urdf.xacro:1: xacro: package 'evil' not found"), text


def test_a_commands_inputs_are_its_own_in_a_reused_worker(repo):
    """What an earlier command's expansion read is no input of the next one: its report may
    be written over such a file (the worker, reused, says only what this file read)."""
    (repo / "part.inc").write_text(robot('<link name="p"/>'))
    (repo / "a.urdf.xacro").write_text(robot('<xacro:include filename="part.inc"/>'))
    (repo / "b.urdf.xacro").write_text(robot('<link name="b"/>'))
    runner = CliRunner()
    refused = runner.invoke(cli, ["validate", "--format", "json:part.inc", "a.urdf.xacro"])
    assert refused.exit_code == 2 and "is an input of this command" in refused.stderr
    written = runner.invoke(cli, ["validate", "--format", "json:part.inc", "b.urdf.xacro"])
    assert (written.exit_code, written.stderr) == (0, "")
    assert json.loads((repo / "part.inc").read_text())
