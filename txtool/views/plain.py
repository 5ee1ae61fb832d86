"""What rich would print for a simple table and lines, written without loading rich.

Loading rich's console and laying out a table of 70 rows costs more than the rest of
``roundtrip`` together. Where the output is plain (not a terminal: no colour, the fixed width
:func:`txtool.views.render.console` gives a pipe or a file) and every text is plain ASCII that
fits that width, the layout is simple: no wrapping, each column as wide as its widest cell.
:func:`plain_table` writes that text, the same characters as rich's, and answers None for
anything else (colour, a terminal, a cell rich would wrap, read as markup or as an emoji code),
which the caller then prints through rich. A property test holds the two to the same text.
"""

from __future__ import annotations

import builtins
import os
import re
from collections.abc import Sequence
from typing import Any, TextIO

PIPE_WIDTH = 140  # txtool.views.render.console's width when output is not a terminal
_PLAIN = re.compile(r"[ -Z^-~✓✗→]*")  # printable ASCII but [ \ ], and the marks we print
_EMOJI_CODE = re.compile(r":\S*?:")


def output_size(stream: TextIO) -> tuple[int, int]:
    """Columns and lines for rich's tables on ``stream``: ``COLUMNS`` when set; else a
    terminal's own size, or :data:`PIPE_WIDTH` for a pipe or a file (wide enough that the
    tables do not wrap). Given to rich always, so that ``TERM=dumb`` (``--color never``) keeps
    the terminal's width rather than rich's 80 columns."""
    lines = 25
    try:
        size = os.get_terminal_size(stream.fileno()) if stream.isatty() else None
    except (AttributeError, ValueError, OSError):
        size = None
    columns = size.columns if size is not None and size.columns > 0 else PIPE_WIDTH
    if size is not None and size.lines > 0:
        lines = size.lines
    given = os.environ.get("COLUMNS", "")
    if given.isdigit() and int(given) > 0:
        columns = int(given)
    return columns, lines


def plain_output(stream: TextIO) -> bool:
    """Whether rich would write to ``stream`` at the pipe width without colour or styles: not
    a terminal (``isatty``), and no variable of rich's says it is one."""
    try:
        if stream.isatty():
            return False
    except (AttributeError, ValueError):
        return False
    if "get_ipython" in vars(builtins):  # rich's Jupyter detection sets its own width
        return False
    if os.environ.get("TTY_COMPATIBLE", "") == "1":
        return False
    return os.environ.get("FORCE_COLOR") in (None, "") or os.environ.get("TTY_COMPATIBLE") == "0"


def stretchable(stream: TextIO) -> bool:
    """Whether tables on ``stream`` may be as wide as they need: a pipe or a file (no terminal
    to fit), ``COLUMNS`` unset."""
    try:
        terminal = stream.isatty()
    except (AttributeError, ValueError):
        terminal = False
    return not terminal and not os.environ.get("COLUMNS", "").isdigit()


def _pipe_width() -> int:
    given = os.environ.get("COLUMNS", "")
    return int(given) if given.isdigit() and int(given) > 0 else PIPE_WIDTH


def _plain(text: str) -> bool:
    return _PLAIN.fullmatch(text) is not None and not _EMOJI_CODE.search(text)


def plain_table(
    title: str,
    columns: Sequence[str],
    rows: Sequence[Sequence[str]],
    lines: Sequence[str] = (),
    width: int | None = None,
) -> str | None:
    """rich's ``Table(title=title, title_justify="left")`` of these columns and rows, then
    ``lines``, as printed at ``width`` without colour; None unless every text is plain and the
    table and each line fit the width (by default a pipe's, see :func:`output_size`). Texts
    are as printed (no markup)."""
    if width is None:
        width = _pipe_width()
    texts = {title, *columns, *lines, *(cell for row in rows for cell in row)}
    if not all(_plain(text) for text in texts) or any(len(line) > width for line in lines):
        return None
    widths = [max([len(name)] + [len(row[i]) for row in rows]) for i, name in enumerate(columns)]
    table_width = sum(widths) + 3 * len(widths) + 1
    if not rows or table_width > width or len(title) > table_width or not title.strip():
        return None
    out = [title.ljust(table_width)]
    out.append("┏" + "┳".join("━" * (w + 2) for w in widths) + "┓")
    out.append(_row("┃", columns, widths))
    out.append("┡" + "╇".join("━" * (w + 2) for w in widths) + "┩")
    tails: dict[tuple[str, ...], str] = {}  # the cells after the first, alike in many rows
    for row in rows:
        tail = tuple(row[1:])
        text = tails.get(tail)
        if text is None:
            text = tails[tail] = "".join(
                f" {cell.ljust(width)} │" for cell, width in zip(tail, widths[1:], strict=True))
        out.append(f"│ {row[0].ljust(widths[0])} │{text}")
    out.append("└" + "┴".join("─" * (w + 2) for w in widths) + "┘")
    out.extend(lines)
    return "\n".join(out) + "\n"


def _row(edge: str, cells: Sequence[str], widths: Sequence[int]) -> str:
    padded = (f" {cell.ljust(width)} " for cell, width in zip(cells, widths, strict=True))
    return edge + edge.join(padded) + edge


def roundtrip_text(report: Any) -> str | None:
    """``roundtrip``'s table and lines (a :class:`txtool.transform.roundtrip.RoundTripReport`)
    as :func:`plain_table` writes them, or None where rich must."""
    from txtool.io.printable import printable
    from txtool.views.tables import FIELDS

    rows = []
    lines = []
    rests: dict[tuple, list[str]] = {}  # the cells after the name, alike in many rows
    for row in report.rows:
        cycle = " → ".join(row.cycle)
        key = (row.cycle, id(row.fields), row.equivalent)  # rows of repeats share fields
        rest = rests.get(key)
        if rest is None:
            rest = rests[key] = [cycle, *("✓" if row.fields[f] else "✗" for f in FIELDS),
                                 row.equivalent.split(":", 1)[0]]
        rows.append([printable(row.transmission), *rest])
        if row.details or row.equivalent != "yes":
            reason = row.equivalent.split(": ", 1)[1:] if row.equivalent != "yes" else []
            lines.extend(printable(f"{row.transmission} ({cycle}): {detail}")
                         for detail in (*row.details, *reason))
    lines.extend(printable(f"passed through untouched: {skipped}") for skipped in report.skipped)
    lines.append(report.summary)
    columns = ("transmission", "cycle", *FIELDS, "equivalent")
    return plain_table(printable(f"{report.path}: round trips"), columns, rows, lines)
