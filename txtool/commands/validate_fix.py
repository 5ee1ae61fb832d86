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
import os
from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING

import click

from txtool.io.printable import printable

if TYPE_CHECKING:
    from txtool.io.xmlio import XacroOptions
    from txtool.lint.api import LintResult
    from txtool.lint.problem import Problem
    from txtool.reporters.fixes import Edit
    from txtool.transform.migrate import FileResult, Report


@dataclasses.dataclass(frozen=True)
class FixSelection:
    """The rules ``validate`` was told to check: migrate fixes the fixable ones among them."""

    select: tuple[str, ...] | None
    ignore: tuple[str, ...]
    config: str | None
    # How validate read the files: the fixed text is checked the same way (lint.target_check)
    ros_distro: str | None = None
    xacro: XacroOptions | None = None
    no_xacro: bool = False
    jobs: int = 0  # validate's --jobs: the processes that share the files


def fixable_paths(problems: Sequence[Problem], stdin_name: str | None) -> list[str]:
    """The files holding findings marked fixable, in order; never standard input's."""
    paths = (p.path for p in problems if p.fixable and p.path != stdin_name)
    return list(dict.fromkeys(paths))


def print_diff(result: LintResult, selection: FixSelection) -> int:
    """``--diff``: migrate's diff of the files holding fixable findings; nothing written.
    2 if a file could not be read, 1 if one would change, else 0."""
    paths = _targets(result.problems)
    if not paths:
        click.echo("txtool: nothing to fix", err=True)
        return 2 if result.errors else 0
    report = run_fixes(paths, "diff", selection)
    for text in report.diffs:
        click.echo(text, nl=False)
    for message in report.messages:
        if not message.startswith("txtool: note: "):  # the configuration's, told already
            click.echo(printable(message), err=True)
    return 2 if result.errors else report.exit_code


def apply_fixes(result: LintResult, selection: FixSelection) -> tuple[bool, bool, bool]:
    """``--fix``: migrate rewrites the files holding fixable findings; whether it changed one,
    whether a write failed, and whether a file's fixes were refused (what they would write
    has an error for the file's readers that it did not have: it is left unchanged)."""
    paths = _targets(result.problems)
    if not paths:
        return False, False, False
    report = run_fixes(paths, "write", selection)
    for message in report.messages:
        if message.startswith(("error: ", "refused ")):
            click.echo(printable(message), err=True)
    for changed in report.changed:
        click.echo(f"txtool: fixed {printable(changed.path)} ({changed.describe()})", err=True)
    for error in report.errors:
        click.echo(f"txtool: {printable(error)}", err=True)
    return bool(report.changed), bool(report.errors), bool(report.refused)


def _targets(problems: Sequence[Problem]) -> list[str]:
    """:func:`fixable_paths` without a leading ``./`` (a walk of ``.``), so that diff headers
    read ``a/src/x.urdf``; ``--fix`` and ``--diff`` refuse standard input beforehand."""
    return [_without_dot(path) for path in fixable_paths(problems, None)]


def _without_dot(path: str) -> str:
    for prefix in ("./", "." + os.sep):
        while path.startswith(prefix) and len(path) > len(prefix):
            path = path[len(prefix):]
    return path


def run_fixes(paths: Sequence[str], mode: str, selection: FixSelection) -> Report:
    """migrate on ``paths`` in ``mode`` (``check``, ``diff`` or ``write``)."""
    from txtool.transform.migrate import MigrateOptions, migrate_paths

    options = MigrateOptions(mode=mode,  # type: ignore[arg-type]
                             select=selection.select, ignore=selection.ignore,
                             config=selection.config, ros_distro=selection.ros_distro,
                             no_xacro=selection.no_xacro, jobs=selection.jobs)
    if selection.xacro is not None:
        options = dataclasses.replace(options, xacro=selection.xacro)
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
