"""Inline suppressions written as XML comments.

``<!-- txtool: disable-next-line TX105 -->`` silences the listed codes on the next line,
``<!-- txtool: disable-line TX105 -->`` on the comment's own line, and
``<!-- txtool: disable-file TX300 TX301 -->`` in the whole file. Codes are separated by
spaces or commas; without codes every rule is silenced. Text after ``;`` is a free reason
(``<!-- txtool: disable-line TX106; zero on purpose -->``).
"""

from __future__ import annotations

import re
from collections.abc import Iterator
from typing import NamedTuple

from txtool.lint.problem import Problem
from txtool.lint.text import scanned_form

_MARK = b"txtool:"
KINDS = ("disable-next-line", "disable-line", "disable-file")
_DIRECTIVE = re.compile(rb"<!--\s*txtool:\s*([\w-]*)(.*?)-->", re.DOTALL)
_CODE = re.compile(r"^TX\d{3}$", re.IGNORECASE)


class Directive:
    """One ``txtool: disable-...`` comment; ``used`` collects the codes it silenced."""

    __slots__ = ("kind", "line", "column", "target", "codes", "used")

    def __init__(self, kind: str, line: int, column: int, target: int | None,
                 codes: frozenset[str]) -> None:
        self.kind = kind
        self.line = line
        self.column = column
        self.target = target  # the line silenced; None for the whole file
        self.codes = codes  # empty: every code
        self.used: set[str] = set()

    def covers(self, problem: Problem) -> bool:
        if self.target is not None and problem.line != self.target:
            return False
        return not self.codes or problem.code in self.codes


class Invalid(NamedTuple):
    """A ``txtool:`` comment that silences nothing as written: a misspelt directive or a
    token that is not a rule code (``reason`` says which)."""

    line: int
    column: int
    reason: str


class Suppressions:
    """The directives of a document, and the comments that are none."""

    __slots__ = ("directives", "invalid")

    def __init__(self) -> None:
        self.directives: list[Directive] = []
        self.invalid: list[Invalid] = []

    def __bool__(self) -> bool:
        return bool(self.directives or self.invalid)

    def suppressed(self, problem: Problem) -> bool:
        """Whether a directive silences ``problem`` (and remember that it was used)."""
        hit = False
        for directive in self.directives:
            if directive.covers(problem):
                directive.used.add(problem.code)
                hit = True
        return hit

    def unused(self, enabled: frozenset[str]) -> Iterator[tuple[Directive, str]]:
        """``(directive, code)`` for each enabled code a directive lists but never silenced."""
        for directive in self.directives:
            if not directive.codes:
                if not directive.used:
                    yield directive, ""
                continue
            for code in sorted(directive.codes - directive.used):
                if code in enabled:
                    yield directive, code


def parse(data: bytes) -> Suppressions:
    """The suppression comments of a document (cheap when there are none)."""
    data = scanned_form(data)  # UTF-8 with LF line ends, lines where libxml2 counts them
    if _MARK not in data:
        return Suppressions()
    found = Suppressions()
    for match in _DIRECTIVE.finditer(data):
        start_line = data.count(b"\n", 0, match.start()) + 1
        end_line = start_line + match.group(0).count(b"\n")
        column = match.start() - (data.rfind(b"\n", 0, match.start()) + 1) + 1
        kind = match.group(1).decode("utf-8", "replace")
        if kind not in KINDS:
            found.invalid.append(Invalid(start_line, column, _misspelt(kind)))
            continue
        target = {"disable-next-line": end_line + 1, "disable-line": start_line}.get(kind)
        reason_free = match.group(2).decode("utf-8", "replace").split(";", 1)[0]
        tokens = [t for t in re.split(r"[\s,]+", reason_free) if t]
        bad = [t for t in tokens if not _CODE.match(t)]
        if bad:
            found.invalid.append(Invalid(
                start_line, column, f"'{bad[0]}' is not a rule code (write TXnnn; a reason goes "
                "after ';')",
            ))
        codes = frozenset(t.upper() for t in tokens if _CODE.match(t))
        found.directives.append(Directive(kind, start_line, column, target, codes))
    return found


def _misspelt(kind: str) -> str:
    import difflib

    near = difflib.get_close_matches(kind, KINDS, n=1)
    hint = f"did you mean '{near[0]}'?" if near else "use " + ", ".join(KINDS)
    return f"unknown directive 'txtool: {kind}': {hint}"
