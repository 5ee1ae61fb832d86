"""The lint pipeline for one document: parse, expand, run rules, stamp, suppress, sort.

Which tree the rules see:

* a plain file: the file as parsed;
* a xacro file whose expansion contains transmissions: the expansion (positions traced back to
  the file as written, see :mod:`txtool.io.locate`);
* a xacro macro library (the expansion has no transmission, the file has some inside macros),
  a xacro file read from stdin or with xacro turned off, or one whose expansion failed (TX002):
  the file as written, in *literal* mode, where values containing ``${...}``/``$(...)`` are
  unknown. A file with both literal transmissions and transmissions produced by macro calls is
  checked on its expansion: every transmission it produces is checked once, where it is
  produced; macros the file defines but never calls are not checked then.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Iterable
from dataclasses import replace
from typing import TYPE_CHECKING

from txtool.io.encodings import Lines, document_text, text_lines
from txtool.io.load import needs_expansion
from txtool.io.xmlio import (
    InputError,
    Source,
    XMLSyntax,
    parse_bytes,
    read_bytes,
)
from txtool.lint.config import Settings, resolve
from txtool.lint.context import LintContext
from txtool.lint.problem import Problem
from txtool.lint.readers import Findings, record
from txtool.lint.rule_helpers import all_canonical
from txtool.lint.suppress import Suppressions
from txtool.lint.suppress import parse as parse_suppressions
from txtool.lint.text import scanned_form
from txtool.rules import Rule, all_rules

if TYPE_CHECKING:
    from txtool.io.xacro import XacroError
    from txtool.lint.config import Config

PIPELINE_CODES = frozenset({"TX001", "TX002", "TX003", "TX005", "TX006"})
_TAG_END = re.compile(r"<[^>]*>?")


def lint_source(source: Source, config: Config | Settings | None = None) -> list[Problem]:
    """Problems of an already loaded document (expanded or not), sorted by position."""
    settings = as_settings(config)
    return finish(_checked(source, settings), source, settings)


def lint_file(
    path: str, settings: Settings, *, stdin_name: str | None = None, named: bool = False,
    fragment: bool = False,
) -> list[Problem]:
    """Problems of one file (or ``-``); malformed XML and failed xacro are findings.

    A file ``named`` on the command line that holds no transmission gets TX006 (a file found
    in a folder walk, such as an included fragment, does not). A ``fragment`` (a file another
    checked file includes, see :mod:`txtool.lint.fragments`) whose expansion alone fails is
    checked as written, without TX002: its includer's expansion is its check. Raises
    :class:`~txtool.io.xmlio.InputError` when the file cannot be read.
    """
    problems = _lint_file(path, settings, stdin_name, fragment)
    if named and "TX006" in settings.enabled and not problems and problems.readers is None:
        return _no_transmission(path, stdin_name, settings)
    return problems


def lint_buffer(path: str, data: bytes, settings: Settings) -> list[Problem]:
    """Problems of ``data``, the unsaved text of the file at ``path`` (an editor's buffer),
    checked as :func:`lint_file` checks that file found in a folder walk (no TX006): ``path``
    names it, and a xacro expansion finds its includes and packages from where it is."""
    return _lint_file(path, settings, None, buffer=data)


def _no_transmission(path: str, stdin_name: str | None, settings: Settings) -> list[Problem]:
    display, data = read_bytes(path, stdin_name=stdin_name)
    try:
        source = Source(path=display, data=data, tree=parse_bytes(data, display))
        if not settings.no_xacro and needs_expansion(display, data, source.tree) and path != "-":
            from txtool.io.xacro import expand_xacro

            tree = expand_xacro(path, display, settings.xacro)
            source = Source(path=display, data=data, tree=tree, expanded=True,
                            source_tree=source.tree)
    except InputError:  # with TX001/TX002 turned off: nothing more to say
        return []
    if context_for(source, settings).found:
        return []
    message = "no <transmission> in this file: nothing to check"
    return finish([_pipeline(display, 1, 1, "TX006", message)], source, settings)


def _lint_file(
    path: str, settings: Settings, stdin_name: str | None, fragment: bool = False,
    buffer: bytes | None = None,
) -> Findings:
    """:func:`lint_file`'s work; ``buffer``: the text to check for the file at ``path``."""
    display, data = read_bytes(path, stdin_name=stdin_name) if buffer is None else (path, buffer)
    try:
        tree = parse_bytes(data, display)
    except XMLSyntax as exc:
        bare = Source(path=display, data=data, tree=None)  # type: ignore[arg-type]
        failed = _pipeline(display, exc.line, exc.column, "TX001", exc.reason)
        return Findings(finish([failed], bare, settings))
    source = Source(path=display, data=data, tree=tree)
    late = _late_declaration(display, data)
    if path == "-" or settings.no_xacro or not needs_expansion(display, data, tree):
        checked = _checked(source, settings)
        return _carry(finish(late + checked, source, settings), checked)
    from txtool.io.xacro import XacroError, expand_xacro

    try:
        expanded = expand_xacro(path, display, settings.xacro, data=buffer)
    except XacroError as exc:
        checked = _checked(source, settings)
        failed = [] if fragment else [_xacro_failed(display, data, exc)]
        return _carry(finish([*late, *failed, *checked], source, settings), checked)
    full = Source(path=display, data=data, tree=expanded, expanded=True, source_tree=tree)
    checked = _checked(full, settings)
    return _carry(finish(late + checked, full, settings), checked)


def _xacro_failed(path: str, data: bytes, exc: XacroError) -> Problem:
    """TX002 where the expansion failed. An argument or package the command line lacks is an
    info that says how to give it: the file is not at fault, only the run did not expand it."""
    line, column = _xacro_position(data, exc.reason)
    if not exc.missing:
        return _pipeline(path, line, column, "TX002", f"xacro: {exc.reason}")
    message = f"not expanded, checked as written only: xacro: {exc.reason}"
    return replace(_pipeline(path, line, column, "TX002", message), loader_severity="info")


def _late_declaration(path: str, data: bytes) -> list[Problem]:
    """TX001 for an ``<?xml ...?>`` declaration after a comment (read anyway, see xmlio)."""
    head = scanned_form(data)[:4096].removeprefix(b"\xef\xbb\xbf")
    index = head.find(b"<?xml")
    if index <= 0 or not head[:index].strip():
        return []
    line = head.count(b"\n", 0, index) + 1
    column = index - (head.rfind(b"\n", 0, index) + 1) + 1
    reason = (
        "XML declaration not at the start of the document (it follows a comment): not "
        "well-formed, so xacro and other strict XML parsers reject the file"
    )
    return [_pipeline(path, line, column, "TX001", reason)]


def as_settings(config: Config | Settings | None) -> Settings:
    if isinstance(config, Settings):
        return config
    return resolve(config)


def context_for(source: Source, settings: Settings) -> LintContext:
    """The context the rules see (see the module documentation for the choice)."""
    options = settings.options
    stated = settings.stated
    enabled = settings.enabled
    if not source.expanded:
        literal = needs_expansion(source.path, source.data, source.tree)
        return LintContext(source, literal=literal, options=options, stated=stated,
                           enabled=enabled)
    expanded = LintContext(source, options=options, stated=stated, enabled=enabled)
    if expanded.found or source.source_tree is None:
        return expanded
    as_written = Source(path=source.path, data=source.data, tree=source.source_tree)
    literal = LintContext(as_written, literal=True, options=options, stated=stated,
                          enabled=enabled)
    return literal if literal.found else expanded


def _checked(source: Source, settings: Settings) -> Findings:
    """Read a document and run the rules on it; the readers the document was judged for go
    with the problems."""
    ctx = context_for(source, settings)
    found = Findings(run_rules(ctx, settings))
    if ctx.found:
        found.readers = record(source.path, ctx.readers)
    return found


def _carry(problems: list[Problem], checked: Findings) -> Findings:
    """``problems`` (``checked`` finished) with the readers ``checked`` was judged for."""
    found = Findings(problems)
    found.readers = checked.readers
    return found


def run_rules(ctx: LintContext, settings: Settings) -> list[Problem]:
    """The problems of every enabled rule, as the rules made them (:func:`finish` stamps them)."""
    problems: list[Problem] = []
    every, whole = _checks(settings.enabled)
    if not ctx.found:
        # Nearly every rule is about transmissions; a few are about what makes the loader
        # refuse the whole robot, transmissions or not (rule_helpers.whole_robot).
        for check in every:
            if getattr(check, "whole_robot", False):
                problems.extend(check(ctx))
        return problems
    # A document of canonical transmissions: the rules about one transmission at a time have
    # nothing to say (see rule_helpers.per_transmission); the others look at the whole document.
    for check in whole if len(whole) < len(every) and all_canonical(ctx) else every:
        problems.extend(check(ctx))
    ctx.release()
    return problems


Checks = list[Callable[[LintContext], Iterable[Problem]]]
_CHECKS: dict[frozenset[str], tuple[Checks, Checks]] = {}


def _checks(enabled: frozenset[str]) -> tuple[Checks, Checks]:
    """The check functions of the enabled rules run on a context, in code order: all of them,
    and those not marked :func:`~txtool.lint.rule_helpers.per_transmission`."""
    known = _CHECKS.get(enabled)
    if known is None:
        every = [
            rule.check for rule in all_rules().values()
            if rule.check is not None and rule.code in enabled and rule.code not in PIPELINE_CODES
        ]
        whole = [check for check in every if not getattr(check, "per_transmission", False)]
        known = _CHECKS[enabled] = (every, whole)
    return known


def finish(problems: list[Problem], source: Source, settings: Settings) -> list[Problem]:
    """Select, suppress, report unused suppressions, stamp, add end positions, sort."""
    enabled = settings.enabled
    kept = [p for p in problems if p.code in enabled] if problems else []
    suppressions = parse_suppressions(source.data)
    if suppressions:
        kept = [p for p in kept if not suppressions.suppressed(p)]
        kept += _invalid_suppressions(suppressions, source.path, settings)
        if "TX003" in settings.enabled:
            for directive, code in suppressions.unused(settings.enabled):
                what = f"'{directive.kind} {code}'" if code else f"'{directive.kind}'"
                message = f"suppression {what} silences nothing: remove it"
                kept.append(
                    _pipeline(source.path, directive.line, directive.column, "TX003", message)
                )
    if not kept:
        return kept
    rules = all_rules()
    lines = _Lines(text_lines(source.data))
    return sorted(_stamped(p, rules[p.code], settings, lines) for p in kept)


def _invalid_suppressions(
    suppressions: Suppressions, path: str, settings: Settings
) -> list[Problem]:
    """TX005: misspelt directives, tokens that are not codes, and codes of no rule."""
    if "TX005" not in settings.enabled:
        return []
    rules = all_rules()
    found = [_pipeline(path, bad.line, bad.column, "TX005", bad.reason)
             for bad in suppressions.invalid]
    for directive in suppressions.directives:
        for code in sorted(directive.codes - rules.keys()):
            message = f"suppression names '{code}', which is no rule: see `txtool rules`"
            found.append(_pipeline(path, directive.line, directive.column, "TX005", message))
    return found


def _stamped(problem: Problem, rule: Rule, settings: Settings, lines: _Lines) -> Problem:
    """The problem with its registry name, configured severity, fixability and end."""
    return Problem(
        problem.path,
        problem.line,
        problem.column,
        problem.code,
        problem.message,
        end_line=problem.line,
        end_column=_end_column(problem, lines),
        severity=settings.severity.get(rule.code, problem.loader_severity or rule.severity),
        name=rule.name,
        fixable=rule.fixable and problem.fixable is not False,
        related=problem.related,
        refuses_whole=problem.refuses_whole,
    )


def _pipeline(path: str, line: int, column: int, code: str, message: str) -> Problem:
    return Problem(path, max(line, 1), max(column, 1), code, message)


class _Lines:
    """The document's lines, and where the text of each ends (worked out once per line)."""

    __slots__ = ("lines", "_text_ends")

    def __init__(self, lines: Lines) -> None:
        self.lines = lines
        self._text_ends: dict[int, int] = {}

    def text_end(self, line: int) -> int:
        """Characters up to the last one that is not white space on ``line`` (1-based)."""
        end = self._text_ends.get(line)
        if end is None:
            end = self._text_ends[line] = len(self.lines[line - 1].rstrip())
        return end


def _end_column(problem: Problem, lines: _Lines) -> int:
    """Exclusive end: the end of the tag (or text) starting at the position, on its line.

    Read in place, never by copying the rest of the line: a document written on one line
    holds every problem on that line."""
    if not 1 <= problem.line <= len(lines.lines):
        return problem.column + 1
    start = problem.column - 1
    first, last = lines.lines.span(problem.line - 1)
    match = _TAG_END.match(lines.lines.text, first + start, last)
    if match:
        return match.end() - first + 1
    end = lines.text_end(problem.line)
    return end + 1 if end > start else problem.column + 1


def _xacro_position(data: bytes, reason: str) -> tuple[int, int]:
    """Where the missing argument, package or property is used, or the include of the file
    that failed, else 1:1."""
    include = _include_position(data, reason)
    if include is not None:
        return include
    quoted = re.search(r"'([^']+)'", reason)
    if not quoted:
        return 1, 1
    name = re.escape(quoted.group(1))
    if reason.startswith("missing argument"):  # not "in": the reason may name folders
        pattern = rf"\$\(arg\s+{name}\s*\)"
    elif reason.startswith("package"):
        pattern = rf"\$\(find\s+{name}\s*\)"
    else:
        pattern = rf"\$\{{[^}}]*\b{name}\b"
    return _first_match(data, pattern) or (1, 1)


def _include_position(data: bytes, reason: str) -> tuple[int, int] | None:
    """The ``<xacro:include>`` of a file the reason names (missing, or refused when read)."""
    named = re.findall(r"'([^']+)'", reason) + re.findall(r"(\S+?):\d+:", reason)
    for path in named:
        base = re.escape(path.replace("\\", "/").rsplit("/", 1)[-1])
        if not base:
            continue
        found = _first_match(
            data, rf"<(?:[\w.-]+:)?include\b[^>]*filename\s*=\s*[\"'][^\"']*{base}[\"']"
        )
        if found is not None:
            return found
    return None


def _first_match(data: bytes, pattern: str) -> tuple[int, int] | None:
    text = document_text(data)
    match = re.search(pattern, text)
    if not match:
        return None
    line = text.count("\n", 0, match.start()) + 1
    column = match.start() - (text.rfind("\n", 0, match.start()) + 1) + 1
    return line, column
