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
from dataclasses import dataclass, field

from txtool.lint.problem import Problem

_MARK = b"txtool:"
_DIRECTIVE = re.compile(
    rb"<!--\s*txtool:\s*(disable-next-line|disable-line|disable-file)\b(.*?)-->", re.DOTALL
)
_CODE = re.compile(r"\bTX\d{3}\b", re.IGNORECASE)


@dataclass
class Directive:
    kind: str
    line: int
    column: int
    target: int | None  # the line silenced; None for the whole file
    codes: frozenset[str]  # empty: every code
    used: set[str] = field(default_factory=set)

    def covers(self, problem: Problem) -> bool:
        if self.target is not None and problem.line != self.target:
            return False
        return not self.codes or problem.code in self.codes


@dataclass
class Suppressions:
    directives: list[Directive] = field(default_factory=list)

    def __bool__(self) -> bool:
        return bool(self.directives)

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
    if _MARK not in data:
        return Suppressions()
    directives = []
    for match in _DIRECTIVE.finditer(data):
        start_line = data.count(b"\n", 0, match.start()) + 1
        end_line = start_line + match.group(0).count(b"\n")
        column = match.start() - (data.rfind(b"\n", 0, match.start()) + 1) + 1
        kind = match.group(1).decode()
        target = {"disable-next-line": end_line + 1, "disable-line": start_line}.get(kind)
        reason_free = match.group(2).decode("utf-8", "replace").split(";", 1)[0]
        codes = frozenset(code.upper() for code in _CODE.findall(reason_free))
        directives.append(Directive(kind, start_line, column, target, codes))
    return Suppressions(directives)
