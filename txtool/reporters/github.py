"""GitHub Actions workflow commands: one ``::error file=...::message`` annotation per problem."""

from __future__ import annotations

import os
from collections.abc import Sequence

from txtool.io.printable import printable
from txtool.lint.problem import Problem
from txtool.reporters import Summary, end_of

LEVELS = {"error": "error", "warning": "warning", "info": "notice"}


def _data(text: str) -> str:
    """GitHub's escapes for ``%``, CR and LF; other control characters and bytes that are not
    UTF-8 (in a file name) as ``\\x1b``-style escapes, so no message drives the log viewer."""
    return printable(text.replace("%", "%25").replace("\r", "%0D").replace("\n", "%0A"))


def _property(text: str) -> str:
    return _data(text).replace(":", "%3A").replace(",", "%2C")


def annotation_path(path: str) -> str:
    """The path as GitHub matches it to a pull request's files: relative to the workspace
    (``GITHUB_WORKSPACE``, else the working folder), without ``./``; a file outside it keeps
    its absolute path."""
    if path == "-" or not path:
        return path
    root = os.environ.get("GITHUB_WORKSPACE") or os.getcwd()
    absolute = os.path.normpath(os.path.join(os.getcwd(), path))
    relative = os.path.relpath(absolute, root)
    if relative == os.pardir or relative.startswith(os.pardir + os.sep):
        return absolute
    return relative.replace(os.sep, "/")


def annotation(problem: Problem) -> str:
    end_line, end_column = end_of(problem)
    fields = [
        f"file={_property(annotation_path(problem.path))}",
        f"line={problem.line}",
        f"col={problem.column}",
        f"endLine={end_line}",
        f"endColumn={end_column}",
        f"title={_property(f'{problem.code} {problem.name}')}",
    ]
    level = LEVELS.get(problem.severity, "error")
    return f"::{level} {','.join(fields)}::{_data(problem.message + problem.chain())}"


def render(problems: Sequence[Problem], summary: Summary, *, color: bool = False) -> str:
    failures = (
        f"::error file={_property(annotation_path(f.path))},title=txtool::{_data(f.message)}\n"
        for f in summary.failures
    )
    return "".join(annotation(p) + "\n" for p in problems) + "".join(failures)
