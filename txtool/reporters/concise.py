"""``path:line:col: CODE message`` lines of about 100 characters, and the summary line.

The message is its first clause, what is wrong (the rest says what the loader does and how
to fix it: ``txtool rules CODE`` explains the rule); a clause longer than the line allows is
cut at a word, with ``…``.
"""

from __future__ import annotations

import re
from collections.abc import Sequence

from txtool.io.printable import printable
from txtool.lint.problem import Problem
from txtool.reporters import Summary
from txtool.reporters.text import FIXABLE, summary_line

WIDTH = 100  # a line's length aimed at; a long path alone may pass it
MIN_MESSAGE = 96  # characters of message kept however long the path (a headline fits)
MIN_CLAUSE = 24  # a first clause shorter than this ("xacro") says too little alone
_SEPARATORS = (": ", "; ")


def line_of(problem: Problem) -> str:
    mark = f" {FIXABLE}" if problem.fixable else ""
    head = f"{printable(problem.path)}:{problem.line}:{problem.column}: {problem.code}{mark} "
    room = max(WIDTH - len(head), MIN_MESSAGE)
    return head + shorten(headline(printable(problem.message)), room)


def headline(message: str) -> str:
    """The message up to its first ``: `` or ``; `` outside parentheses and double quotes
    (once it has said enough: more than a name), else the whole message."""
    depth, quoted = 0, False
    for index, char in enumerate(message):
        if char == '"':
            quoted = not quoted
        elif char in "([<" and not quoted:
            depth += 1
        elif char in ")]>" and not quoted and depth:
            depth -= 1
        elif (not depth and not quoted and index >= MIN_CLAUSE
              and message.startswith(_SEPARATORS, index)
              and not _LABEL.fullmatch(message, 0, index)):
            return message[:index]
    return message


# A clause that only names what the finding is about ("transmission 't'"): the next one says.
_LABEL = re.compile(r"(?:[\w-]+ )+'[^']*'")


def shorten(text: str, room: int) -> str:
    """``text`` whole if it fits in ``room`` characters, else cut at a word and marked ``…``."""
    if len(text) <= room:
        return text
    cut = text.rfind(" ", 0, room)
    return text[: cut if cut > room // 2 else room - 1].rstrip(" ,;:") + "…"


def render(problems: Sequence[Problem], summary: Summary, *, color: bool = False) -> str:
    return "".join(line_of(p) + "\n" for p in problems) + summary_line(summary) + "\n"
