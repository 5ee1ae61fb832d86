"""The lint entry points for commands and callers: files in, problems and an exit code out."""

from __future__ import annotations

import os
import sys
import threading
from collections.abc import Callable, Iterator
from typing import NamedTuple

from txtool.io.xmlio import InputError, XacroOptions
from txtool.lint.config import Overrides, Settings, SettingsCache
from txtool.lint.config_files import find_config_cache_clear
from txtool.lint.discover import describes_robot, expand_paths
from txtool.lint.engine import lint_file, lint_source
from txtool.lint.macro_calls import without_repeats
from txtool.lint.problem import InputFailure, Problem
from txtool.lint.readers import FileReaders

__all__ = ["LintOptions", "LintResult", "exit_code", "lint_paths", "lint_source"]


class LintOptions(NamedTuple):
    """Everything ``txtool validate`` takes besides the paths and the output format."""

    select: tuple[str, ...] | None = None
    ignore: tuple[str, ...] = ()
    config: str | None = None
    xacro: XacroOptions = XacroOptions()
    no_xacro: bool = False
    stdin_filename: str | None = None
    strict: bool = False
    exit_zero: bool = False
    jobs: int = 0  # worker processes; 0: one per usable CPU when there are enough files
    exclude: tuple[str, ...] | None = None  # replaces the configuration's exclude
    extend_exclude: tuple[str, ...] = ()
    respect_gitignore: bool | None = None  # None: as configured (default True)
    ros_distro: str | None = None  # --ros-distro: the distribution reading the files
    force_exclude: bool = False  # exclude patterns pass over files named as well
    controllers: tuple[str, ...] = ()  # --controllers: controller files to judge (TX5xx)


class LintResult:
    """Problems of every file in input order, how many files were read, and input errors."""

    __slots__ = ("problems", "files", "errors", "readers", "notes")

    def __init__(self) -> None:
        self.problems: list[Problem] = []
        self.files = 0
        self.errors: list[InputFailure] = []
        # The readers each file holding transmissions was judged for, in input order.
        self.readers: list[FileReaders] = []
        self.notes: list[str] = []  # configuration files passed over (see SettingsCache)

    def count(self, severity: str) -> int:
        return sum(1 for p in self.problems if p.severity == severity)


def lint_paths(paths: list[str] | tuple[str, ...], options: LintOptions,
               progress: Callable[[int, int], None] | None = None) -> LintResult:
    """Lint files, folders (recursively) and ``-``; ``progress`` is told (files done, files in
    all) as each file's result arrives.

    A file that cannot be read is recorded in ``errors`` and the others are still checked; a
    bad configuration or rule selection raises :class:`~txtool.lint.config.ConfigError`. Many
    files are shared among worker processes (see :func:`worker_count`); the result is the
    same, in the same order, as when one process checks them all.
    """
    overrides = Overrides(
        select=options.select, ignore=options.ignore, xacro=options.xacro,
        no_xacro=options.no_xacro, exclude=options.exclude,
        extend_exclude=options.extend_exclude, respect_gitignore=options.respect_gitignore,
        ros_distro=options.ros_distro,
    )
    # Each run looks again: a script (or an editor) may change configuration files between runs.
    find_config_cache_clear()
    settings = SettingsCache(overrides, options.config)
    work: list[tuple[str, Settings]] = []
    named = frozenset(paths)
    unread: list[InputFailure] = []  # what a folder walk could not read; it went on
    def pass_over(path: str) -> bool:
        """A file named that describes no robot (a launch file, package.xml), or one an
        exclude pattern names under ``force_exclude`` (as pre-commit names every .xml file)."""
        return (options.force_exclude and settings.excluded(path, False)) or not describes_robot(
            path)

    for path in expand_paths(paths, skip=settings.excluded, gitignore=settings.respects_gitignore,
                             report=lambda where, reason: unread.append(
                                 InputFailure(where, f"{where}: {reason}")),
                             pass_over=pass_over):
        if path not in named and path.startswith("./") and path != "./-":
            path = path[2:]  # noqa: PLW2901 - a walk of '.' names urdf/r.urdf, as ruff does
        where = options.stdin_filename if path == "-" and options.stdin_filename else path
        work.append((path, settings.for_file(where)))  # a ConfigError stops the run
    result = LintResult()
    result.errors.extend(unread)
    result.notes.extend(settings.notes)
    shared = None if progress is None else (lambda done: progress(done, len(work)))
    outcomes = _outcomes(work, options, paths, _fragments(work, paths), shared)
    robots: list[tuple[str, Settings]] = []  # the files read, each a robot a controller may drive
    for done, outcome in enumerate(outcomes, 1):
        if progress is not None:
            progress(done, len(work))
        if isinstance(outcome, InputFailure):
            result.errors.append(outcome)
            continue
        result.files += 1
        result.problems.extend(outcome)
        readers = getattr(outcome, "readers", None)
        if readers is not None:
            result.readers.append(readers)
        if work[done - 1][0] != "-":
            robots.append(work[done - 1])
    result.problems = without_repeats(result.problems)
    _add_controllers(result, robots, paths, options, settings)
    return result


def _add_controllers(result: LintResult, robots: list[tuple[str, Settings]],
                     given: list[str] | tuple[str, ...], options: LintOptions,
                     settings: SettingsCache) -> None:
    """The controller files' findings (TX5xx): those named with ``--controllers``, and those
    of the packages of robot files found in folder walks (see
    :mod:`txtool.lint.controller_files`)."""
    from txtool.lint.controller_files import controller_problems

    named = frozenset(given)
    walked = [(path, s) for path, s in robots if path not in named]
    if not options.controllers and not walked:
        return
    folders = [path for path in given if path != "-" and os.path.isdir(path)]
    for outcome in controller_problems(robots, walked, folders, options.controllers,
                                       settings.for_file):
        if isinstance(outcome, InputFailure):
            result.errors.append(outcome)
        else:
            result.problems.extend(outcome)


def _fragments(work: list[tuple[str, Settings]], given: list[str] | tuple[str, ...]
               ) -> frozenset[str]:
    """The files found in folder walks that another file of ``work`` includes."""
    named = frozenset(given)
    walked = [path for path, settings in work if path not in named and not settings.no_xacro]
    if not walked:
        return frozenset()
    from txtool.lint.fragments import fragments

    expanded = ((path, settings.xacro) for path, settings in work if not settings.no_xacro)
    return fragments(expanded, walked)


# Below this many files per process, forking costs more than it saves.
MIN_FILES_PER_WORKER = 32


def worker_count(files: int, jobs: int) -> int:
    """How many processes (this one and its forks, see :mod:`txtool.lint.workers`) check
    ``files`` files: ``jobs``, or with 0 one per usable CPU, but one when there are few files,
    and one where processes cannot be forked (only a fork inherits the loaded modules cheaply)
    or threads are running (forking them is unsafe)."""
    if jobs == 1 or sys.platform == "win32" or not hasattr(os, "fork"):
        return 1
    if threading.active_count() > 1:
        return 1
    cpus = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count()
    wanted = jobs if jobs > 1 else (cpus or 1)
    return max(1, min(wanted, files // MIN_FILES_PER_WORKER))


def _outcomes(
    work: list[tuple[str, Settings]], options: LintOptions, given: tuple[str, ...] | list[str] = (),
    fragments: frozenset[str] = frozenset(), shared: Callable[[int], None] | None = None,
) -> Iterator[list[Problem] | InputFailure]:
    """Each file's problems, or why it could not be read, in input order; ``shared`` is told
    how many files are done while worker processes share them (their results come at the
    end)."""
    workers = worker_count(len(work), options.jobs)
    stdin_name = options.stdin_filename
    named = frozenset(given)
    if workers == 1 or any(path == "-" for path, _ in work):
        for index in range(len(work)):
            yield _lint_one(index, work, stdin_name, named, fragments)
        return
    from txtool.lint.workers import forked_map

    yield from forked_map(
        lambda index: _lint_one(index, work, stdin_name, named, fragments), len(work), workers,
        progress=shared,
    )


def _lint_one(
    index: int, work: list[tuple[str, Settings]], stdin_name: str | None, named: frozenset[str],
    fragments: frozenset[str] = frozenset(),
) -> list[Problem] | InputFailure:
    path, settings = work[index]
    try:
        return lint_file(path, settings, stdin_name=stdin_name, named=path in named,
                         fragment=path in fragments)
    except InputError as exc:
        shown = stdin_name if path == "-" and stdin_name else path
        return InputFailure(shown, str(exc))


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

