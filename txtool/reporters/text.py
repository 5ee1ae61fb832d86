"""``path:line:col: severity CODE name: message`` lines and a summary line.

Plain text unless ``color``; then rich styles it (imported only in that case). Given a
terminal's ``width``, a finding longer than it goes on over indented lines, broken between
words; else (a pipe, a file) each finding is one line, for tools that read them.
"""

from __future__ import annotations

import textwrap
from collections.abc import Sequence

from txtool.io.printable import printable
from txtool.lint.problem import Problem
from txtool.reporters import Summary

INDENT = "    "  # before the lines a finding goes on over
MIN_WIDTH = 40  # below this a terminal is too narrow to wrap for: one finding a line
STYLES = {"error": "bold red", "warning": "yellow", "info": "cyan"}
FIXABLE = "[*]"  # after the code of a finding ``validate --fix`` fixes, as ruff marks them
FIX_HINT = "`txtool validate --fix`"


def line_of(problem: Problem) -> str:
    """One finding on one line: control characters in its path or message are escaped."""
    return (
        f"{printable(problem.path)}:{problem.line}:{problem.column}: {problem.severity} "
        f"{problem.code}{_mark(problem)} {problem.name}: "
        f"{printable(problem.message + problem.chain())}"
    )


def _mark(problem: Problem) -> str:
    return f" {FIXABLE}" if problem.fixable else ""


def summary_line(summary: Summary) -> str:
    files = _plural(summary.files, "file")
    counts = [
        _plural(count, noun)
        for count, noun in (
            (summary.errors, "error"), (summary.warnings, "warning"), (summary.infos, "info"),
        )
        if count
    ]
    unreadable = _plural(summary.unreadable, "file")
    if not counts and summary.unreadable:  # never "No problems" beside a failure (exit 2)
        read = f"no findings in the {files} read" if summary.files else "nothing was checked"
        return f"{unreadable} could not be read; {read}."
    line = f"Found {', '.join(counts)} in {files}" if counts else f"No problems in {files}"
    if summary.not_expanded:
        line += f"; {_plural(summary.not_expanded, 'file')} not expanded (TX002)"
    if summary.unreadable:
        line += f"; {unreadable} could not be read"
    if summary.fixable:
        line += f"; {summary.fixable} fixable with {FIX_HINT}"
    return line + "."


def _plural(count: int, noun: str) -> str:
    return f"{count} {noun}" + ("" if count == 1 else "s")


def render(problems: Sequence[Problem], summary: Summary, *, color: bool = False,
           width: int | None = None) -> str:
    if not color:
        lines = [_fitted(line_of(p), width) for p in problems]
        return "\n".join([*lines, summary_line(summary)]) + "\n"
    return _render_rich(problems, summary, width)


def render_quiet(problems: Sequence[Problem], *, color: bool = False,
                 width: int | None = None) -> str:
    """The findings alone, no summary line (``validate -q``)."""
    if not problems:
        return ""
    if not color:
        return "".join(_fitted(line_of(p), width) + "\n" for p in problems)
    return _render_rich(problems, None, width)


def _fitted(line: str, width: int | None) -> str:
    """``line`` over as many lines of ``width`` as it needs (paths and names never broken)."""
    if width is None or width < MIN_WIDTH or len(line) <= width:
        return line
    return "\n".join(textwrap.wrap(line, width, subsequent_indent=INDENT,
                                   break_long_words=False, break_on_hyphens=False))


def statistics(problems: Sequence[Problem], summary: Summary) -> str:
    """``validate --statistics``: one row per rule, most frequent first, ``[*]`` where some of
    its findings are fixable, then the summary."""
    counts: dict[tuple[str, str, str], int] = {}
    fixable = {p.code for p in problems if p.fixable}
    for p in problems:
        key = (p.code, p.name, p.severity)
        counts[key] = counts.get(key, 0) + 1
    rows = sorted(counts.items(), key=lambda item: (-item[1], item[0][0]))
    width = max((len(str(n)) for _, n in rows), default=1)
    blank = " " * len(FIXABLE)
    lines = [f"{n:>{width}}  {code}  {severity:<7}  {FIXABLE if code in fixable else blank} "
             f"{name}" for (code, name, severity), n in rows]
    return "\n".join([*lines, summary_line(summary)]) + "\n"


def _render_rich(problems: Sequence[Problem], summary: Summary | None,
                 width: int | None = None) -> str:
    import io

    from rich.console import Console
    from rich.text import Text

    out = io.StringIO()
    console = Console(
        file=out, force_terminal=True, color_system="standard", width=10_000,
        highlight=False, soft_wrap=True,
    )
    for p in problems:
        head = Text.assemble(
            (f"{printable(p.path)}:{p.line}:{p.column}:", "bold"),
            " ",
            (p.severity, STYLES.get(p.severity, "")),
            " ",
            (p.code, "bold"),
            (_mark(p), "bold"),
            " ",
            (p.name, "dim"),
            ":",
        )
        # The plain line wrapped, its head styled: the head fits on the first line unless
        # a path alone is wider than the terminal (then it is left unstyled).
        first, *rest = _fitted(line_of(p), width).split("\n")
        if first.startswith(head.plain):
            console.print(Text.assemble(head, first[len(head.plain):]))
        else:
            console.print(Text(first))
        for line in rest:
            console.print(Text(line))
    if summary is not None:
        failed = summary.errors or summary.warnings or summary.infos or summary.unreadable
        console.print(Text(summary_line(summary), style="bold" if failed else "green"))
    return out.getvalue()
