"""The lint entry points for commands and callers: files in, problems and an exit code out."""

from __future__ import annotations

from dataclasses import dataclass, field

from txtool.config import Overrides, SettingsCache
from txtool.lint.discover import expand_paths
from txtool.lint.engine import lint_file, lint_source
from txtool.problem import Problem
from txtool.xmlio import InputError, XacroOptions

__all__ = ["LintOptions", "LintResult", "exit_code", "lint_paths", "lint_source"]


@dataclass(frozen=True)
class LintOptions:
    """Everything ``txtool validate`` takes besides the paths and the output format."""

    select: tuple[str, ...] | None = None
    ignore: tuple[str, ...] = ()
    config: str | None = None
    xacro: XacroOptions = XacroOptions()
    no_xacro: bool = False
    stdin_filename: str | None = None
    strict: bool = False
    exit_zero: bool = False


@dataclass
class LintResult:
    """Problems of every file in input order, how many files were read, and input errors."""

    problems: list[Problem] = field(default_factory=list)
    files: int = 0
    errors: list[str] = field(default_factory=list)

    def count(self, severity: str) -> int:
        return sum(1 for p in self.problems if p.severity == severity)


def lint_paths(paths: list[str] | tuple[str, ...], options: LintOptions) -> LintResult:
    """Lint files, folders (recursively) and ``-``.

    A file that cannot be read is recorded in ``errors`` and the others are still checked; a
    bad configuration or rule selection raises :class:`~txtool.config.ConfigError`.
    """
    overrides = Overrides(
        select=options.select, ignore=options.ignore, xacro=options.xacro,
        no_xacro=options.no_xacro,
    )
    settings = SettingsCache(overrides, options.config)
    result = LintResult()
    for path in expand_paths(paths):
        where = options.stdin_filename if path == "-" and options.stdin_filename else path
        file_settings = settings.for_file(where)  # a ConfigError stops the run
        try:
            problems = lint_file(path, file_settings, stdin_name=options.stdin_filename)
        except InputError as exc:
            result.errors.append(str(exc))
            continue
        result.files += 1
        result.problems.extend(problems)
    return result


def exit_code(result: LintResult, options: LintOptions) -> int:
    """0: nothing at the failing level; 1: findings at it; 2: a file could not be read.

    Errors fail; warnings fail under ``strict``; infos never do. ``exit_zero`` turns 1
    into 0 but never hides 2.
    """
    if result.errors:
        return 2
    failing = {"error", "warning"} if options.strict else {"error"}
    if options.exit_zero or not any(p.severity in failing for p in result.problems):
        return 0
    return 1

