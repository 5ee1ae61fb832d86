"""``txtool roundtrip FILE``: which fields survive every conversion cycle."""

from __future__ import annotations

import json

import click

from txtool.commands.common import (
    CONFIG_OPTION,
    FILE,
    FORMAT_OPTION,
    NO_XACRO_OPTION,
    Choice,
    configured_packages,
    exit_on_input_error,
    xacro_disabled,
    xacro_options,
)
from txtool.io.printable import printable


@click.command("roundtrip")
@click.argument("path", metavar="FILE", type=FILE)
@click.option("--against", metavar="OTHER", type=FILE,
              help="Instead, compare FILE's transmissions with OTHER's behaviourally.")
@click.option("--effort-convention", "convention", type=Choice(["ros2", "ros1"]),
              help="With --against: map four-bar efforts of both files with ros2_control's "
                   "or ros_control's map (default: each file with its own loader's).")
@FORMAT_OPTION
@NO_XACRO_OPTION
@CONFIG_OPTION
@xacro_options
@exit_on_input_error
def command(path, against, convention, output_format, no_xacro, config_path,
            xacro) -> int:
    """Convert FILE through every dialect cycle and report what survives.

    Columns: reduction, offset, direction, roles, interfaces (field by field, floats bit for
    bit) and whether the first conversion drives the actuators exactly like the original.
    Exit 1 if any cycle loses something or changes behaviour.
    """
    from txtool.io.load import load
    from txtool.io.xmlio import InputError

    if convention and not against:
        raise InputError("--effort-convention applies to --against only")
    expand = not xacro_disabled(no_xacro, path, against, config=config_path)
    source = load(path, xacro=configured_packages(xacro, path, config_path) if expand else xacro,
                  expand=expand)
    if against:
        other = configured_packages(xacro, against, config_path) if expand else xacro
        return _against(source, load(against, xacro=other, expand=expand), output_format,
                        convention)
    from txtool.transform.roundtrip import roundtrip

    report = roundtrip(source, consume=True)
    if output_format == "json":
        from txtool.views.report_json import roundtrip_json

        click.echo(roundtrip_json(report))
    else:
        _print_table(report)
    return 0 if report.ok else 1


def _print_table(report) -> None:
    import sys

    from txtool.views.plain import plain_output, roundtrip_text

    if plain_output(sys.stdout):
        text = roundtrip_text(report)
        if text is not None:
            sys.stdout.write(text)
            return
    _print_rich_table(report)


def _print_rich_table(report) -> None:
    from rich.table import Table

    from txtool.views.render import console, fit, safe
    from txtool.views.tables import FIELDS

    table = Table(title=safe(f"{report.path}: round trips"), title_justify="left")
    for column in ("transmission", "cycle", *FIELDS, "equivalent"):
        table.add_column(column)
    for row in report.rows:
        marks = ["✓" if row.fields[f] else "[red]✗[/red]" for f in FIELDS]
        equivalent = row.equivalent.split(":", 1)[0]
        if equivalent == "no":
            equivalent = "[red]no[/red]"
        table.add_row(safe(row.transmission), " → ".join(row.cycle), *marks, equivalent)
    out = console()
    fit(out, table)
    out.print(table)
    # One line each, wrapped by the terminal: rich's own wrapping of a line is quadratic in
    # its length (a 4 MB value took 18 s).
    for row in report.rows:
        reason = row.equivalent.split(": ", 1)[1:] if row.equivalent != "yes" else []
        for detail in (*row.details, *reason):
            out.print(safe(f"{row.transmission} ({' → '.join(row.cycle)}): {detail}"),
                      soft_wrap=True)
    for skipped in report.skipped:
        out.print(safe(f"passed through untouched: {skipped}"), soft_wrap=True)
    out.print(safe(report.summary) if report.ok else f"[red]{safe(report.summary)}[/red]",
              soft_wrap=True)


def _against(a, b, output_format, convention) -> int:
    from txtool.dialects.read import read_source
    from txtool.mechanics.equivalence import compare
    from txtool.model.robot import robot_joints
    from txtool.transform.bb.roundtrip import bb_drops

    a_transmissions = [f.transmission for f in read_source(a)]
    b_found = read_source(b)
    report = compare(a_transmissions, [f.transmission for f in b_found], robot_joints(a.root),
                     convention=convention)
    bb_dropped = bb_drops(a_transmissions, b_found)  # B written by Beam Bots' URDF exporter
    if output_format == "json":
        rows = [{"joints": list(r.joints), "a": r.a, "b": r.b, "status": r.status,
                 "differences": r.differences, "reason": r.reason} for r in report.rows]
        # The shape of every roundtrip report (schemas/roundtrip.schema.json): no cycles here.
        click.echo(json.dumps({"path": a.path, "against": b.path, "ok": report.equivalent,
                               "cycles": [], "skipped": [], "transmissions": rows,
                               "bb_exporter_dropped": bb_dropped}, indent=2))
    else:
        from rich.table import Table

        from txtool.views.render import console, fit, safe

        table = Table(title=safe(f"{a.path} against {b.path}"), title_justify="left")
        for column in ("joints", safe(a.path), safe(b.path), "status", "reason"):
            table.add_column(column)
        for r in report.rows:
            status = r.status if r.status == "equivalent" else f"[red]{r.status}[/red]"
            table.add_row(safe(", ".join(r.joints)), safe(r.a or "-"), safe(r.b or "-"), status,
                          safe(r.reason))
        out = console()
        fit(out, table)
        out.print(table)
        out.print("efforts: " + (f"{convention} maps for both (--effort-convention)" if convention
                                 else "each file through its own loader's maps"), markup=False)
        for line in bb_dropped:
            click.echo(f"BB dropped: {printable(line)}")
    return 0 if report.equivalent and not bb_dropped else 1
