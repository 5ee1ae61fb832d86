"""Inline suppressions written as XML comments.

``<!-- txtool: disable-next-line TX105 -->`` silences the listed codes on the next line,
``<!-- txtool: disable-line TX105 -->`` on the comment's own line, and
``<!-- txtool: disable-file TX300 TX301 -->`` in the whole file. Codes are separated by
spaces or commas; without codes every rule is silenced. Text after ``;`` is a free reason
(``<!-- txtool: disable-line TX106; zero on purpose -->``).
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Iterator
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


class Invalid(NamedTuple):
    """A ``txtool:`` comment that silences nothing as written: a misspelt directive or a
    token that is not a rule code (``reason`` says which)."""

    line: int
    column: int
    reason: str


class Suppressions:
    """The directives of a document, and the comments that are none.

    Matching looks a problem's line and code up (a document may hold thousands of directives
    on one line, and thousands of problems): which codes each line silences is worked out once,
    and what was silenced is kept as (line, code) pairs, read back into each directive's
    ``used`` when :meth:`unused` asks.
    """

    __slots__ = ("directives", "invalid", "_silenced", "_hits")

    def __init__(self) -> None:
        self.directives: list[Directive] = []
        self.invalid: list[Invalid] = []
        # line (None: the whole file) -> the codes silenced there ("" for every code)
        self._silenced: dict[int | None, set[str]] | None = None
        self._hits: set[tuple[int | None, str]] = set()

    def __bool__(self) -> bool:
        return bool(self.directives or self.invalid)

    def suppressed(self, problem: Problem) -> bool:
        """Whether a directive silences ``problem`` (and remember that it was used)."""
        hit = False
        for line in (None, problem.line):
            if self._covers(line, problem.code):
                self._hits.add((line, problem.code))
                hit = True
        return hit

    def silences(self, code: str, lines: Iterable[int]) -> bool:
        """Whether a directive covers ``code`` on any of ``lines`` (nothing is marked used)."""
        return self._covers(None, code) or any(self._covers(line, code) for line in lines)

    def _covers(self, line: int | None, code: str) -> bool:
        if self._silenced is None:
            self._silenced = {}
            for directive in self.directives:
                codes = self._silenced.setdefault(directive.target, set())
                codes.update(directive.codes or ("",))
        codes = self._silenced.get(line)
        return codes is not None and ("" in codes or code in codes)

    def unused(self, enabled: frozenset[str]) -> Iterator[tuple[Directive, str]]:
        """``(directive, code)`` for each enabled code a directive lists but never silenced."""
        hit_lines = {line for line, _ in self._hits}
        for directive in self.directives:
            if not directive.codes:
                if directive.target not in hit_lines:
                    yield directive, ""
                continue
            for code in sorted(directive.codes):
                if (directive.target, code) in self._hits:
                    directive.used.add(code)
                elif code in enabled:
                    yield directive, code


def parse(data: bytes) -> Suppressions:
    """The suppression comments of a document (cheap when there are none).

    One pass: each comment is matched within its own bounds and lines are counted from the
    previous comment on, so a document of many comments on one line (or none closed) costs
    time in proportion to its size."""
    data = scanned_form(data)  # UTF-8 with LF line ends, lines where libxml2 counts them
    if _MARK not in data:
        return Suppressions()
    found = Suppressions()
    place = _Lines(data)
    for match in _comments(data):
        start_line, column = place.of(match.start())
        end_line = start_line + match.group(0).count(b"\n")
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


def _comments(data: bytes) -> Iterator[re.Match[bytes]]:
    """:data:`_DIRECTIVE` matches in order, each searched for only up to the end of its
    comment (a regular-expression search from each ``<!--`` would read to the end of an
    unclosed one every time)."""
    start = data.find(b"<!--")
    end = -1
    while start >= 0:
        if end < start + 4:
            end = data.find(b"-->", start + 4)
            if end < 0:
                return
        match = _DIRECTIVE.match(data, start, end + 3)
        if match is not None:
            yield match
            start = data.find(b"<!--", match.end())
        else:
            start = data.find(b"<!--", start + 4)


class _Lines:
    """Line and column (1-based) of increasing offsets, counted from the offset before."""

    __slots__ = ("data", "offset", "line", "line_start")

    def __init__(self, data: bytes) -> None:
        self.data = data
        self.offset = self.line_start = 0
        self.line = 1

    def of(self, offset: int) -> tuple[int, int]:
        newlines = self.data.count(b"\n", self.offset, offset)
        if newlines:
            self.line += newlines
            self.line_start = self.data.rfind(b"\n", self.offset, offset) + 1
        self.offset = offset
        return self.line, offset - self.line_start + 1


def _misspelt(kind: str) -> str:
    import difflib

    near = difflib.get_close_matches(kind, KINDS, n=1)
    hint = f"did you mean '{near[0]}'?" if near else "use " + ", ".join(KINDS)
    return f"unknown directive 'txtool: {kind}': {hint}"
