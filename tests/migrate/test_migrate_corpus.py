"""On copies of the corpus: after ``migrate --write`` validate finds no fixable problem left,
and a second run has nothing to do (also after each conversion)."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from tests.corpus import corpus_file, corpus_names
from txtool.dialects.read import transmission_elements
from txtool.io.xmlio import parse_bytes
from txtool.lint.api import LintOptions, lint_paths

NAMES = [n for n in corpus_names() if n.endswith((".xacro", ".urdf")) or n.startswith("<")]
NOTHING = "nothing to do (1 file(s) checked)\n"


def _copy(name: str, tmp_path: Path) -> Path:
    path = tmp_path / name
    shutil.copyfile(corpus_file(name), path)
    return path


@pytest.mark.parametrize("name", NAMES)
def test_after_migrate_validate_finds_no_fixable_problem_left(name, tmp_path, run):
    path = _copy(name, tmp_path)
    code, out, err = run("migrate", "--write", str(path))
    assert (code, out) == (0, ""), err
    # Expansion fails on a lone copy ($(find ...), relative includes): validate then lints
    # the file as written, the way it does for a macro library.
    result = lint_paths([str(path)], LintOptions())
    assert result.errors == []
    assert [p for p in result.problems if p.fixable] == []
    assert run("migrate", "--check", str(path)) == (0, "", NOTHING)


@pytest.mark.parametrize("target", ["ros1", "ros2-p1", "ros2-p2"])
@pytest.mark.parametrize("name", NAMES)
def test_a_second_conversion_has_nothing_to_do(name, target, tmp_path, run):
    path = _copy(name, tmp_path)
    before = len(transmission_elements(parse_bytes(path.read_bytes(), name).getroot()))
    code, out, err = run("migrate", "--write", "--to", target, "--allow-lossy", str(path))
    assert (code, out) == (0, ""), err
    after = len(transmission_elements(parse_bytes(path.read_bytes(), name).getroot()))
    assert after == before
    code, out, err = run("migrate", "--check", "--to", target, "--allow-lossy", str(path))
    assert (code, out) == (0, "")
    assert err.endswith(NOTHING)
