"""Rich tables for ``show`` and ``roundtrip`` (pure functions of the data they print)."""

from __future__ import annotations

from collections.abc import Mapping, Sequence

from rich.markup import escape
from rich.table import Table

from txtool.io.printable import printable
from txtool.model.core import Number, Transmission


def safe(text: str) -> str:
    """A name or path from a file, as a table cell or title: no control characters, and
    brackets shown rather than read as rich markup (``[/]`` would stop the table)."""
    return escape(printable(text))


def _number(number: Number | None) -> str:
    if number is None:
        return "-"
    return number.text.strip() if number.text and number.text.strip() else "(empty)"


def transmissions_table(transmissions: Sequence[Transmission], title: str,
                        verdicts: Mapping[str, Sequence[str]] | None = None) -> Table:
    """One row per joint and actuator, grouped under their transmission; with ``verdicts``
    (what validate says of a transmission, by name), a ``validate`` column holding them
    (``✗ TX205`` for an error, ``! TX300`` for a warning), when one has any."""
    verdicts = verdicts or {}
    table = Table(title=safe(title), title_justify="left")
    shown = any(t.name in verdicts for t in transmissions)
    for column in ("transmission", "dialect", "type", "member", "role", "reduction", "offset",
                   "interfaces", *(["validate"] if shown else [])):
        table.add_column(column)
    for t in transmissions:
        line = f":{t.location.line}" if t.location else ""
        head = [safe(f"{t.name}{line}"), t.dialect, safe(_short(t.type))]
        said = [_mark(verdict) for verdict in verdicts.get(t.name, ())]
        members = [("joint", j) for j in t.joints] + [("actuator", a) for a in t.actuators]
        for index, (noun, member) in enumerate(members or [("-", None)]):
            cells = head if index == 0 else ["", "", ""]
            tail = ([", ".join(said) if index == 0 else ""] if shown else [])
            if member is None:
                table.add_row(*cells, "-", "", "", "", "", *tail, end_section=True)
                continue
            table.add_row(
                *cells,
                safe(f"{noun} {member.name}"),
                safe(member.role or ""),
                safe(_number(member.mechanical_reduction)),
                safe(_number(member.offset)) if noun == "joint" else "",
                safe(", ".join(_short(i) for i in member.interfaces)),
                *tail,
                end_section=index == len(members) - 1,
            )
    return table


def _mark(verdict: str) -> str:
    """``✗ TX205`` of ``error TX205: ...``, ``! TX300`` of a warning."""
    severity, code = verdict.split(":", 1)[0].split(" ", 1)
    return f"{'✗' if severity == 'error' else '!'} {code}"


def _short(text: str) -> str:
    for prefix in ("transmission_interface/", "hardware_interface/"):
        if text.startswith(prefix):
            return text[len(prefix):]
    return text or "(none)"


def limits_table(rows: Sequence[tuple[str, str, object]]) -> Table:
    """Rows of (transmission, actuator, ActuatorLimit)."""
    table = Table(title="Actuator-space limits", title_justify="left")
    for column in ("transmission", "actuator", "position", "velocity", "effort"):
        table.add_column(column)
    for transmission, actuator, limit in rows:
        position = getattr(limit, "position", None)
        table.add_row(
            safe(transmission),
            safe(actuator),
            escape(f"[{position[0]:.6g}, {position[1]:.6g}]") if position else "-",
            _maybe(getattr(limit, "velocity", None)),
            _maybe(getattr(limit, "effort", None)),
        )
    return table


def _maybe(value: float | None) -> str:
    return "-" if value is None else f"{value:.6g}"


def console(*, stderr: bool = False):
    """A rich console as wide as the terminal, or wide enough for tables when output goes to
    a file or a pipe (see :func:`txtool.views.plain.output_size`)."""
    import sys

    from rich.console import Console

    from txtool.views.plain import output_size

    stream = sys.stderr if stderr else sys.stdout
    width, height = output_size(stream)
    return Console(file=stream, width=width, height=height, highlight=False, emoji=False)


MAX_STRETCH = 400  # columns a table in a pipe may take, at most (a title is padded to them)


def fit(out, *tables: Table) -> None:
    """In a pipe or a file (``COLUMNS`` unset), widen the console ``out`` so that ``tables``
    are laid out whole rather than squeezed into 140 columns, up to :data:`MAX_STRETCH`."""
    from txtool.views.plain import stretchable

    if not stretchable(out.file):
        return
    options = out.options.update_width(MAX_STRETCH)
    needed = max(out.measure(table, options=options).maximum for table in tables)
    if needed > out.width:
        out.width = needed


def print_table(out, table: Table) -> None:
    """``table`` on the console ``out``: whole in a pipe (see :func:`fit`); on a terminal
    narrower than the table, folded to one record per row (see :func:`folded`), where rich
    would cut every cell to a few letters."""
    fit(out, table)
    options = out.options.update_width(MAX_STRETCH)
    if out.measure(table, options=options).maximum > out.width:
        out.print(folded(table))
    else:
        out.print(table)


def folded(table: Table):
    """``table`` laid out vertically: its title, then each row as ``column  value`` lines
    (empty cells left out), rows apart by a blank line, sections by a rule."""
    from rich.console import Group
    from rich.rule import Rule

    columns = [(str(column.header), list(column.cells)) for column in table.columns]
    width = max((len(header) for header, _ in columns), default=0)
    parts: list = [table.title, ""] if table.title else []
    for index, row in enumerate(table.rows):
        record = Table.grid(padding=(0, 2))
        record.add_column(style="bold", no_wrap=True, min_width=width)
        record.add_column(overflow="fold")
        for header, cells in columns:
            value = cells[index] if index < len(cells) else ""
            if value != "":
                record.add_row(header, value)
        parts.append(record)
        last = index == len(table.rows) - 1
        if not last:
            parts.append(Rule(style="dim") if row.end_section else "")
    return Group(*parts)
