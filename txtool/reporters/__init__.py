"""Output formats of ``txtool validate``: pure functions from problems to text.

Each format is one module exposing ``render(problems, summary, *, color=False) -> str``; it is
imported only when chosen (the text format loads rich only when colouring).
"""

from __future__ import annotations

import hashlib
import importlib
from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, NamedTuple

from txtool.lint.problem import InputFailure, Problem
from txtool.lint.readers import FileReaders

if TYPE_CHECKING:
    from txtool.reporters.fixes import Edit

FORMATS: dict[str, str] = {
    "text": "text",
    "concise": "concise",
    "json": "json_format",
    "github": "github",
    "sarif": "sarif",
    "junit": "junit",
    "gitlab": "gitlab",
}


class Summary(NamedTuple):
    files: int
    errors: int
    warnings: int
    infos: int
    failures: tuple[InputFailure, ...] = ()  # files that could not be read
    readers: tuple[FileReaders, ...] = ()  # the readers each file was judged for
    not_expanded: int = 0  # xacro files whose expansion failed (TX002): checked as written only
    failing: tuple[str, ...] = ("error",)  # the severities that fail the run (--strict: warnings)
    fixable: int = 0  # findings that ``validate --fix`` fixes
    # What ``--fix`` would change in each file holding fixable findings (SARIF ``fixes``).
    edits: Mapping[str, tuple[Edit, ...]] | None = None

    @property
    def unreadable(self) -> int:
        return len(self.failures)

    @classmethod
    def of(
        cls, problems: Sequence[Problem], files: int, *, failures: Sequence[InputFailure] = (),
        readers: Sequence[FileReaders] = (), edits: Mapping[str, tuple[Edit, ...]] | None = None,
        failing: Sequence[str] = ("error",),
    ) -> Summary:
        def count(level: str) -> int:
            return sum(1 for p in problems if p.severity == level)

        not_expanded = len({p.path for p in problems if p.code == "TX002"})
        fixable = sum(1 for p in problems if p.fixable)
        return cls(files, count("error"), count("warning"), count("info"), tuple(failures),
                   tuple(readers), not_expanded, tuple(failing), fixable, edits)


def render(
    output_format: str, problems: Sequence[Problem], summary: Summary, *, color: bool = False,
    width: int | None = None,
) -> str:
    """The report in ``output_format`` (one of :data:`FORMATS`); ``width``: the text format's
    findings wrapped to that many columns (a terminal's), else one a line."""
    module = importlib.import_module(f"{__name__}.{FORMATS[output_format]}")
    if output_format == "text":
        return module.render(problems, summary, color=color, width=width)  # type: ignore[no-any-return]
    return module.render(problems, summary, color=color)  # type: ignore[no-any-return]


def end_of(problem: Problem) -> tuple[int, int]:
    """The exclusive end position, one character past the start when the pipeline set none."""
    if problem.end_line is None or problem.end_column is None:
        return problem.line, problem.column + 1
    return problem.end_line, problem.end_column


def fingerprints(problems: Sequence[Problem]) -> list[str]:
    """Each finding's identity across commits: a digest of its path, code and message, and
    how many alike came before it in the file, never of its line (a line added above moves
    it, and it stays the same finding: SARIF ``partialFingerprints``, GitLab ``fingerprint``)."""
    seen: dict[tuple[str, str, str], int] = {}
    found = []
    for problem in problems:
        key = (problem.path.removeprefix("./"), problem.code, problem.message)
        seen[key] = occurrence = seen.get(key, 0) + 1
        text = "\0".join([*key, str(occurrence)])
        found.append(hashlib.sha256(text.encode("utf-8", "surrogateescape")).hexdigest())
    return found
