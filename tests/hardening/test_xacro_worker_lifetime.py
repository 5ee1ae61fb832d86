"""The xacro worker's life: one per process, reused across files with each file's budgets
afresh, replaced after a limit, never outliving txtool, and sharing the command's memory
bound with the workers of its forks (``validate -j N``)."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import pytest

from txtool.io import xacro_sandbox
from txtool.io.xacro_eval import MAX_WORK
from txtool.io.xacro_guard import MAX_NODES
from txtool.io.xacro_sandbox import XacroLimit, expand_in_sandbox
from txtool.io.xmlio import XacroError, XacroOptions
from txtool.lint.workers import forked_map

ROOT = Path(__file__).resolve().parents[2]


def robot(body: str) -> str:
    return ('<?xml version="1.0"?>\n<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
            f"  <link name=\"base\"/>\n{body}\n</robot>\n")


@pytest.fixture
def repo(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    root = tmp_path / "repo"
    (root / ".git").mkdir(parents=True)
    monkeypatch.chdir(root)
    for name in ("TXTOOL_XACRO_TIMEOUT", "TXTOOL_XACRO_MEMORY_MB"):
        monkeypatch.delenv(name, raising=False)
    return root


def expand(repo: Path, name: str, body: str) -> str:
    path = repo / name
    path.write_text(robot(body))
    return expand_in_sandbox(str(path), name, XacroOptions())


def worker_pid() -> int:
    assert xacro_sandbox._current is not None
    return xacro_sandbox._current.process.pid


# Two sums of a million: about 4,000,000 steps, more than half the budget of one file.
HEAVY = "".join(f'<link name="s{i}_${{python.sum(python.range(999999))}}"/>' for i in range(2))
# Calls of a macro whose body is a hundred nodes: more than half of MAX_NODES clones.
NODES = ('<xacro:macro name="m" params=""><g>' + "<a/>" * 99 + "</g></xacro:macro>"
         + "<h><xacro:m/></h>" * (MAX_NODES * 6 // 10 // 101))


@pytest.mark.parametrize("body", [HEAVY, NODES], ids=["work", "nodes"])
def test_each_file_has_its_own_budget_in_a_reused_worker(repo, body):
    expand(repo, "warm.urdf.xacro", '<link name="x"/>')
    pid = worker_pid()
    for name in ("a.urdf.xacro", "b.urdf.xacro", "c.urdf.xacro"):
        expand(repo, name, body)  # each alone takes over half the budget: no exception
        assert worker_pid() == pid


def test_the_budgets_are_real_in_the_worker(repo):
    with pytest.raises(XacroLimit) as raised:
        expand(repo, "twice.urdf.xacro", HEAVY + HEAVY)
    assert str(raised.value) == (f"twice.urdf.xacro: xacro: expansion exceeded {MAX_WORK} "
                                 "steps of work (a safety limit)")
    assert 'name="2"' in expand(repo, "next.urdf.xacro", '<link name="${1 + 1}"/>')


def test_a_lone_surrogate_is_one_line_and_the_worker_lives_on(repo):
    expand(repo, "warm.urdf.xacro", '<link name="x"/>')
    pid = worker_pid()
    for expression in ("'\\ud800'", "python.chr(0xdfff)"):
        with pytest.raises(XacroError) as raised:
            expand(repo, "lone.urdf.xacro", f'<link name="${{{expression}}}"/>')
        assert "a lone surrogate" in str(raised.value) and "memory" not in str(raised.value)
        assert worker_pid() == pid
    assert 'name="2"' in expand(repo, "next.urdf.xacro", '<link name="${1 + 1}"/>')


# Fifty copies of a megabyte of text (each evaluated anew, so each a string of its own):
# some 150 MiB with the document written out, more than an eighth of 512 MiB, at little work.
LARGE = ('<xacro:macro name="m" params=""><t>' + "_" * 1_000_000 + "</t></xacro:macro>"
         + "<xacro:m/>" * 50)


def test_the_memory_bound_is_shared_by_the_processes_of_one_command(repo):
    (repo / "large.urdf.xacro").write_text(robot(LARGE))
    assert "robot" in expand_in_sandbox("large.urdf.xacro", "large", XacroOptions())

    def one(_index: int) -> str:
        try:
            return expand_in_sandbox("large.urdf.xacro", "large", XacroOptions())[:6]
        except XacroLimit as exc:
            return str(exc)

    said = list(forked_map(one, 8, 8, size=1))
    assert all(s.startswith("large: xacro: expansion exceeded 64 MiB of memory") for s in said)


KILLED = textwrap.dedent("""
    import sys, time
    from txtool.io import xacro_sandbox
    from txtool.io.xmlio import XacroOptions
    xacro_sandbox.expand_in_sandbox(sys.argv[1], "r", XacroOptions())
    print(xacro_sandbox._current.process.pid, flush=True)
    time.sleep(60)
""")


def state(pid: int) -> str:
    """The process's state letter (Z: ended, not yet reaped); '' when it is gone."""
    try:
        return Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0]
    except OSError:
        return ""


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc")
def test_the_worker_ends_when_txtool_is_killed(repo):
    (repo / "r.urdf.xacro").write_text(robot('<link name="x"/>'))
    parent = subprocess.Popen([sys.executable, "-c", KILLED, str(repo / "r.urdf.xacro")],
                              stdout=subprocess.PIPE, text=True,
                              env={**os.environ, "PYTHONPATH": str(ROOT)})
    try:
        assert parent.stdout is not None
        child = int(parent.stdout.readline())
        assert state(child) not in ("", "Z")
        parent.send_signal(signal.SIGKILL)
        parent.wait()
        deadline = time.monotonic() + 10
        while state(child) not in ("", "Z") and time.monotonic() < deadline:
            time.sleep(0.02)
        assert state(child) in ("", "Z")
    finally:
        parent.kill()
        parent.wait()
        if parent.stdout is not None:
            parent.stdout.close()


def cpu_seconds(pid: int) -> float:
    fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")  # utime + stime


def cpu_limit(pid: int) -> int:
    line = next(line for line in Path(f"/proc/{pid}/limits").read_text().splitlines()
                if line.startswith("Max cpu time"))
    return int(line.split()[3])


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc")
def test_a_reused_worker_has_a_whole_cpu_budget_for_each_file(repo):
    """The worker's processor-time limit is set before each file from the time it has used:
    a worker that has spent seconds on earlier files still has the whole timeout (and 2 s) for
    the next, however long it has lived."""
    expand(repo, "warm.urdf.xacro", '<link name="x"/>')
    pid = worker_pid()
    for attempt in range(20):
        used = cpu_seconds(pid)
        expand(repo, f"f{attempt}.urdf.xacro", NODES)
        assert worker_pid() == pid
        if used >= 1.2:
            break
    assert used >= 1.2, "the worker did not spend the time this test needs"
    assert cpu_limit(pid) >= int(used + 30) + 2
