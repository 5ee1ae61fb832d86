"""``txtool validate --fix`` and ``--diff``: ``txtool migrate``'s fixes, through its entry point
(:func:`txtool.transform.migrate.migrate_paths`), on the files holding fixable findings.

A finding's rule says whether it is fixable; the fixes themselves are migrate's, which work
on the file as written (a xacro file is never expanded). So a finding stays marked fixable
only where migrate's fixes change its file under its rule's code: a TX300 finding in a xacro
file whose interface comes from a ``${...}`` expression is not, since the text holds no name
to prefix.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from txtool.lint.problem import Problem
    from txtool.reporters.fixes import Edit
    from txtool.transform.migrate import FileResult, Report


@dataclasses.dataclass(frozen=True)
class FixSelection:
    """The rules ``validate`` was told to check: migrate fixes the fixable ones among them."""

    select: tuple[str, ...] | None
    ignore: tuple[str, ...]
    config: str | None


def fixable_paths(problems: Sequence[Problem], stdin_name: str | None) -> list[str]:
    """The files holding findings marked fixable, in order; never standard input's."""
    paths = (p.path for p in problems if p.fixable and p.path != stdin_name)
    return list(dict.fromkeys(paths))


def run_fixes(paths: Sequence[str], mode: str, selection: FixSelection) -> Report:
    """migrate on ``paths`` in ``mode`` (``check``, ``diff`` or ``write``)."""
    from txtool.transform.migrate import MigrateOptions, migrate_paths

    options = MigrateOptions(mode=mode,  # type: ignore[arg-type]
                             select=selection.select, ignore=selection.ignore,
                             config=selection.config)
    return migrate_paths(paths, options)


def confirmed(problems: Sequence[Problem], stdin_name: str | None, selection: FixSelection,
              *, with_edits: bool) -> tuple[list[Problem], dict[str, tuple[Edit, ...]]]:
    """The findings, marked fixable only where migrate's fixes change their file under their
    code; and, with ``with_edits``, what they change in each such file."""
    paths = fixable_paths(problems, stdin_name)
    if not paths:
        return list(problems), {}
    report = run_fixes(paths, "check", selection)
    fixed = {result.path: result for result in report.files}
    edits: dict[str, tuple[Edit, ...]] = {}
    if with_edits:
        from txtool.io.encodings import document_text
        from txtool.reporters.fixes import edits_between

        edits = {path: edits_between(document_text(result.original),
                                     document_text(result.data))
                 for path, result in fixed.items() if result.changed}
    return [_marked(p, fixed, stdin_name) for p in problems], edits


def _marked(problem: Problem, fixed: Mapping[str, FileResult],
            stdin_name: str | None) -> Problem:
    if not problem.fixable or problem.path == stdin_name:
        return problem
    result = fixed.get(problem.path)  # None: not read again (the same file by another name)
    if result is None or (result.changed and result.fixes.get(problem.code)):
        return problem
    return dataclasses.replace(problem, fixable=False)
