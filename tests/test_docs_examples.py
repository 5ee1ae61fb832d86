"""Every console example in README.md and docs/*.md runs as written and prints what it shows.

A ```console block is a session: lines starting with ``$ `` are commands (a trailing ``\\``
continues one), the lines after a command are what it prints (standard output and standard
error together). A line ``...`` stands for any number of lines, and a line ending in ``...``
for any line that starts with what comes before it. A command followed by no lines prints
nothing. A block marked ``<!-- not run: REASON -->`` is shown only (see :data:`NOT_RUN`). The commands of a page run one after another, in one folder laid out as
``txtool demo --copy DIR`` lays it out (the demo robots in ``fixtures/``, and ``fixtures/examples/*``
at its top), so a page can change a file and look at it again; a ``$ cd DIR`` moves the
commands that follow into ``DIR``. A contributor's page runs in a copy of the repository.
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
from dataclasses import dataclass, field
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PAGES = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
BLOCK = re.compile(r"^(?:<!-- not run: (?P<why>[^\n]+) -->\n)?```console\n(?P<body>.*?)^```$",
                   re.M | re.S)
# The console examples that are shown, not run, each with its reason (a cluster's address, a
# run of minutes): this list, not the pages, says which may be.
NOT_RUN = {
    "simulate.md": 3,
}


@dataclass
class Step:
    command: str
    expected: list[str] = field(default_factory=list)


def sessions(text: str) -> list[list[Step]]:
    """The console blocks of a page that run, each as its commands and their shown output."""
    blocks = []
    for match in BLOCK.finditer(text):
        if match.group("why"):
            continue
        steps: list[Step] = []
        continued = False
        for line in match.group("body").splitlines():
            if continued:
                steps[-1].command += "\n" + line
                continued = line.endswith("\\")
            elif line.startswith("$ "):
                steps.append(Step(line[2:]))
                continued = line.endswith("\\")
            else:
                assert steps, f"output before any command: {line!r}"
                steps[-1].expected.append(line)
        blocks.append(steps)
    return blocks


def matches(expected: list[str], actual: list[str]) -> bool:
    """Whether ``actual`` is what ``expected`` shows, ``...`` lines and line ends as wildcards."""
    if not expected:
        return not actual
    head, rest = expected[0], expected[1:]
    if head.strip() == "...":
        return any(matches(rest, actual[i:]) for i in range(len(actual) + 1))
    if not actual:
        return False
    line = actual[0].rstrip()
    if head.endswith("...") and line.startswith(head[:-3].rstrip()):
        return matches(rest, actual[1:])
    return line == head.rstrip() and matches(rest, actual[1:])


# Pages for contributors: their examples run in a copy of the repository (its package, docs
# and fixtures), as a contributor runs them from a clone.
REPOSITORY_PAGES = {"contributing.md"}


def repository_copy(tmp_path: Path) -> Path:
    for folder in ("txtool", "docs", "fixtures", "schemas"):
        shutil.copytree(ROOT / folder, tmp_path / folder,
                        ignore=shutil.ignore_patterns("__pycache__"))
    shutil.copy(ROOT / "pyproject.toml", tmp_path)
    return tmp_path


def workspace(tmp_path: Path) -> Path:
    """A folder laid out as ``txtool demo --copy`` lays it out."""
    from txtool.io.resources import example_layout

    for name, source in example_layout().items():
        (tmp_path / name).parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(source, tmp_path / name)
    return tmp_path


def run(step: Step, cwd: Path) -> list[str]:
    env = {key: value for key, value in os.environ.items()
           if not key.startswith(("TXTOOL_", "GITHUB_", "ROS_", "AMENT_", "CMAKE_", "FORCE_COLOR"))}
    env.pop("COLUMNS", None)  # in a pipe, a table takes the width it needs
    env.update(NO_COLOR="1", PYTHONUNBUFFERED="1",
               PATH=os.pathsep.join([str(Path(sys.executable).parent), env.get("PATH", "")]))
    done = subprocess.run(["bash", "-c", step.command], cwd=cwd, env=env, timeout=300,
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    return done.stdout.splitlines()


def test_the_session_reader_and_the_wildcards():
    text = "```console\n$ a \\\n  b\none\n...\n$ c\n```\n"
    assert [(s.command, s.expected) for s in sessions(text)[0]] == [
        ("a \\\n  b", ["one", "..."]), ("c", [])]
    assert matches(["one", "...", "four"], ["one", "two", "three", "four"])
    assert matches(["one ..."], ["one two"])
    assert not matches(["one"], ["one", "two"])
    assert not matches([], ["unexpected"])
    assert not matches(["one", "...", "four"], ["one", "two"])


def test_only_the_listed_examples_are_not_run():
    shown = {page.name: len([m for m in BLOCK.finditer(page.read_text(encoding="utf-8"))
                             if m.group("why")]) for page in PAGES}
    assert {name: count for name, count in shown.items() if count} == NOT_RUN


@pytest.mark.parametrize("page", PAGES, ids=lambda p: p.relative_to(ROOT).as_posix())
def test_console_examples_print_what_they_show(page, tmp_path):
    blocks = sessions(page.read_text(encoding="utf-8"))
    if not blocks:
        pytest.skip("no console example")
    cwd = (repository_copy if page.name in REPOSITORY_PAGES else workspace)(tmp_path)
    for steps in blocks:
        for step in steps:
            if step.command.startswith("cd ") and not step.expected:
                cwd = cwd / step.command[3:].strip()  # as the shell would, for what follows
                continue
            actual = run(step, cwd)
            assert matches(step.expected, actual), (
                f"$ {step.command}\n--- shown\n" + "\n".join(step.expected)
                + "\n--- printed\n" + "\n".join(actual))
