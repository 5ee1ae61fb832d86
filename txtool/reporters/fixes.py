"""What ``txtool validate --fix`` would change in a file, as the spans a report can show.

A file and its fixed text (what ``txtool migrate`` makes of it) are compared line by line; each
run of lines that differs is one :class:`Edit`: the span of the original it replaces, in the
positions SARIF counts (1-based lines, columns and offsets in Unicode code points, a line ending
at ``\\n``, ``\\r\\n`` or ``\\r``), and the text put in its place.
"""

from __future__ import annotations

import difflib
import re
from collections.abc import Sequence
from typing import NamedTuple

_LINE = re.compile(r"[^\r\n]*(?:\r\n|\r|\n)|[^\r\n]+\Z")


class Edit(NamedTuple):
    start: tuple[int, int]  # (line, column) of the first character replaced
    end: tuple[int, int]  # (line, column) just past the last one
    offset: int  # the same span in characters from the start of the file
    length: int
    text: str  # what takes its place
    lines: tuple[int, int]  # the original lines it touches (a pure insertion: those around it)

    def touches(self, first: int, last: int) -> bool:
        """Whether the edit touches any of the lines ``first`` to ``last``."""
        return self.lines[0] <= last and first <= self.lines[1]


def lines_of(text: str) -> list[str]:
    """The lines of ``text``, each with its line ending."""
    return _LINE.findall(text)


def edits_between(before: str, after: str) -> tuple[Edit, ...]:
    """The runs of lines in which ``after`` differs from ``before``, in order."""
    old, new = lines_of(before), lines_of(after)
    starts = [0]
    for line in old:
        starts.append(starts[-1] + len(line))
    matcher = difflib.SequenceMatcher(None, old, new, autojunk=False)
    edits = []
    for tag, i1, i2, j1, j2 in matcher.get_opcodes():
        if tag == "equal":
            continue
        touched = (i1 + 1, i2) if i2 > i1 else (max(i1, 1), i1 + 1)
        edits.append(Edit(_position(old, i1), _position(old, i2), starts[i1],
                          starts[i2] - starts[i1], "".join(new[j1:j2]), touched))
    return tuple(edits)


def _position(lines: Sequence[str], index: int) -> tuple[int, int]:
    """Where line ``index`` (0-based) starts; past the last line, the end of the text."""
    if index < len(lines) or not lines:
        return index + 1, 1
    last = lines[-1]
    if last.endswith(("\n", "\r")):
        return len(lines) + 1, 1
    return len(lines), len(last) + 1


def edits_for(edits: Sequence[Edit], first: int, last: int) -> tuple[Edit, ...]:
    """The edits touching lines ``first`` to ``last`` (a finding's); all of them when none
    does (a fix may change a line other than the one its finding points at)."""
    near = tuple(edit for edit in edits if edit.touches(first, last))
    return near or tuple(edits)
