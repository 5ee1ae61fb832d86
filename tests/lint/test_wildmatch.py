"""gitignore patterns matched without backtracking (txtool/lint/wildmatch.py): pathspec's meaning,
in time linear in the path."""

from __future__ import annotations

import random
import resource

import pathspec
import pytest

from txtool.lint.wildmatch import GitIgnore, Program

CRAFTED = "**/a**a**a**a**a**a**a**a**a**a**a**b"  # eleven stars in one name: re backtracks


def test_a_crafted_exclude_pattern_costs_linear_time():
    spec = GitIgnore((CRAFTED,))
    name = "a" * 4000 + "/c"
    before = resource.getrusage(resource.RUSAGE_SELF).ru_utime
    assert spec.match_file(name) is False
    assert spec.match_file("x/" + "a" * 200 + "b") is True
    assert resource.getrusage(resource.RUSAGE_SELF).ru_utime - before < 1.0


def test_patterns_mean_what_pathspec_says():
    """Random patterns and paths (negations, classes, escapes, ** anywhere, folders): the
    linear matcher and pathspec's GitIgnoreSpec give the same answer every time."""
    rng = random.Random(31)
    atoms = ["a", "b", "*", "**", "?", "/", "[ab]", "[!a]", "\\*", ".", "!", " ", "#", "[]a]",
             "[a-c]", "x/", "\\", "[^b]", "**/", "/**", "\n"]
    names = ["a", "b", "ab", "ba", "a.b", "aa", "*", "x", "a b", "!a", "#a", "]", "\\", "a\n"]
    compared = 0
    for _ in range(1500):
        lines = tuple("".join(rng.choice(atoms) for _ in range(rng.randint(1, 6)))
                      for _ in range(rng.randint(1, 4)))
        try:
            reference = pathspec.GitIgnoreSpec.from_lines(lines)
        except pathspec.patterns.gitignore.GitIgnorePatternError:
            continue
        ours = GitIgnore(lines)
        for _ in range(8):
            path = "/".join(rng.choice(names) for _ in range(rng.randint(1, 4)))
            path += rng.choice(["", "/"])
            assert ours.match_file(path) == reference.match_file(path), (lines, path)
            compared += 1
    assert compared > 8000


@pytest.mark.parametrize("regex", ["(?=a)", r"\d", "a{2}", "a*?", "(a)", "[a"])
def test_a_regular_expression_pathspec_does_not_write_is_refused(regex):
    with pytest.raises(ValueError):
        Program(regex)
