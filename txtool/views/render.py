"""Rich tables for ``show`` and ``roundtrip`` (pure functions of the data they print)."""

from __future__ import annotations

from collections.abc import Sequence

from rich.table import Table

from txtool.model.core import Number, Transmission


def _number(number: Number | None) -> str:
    if number is None:
        return "-"
    return number.text.strip() if number.text and number.text.strip() else "(empty)"


def transmissions_table(transmissions: Sequence[Transmission], title: str) -> Table:
    """One row per joint and actuator, grouped under their transmission."""
    table = Table(title=title, title_justify="left")
    for column in ("transmission", "dialect", "type", "member", "role", "reduction", "offset",
                   "interfaces"):
        table.add_column(column)
    for t in transmissions:
        line = f":{t.location.line}" if t.location else ""
        head = [f"{t.name}{line}", t.dialect, _short(t.type)]
        members = [("joint", j) for j in t.joints] + [("actuator", a) for a in t.actuators]
        for index, (noun, member) in enumerate(members or [("-", None)]):
            cells = head if index == 0 else ["", "", ""]
            if member is None:
                table.add_row(*cells, "-", "", "", "", "", end_section=True)
                continue
            table.add_row(
                *cells,
                f"{noun} {member.name}",
                member.role or "",
                _number(member.mechanical_reduction),
                _number(member.offset) if noun == "joint" else "",
                ", ".join(_short(i) for i in member.interfaces),
                end_section=index == len(members) - 1,
            )
    return table


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
            transmission,
            actuator,
            f"[{position[0]:.6g}, {position[1]:.6g}]" if position else "-",
            _maybe(getattr(limit, "velocity", None)),
            _maybe(getattr(limit, "effort", None)),
        )
    return table


def _maybe(value: float | None) -> str:
    return "-" if value is None else f"{value:.6g}"


def console(*, stderr: bool = False):
    """A rich console; wide enough for tables when output goes to a file or a pipe."""
    import sys

    from rich.console import Console

    stream = sys.stderr if stderr else sys.stdout
    width = None if stream.isatty() else 140
    return Console(file=stream, width=width, highlight=False)
