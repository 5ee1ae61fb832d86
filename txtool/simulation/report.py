"""Rendering of simulate runs: rich tables, the JSON document, the CSV time series."""

from __future__ import annotations

import csv
import io
import math
from collections.abc import Callable
from pathlib import Path
from typing import Any

from rich import box
from rich.console import Console
from rich.markup import escape as escape_markup
from rich.table import Table

from txtool.io.printable import printable
from txtool.io.xmlio import write_atomic
from txtool.lint.readers import FileReaders
from txtool.simulation.result import GainsUsed, RunResult


def escape(text: str) -> str:
    """A name or path from a file, printed through rich: one line, brackets as written."""
    return escape_markup(printable(text))

TABLE_WIDTH = 100  # tables fit this many columns (or the terminal, when narrower)


def _num(value: float | None, digits: int = 4) -> str:
    """Short and exact enough to read: 3 (or ``digits``) significant digits, no long exponents."""
    if value is None:
        return "-"
    if math.isinf(value):
        return "none" if value > 0 else "-inf"
    if math.isnan(value):
        return "nan"
    size = abs(value)
    if size != 0 and (size >= 10**5 or size < 1e-3):
        mantissa, exponent = f"{value:.{digits - 1}e}".split("e")
        return f"{mantissa}e{int(exponent)}"
    if size >= 10 ** (digits - 1):
        return f"{value:.0f}"
    return f"{value:.{digits}g}"


def _print_table(console: Console, table: Table) -> None:
    console.print(table, width=min(console.width, TABLE_WIDTH))


def _pct(value: float, limit: float) -> str:
    if math.isinf(limit):
        return "-"
    return "inf" if limit == 0 else f"{100 * value / limit:.0f}%"


def render_text(runs: list[RunResult], console: Console) -> None:
    """One run: its tables and verdict; several: a comparison table and each verdict."""
    if len(runs) == 1:
        render_run(runs[0], console)
        return
    _print_table(console, comparison_table(runs))
    for run in runs:
        console.print(f"{escape(run.config)}: {verdict_line(run)}", soft_wrap=True)
        for reason in run.reasons[1:]:
            console.print(f"  - {escape(reason)}", soft_wrap=True)
    failed = [run.config for run in runs if run.failed]
    unchecked = [run.config for run in runs if run.verdict == "inconclusive"]
    if failed:
        console.print(f"[bold red]FAIL[/]: {len(failed)} of {len(runs)} configs fail: "
                      + ", ".join(escape(c) for c in failed), soft_wrap=True)
    elif unchecked:
        console.print(f"[bold yellow]INCONCLUSIVE[/]: {len(unchecked)} of {len(runs)} configs "
                      "could not be checked: " + ", ".join(escape(c) for c in unchecked),
                      soft_wrap=True)
    else:
        console.print(f"[bold green]PASS[/]: all {len(runs)} configs track the reference")


def render_run(run: RunResult, console: Console) -> None:
    if run.steps == 0:  # judged unrun: nothing to check, or a fault seen without a run
        console.print(f"[bold]simulate[/] {escape(run.robot)} with {escape(run.config)}: "
                      "not simulated", soft_wrap=True)
        for line in readers_lines(run):
            console.print(escape(line), soft_wrap=True)
        for note in run.notes:
            console.print(f"note: {escape(note)}", soft_wrap=True)
        console.print(verdict_line(run), soft_wrap=True)
        for reason in run.reasons[1:]:
            console.print(f"  - {escape(reason)}", soft_wrap=True)
        return
    console.print(f"[bold]simulate[/] {escape(run.robot)} with {escape(run.config)}: "
                  f"{run.steps} steps of {run.dt:g} s ({run.duration:g} s)", soft_wrap=True)
    console.print(f"reference: {escape(run.reference)}", soft_wrap=True)
    for line in readers_lines(run):
        console.print(escape(line), soft_wrap=True)
    for table in [*joint_tables(run), *actuator_tables(run)]:
        _print_table(console, table)
    if run.controllers:
        _print_table(console, controllers_table(run))
    gains = gains_table(run)
    if isinstance(gains, Table):
        _print_table(console, gains)
    elif gains:
        console.print(gains, soft_wrap=True)
    for note in run.notes:
        console.print(f"note: {escape(note)}", soft_wrap=True)
    console.print(verdict_line(run), soft_wrap=True)
    for reason in run.reasons[1:]:
        console.print(f"  - {escape(reason)}", soft_wrap=True)


def readers_lines(run: RunResult) -> list[str]:
    """``read by: ros2_control (jazzy) (--ros-distro jazzy)``: whose reading was simulated, for
    the robot and, when it is another file, the config."""
    robot, config = run.readers["robot"], run.readers.get("config")
    if config is None:
        return [f"read by: {readers_text(robot)}"]
    return [f"robot read by: {readers_text(robot)}", f"config read by: {readers_text(config)}"]


def readers_text(readers: FileReaders) -> str:
    if not readers.readers:
        return "not known (each transmission as the loader of its dialect reads it)"
    text = f"{', '.join(readers.readers)} ({'; '.join(dict.fromkeys(readers.because))})"
    if not readers.decided:
        text += "; nothing rules ROS 1 out: ros_control may read the top-level transmissions"
    return text


def verdict_line(run: RunResult) -> str:
    """The verdict and why; a run that checked only part of the config says how much."""
    covered = run.coverage
    if run.verdict == "inconclusive":
        return f"[bold yellow]INCONCLUSIVE[/]: nothing checked: {escape(covered.why_nothing())}"
    part = f"; {covered.summary()}" if covered.partial else ""
    if run.passed:
        worst = max(run.joints.items(), key=lambda kv: kv[1].max_error)
        return (f"[bold green]PASS[/]: largest tracking error {worst[1].max_error:.3g} "
                f"{worst[1].units} on '{escape(worst[0])}', no limit exceeded{part}")
    more = f" (and {len(run.reasons) - 1} more)" if len(run.reasons) > 1 else ""
    return f"[bold red]FAIL[/]: {escape(run.reasons[0])}{more}{part}"


def _table(title: str) -> Table:
    """The tables' common look: heavy header, no outer edge (they fit 100 columns)."""
    return Table(title=title, title_justify="left", box=box.HEAVY_HEAD, show_edge=False)


def _groups(items: dict[str, Any], units: Callable[[Any], str]) -> list[tuple[str, list[str]]]:
    """Names grouped by units: rotary (rad) first, then linear (m), then mixed."""
    groups: dict[str, list[str]] = {}
    for name, item in items.items():
        groups.setdefault(units(item), []).append(name)
    order = {"rad": 0, "m": 1}
    return sorted(groups.items(), key=lambda kv: order.get(kv[0], 2))


def joint_tables(run: RunResult) -> list[Table]:
    """One table per unit: revolute and continuous joints in rad, prismatic ones in m."""
    tables = []
    for units, names in _groups(run.joints, lambda j: j.units):
        kind = "prismatic joints" if units == "m" else "joints"
        table = _table(f"{kind} ({units})")
        table.add_column("joint", overflow="fold")
        table.add_column("transmission", overflow="fold")
        for name in (f"max\nerror\n({units})", f"RMS\nerror\n({units})", "max\nat\n(s)",
                     f"limit\nmargin\n({units})"):
            table.add_column(name, justify="right")
        for name in names:
            j = run.joints[name]
            table.add_row(escape(name), escape(j.transmission or "(direct)"),
                          _num(j.max_error, 3), _num(j.rms_error, 3), f"{j.max_error_time:.3f}",
                          _num(j.limit_margin, 3))
        tables.append(table)
    return tables


def actuator_tables(run: RunResult) -> list[Table]:
    """One table per unit (rotary N·m and rad/s, linear N and m/s); efforts as demanded."""
    tables = []
    for units, names in _groups(run.actuators, lambda a: a.units):
        first = run.actuators[names[0]]
        effort, speed = first.effort_units, first.speed_units
        kind = {"m": "linear actuators", "mixed": "actuators"}.get(units, "actuators")
        table = _table(f"{kind} ({effort}, {speed}; efforts as demanded, before saturation)")
        table.add_column("actuator", overflow="fold")
        for name in (f"peak\neffort\n({effort})", f"RMS\neffort\n({effort})",
                     f"effort\nlimit\n({effort})", "peak\n% of\nlimit",
                     f"peak\nspeed\n({speed})", f"speed\nlimit\n({speed})",
                     "peak\n% of\nlimit", "time\nsatu-\nrated"):
            table.add_column(name, justify="right")
        for name in names:
            a = run.actuators[name]
            table.add_row(
                escape(name), _num(a.peak_effort, 3), _num(a.rms_effort, 3),
                _num(a.effort_limit), _pct(a.peak_effort, a.effort_limit),
                _num(a.peak_velocity, 3), _num(a.velocity_limit),
                _pct(a.peak_velocity, a.velocity_limit), _share(a.saturated_fraction),
            )
        tables.append(table)
    return tables


def _share(fraction: float) -> str:
    percent = 100 * fraction
    return f"{percent:.1f}%" if 0 < percent < 10 else f"{percent:.0f}%"


def gains_table(run: RunResult) -> Table | str:
    """The gains used: one line when all are the defaults, else a table with their sources."""
    if not run.gains:
        return ""
    if all(g.source is None for g in run.gains.values()):
        g = next(iter(run.gains.values()))
        return (f"gains: kp {_num(g.kp)} 1/s², kd {_num(g.kd)} 1/s, ki 0 for every joint "
                f"(critically damped at --bandwidth {g.bandwidth:g} rad/s)")
    table = _table("gains (acceleration per error: the law multiplies them by M)")
    units = {g.units for g in run.gains.values()}
    shown = units.pop() if len(units) == 1 else None
    divided = any(g.inertia is not None for g in run.gains.values())
    table.add_column("joint", overflow="fold")
    for name in ("kp\n(1/s²)", "kd\n(1/s)", "ki\n(1/s³)", f"I clamp\n({shown or 'rad|m'}/s²)"):
        table.add_column(name, justify="right")
    if divided:
        table.add_column("effort gains\n÷ M_ii\n(kg·m², kg)" if shown is None
                         else f"effort gains\n÷ M_ii\n({'kg' if shown == 'm' else 'kg·m²'})",
                         justify="right")
    table.add_column("from")
    for name, g in run.gains.items():
        clamp = "none" if g.i_clamp is None else _num(g.i_clamp, 3)
        if g.i_clamp is not None and shown is None:
            clamp += f" {g.units}"
        row = [escape(name), _num(g.kp, 4), _num(g.kd, 4), _num(g.ki, 4), clamp if g.ki else "-"]
        if divided:
            row.append(_num(g.inertia, 3))
        table.add_row(*row, escape(gain_origin(g)))
    return table


def controllers_table(run: RunResult) -> Table:
    """``--controllers``: the controller commanding each joint, or none (the joint is held)."""
    table = _table("controllers (--controllers)")
    for name in ("joint", "controller", "command", "at"):
        table.add_column(name, overflow="fold")
    for joint, driver in run.controllers.items():
        if driver is None:
            table.add_row(escape(joint), "none: held", "-", "-")
            continue
        table.add_row(escape(joint), escape(driver.controller), "/".join(driver.interfaces),
                      escape(f"{Path(driver.file).name}:{driver.line}"))
    return table


def gain_origin(g: GainsUsed) -> str:
    """``file:line`` or the default; the rest at the bandwidth when the file gave only some."""
    if g.source is None:
        return f"default (--bandwidth {g.bandwidth:g} rad/s)"
    where = f"{Path(g.source.file).name}:{g.source.line}" if g.source.line else \
        Path(g.source.file).name
    if g.bandwidth is not None:
        where += f", the rest at --bandwidth {g.bandwidth:g}"
    return where


VERDICT_CELL = {"pass": "[green]pass[/]", "fail": "[red]fail[/]",
                "inconclusive": "[yellow]inconclusive[/]"}


def comparison_table(runs: list[RunResult]) -> Table:
    units = {max(r.joints.values(), key=lambda j: j.max_error).units for r in runs if r.joints}
    shown = units.pop() if len(units) == 1 else None
    table = _table("comparison")
    table.add_column("config", overflow="fold")
    table.add_column("verdict")
    table.add_column("worst joint")
    table.add_column(f"max error\n({shown or 'rad|m'})", justify="right")
    table.add_column("peak effort\n% of limit", justify="right")
    table.add_column("peak speed\n% of limit", justify="right")
    for run in runs:
        verdict = VERDICT_CELL[run.verdict]
        if not run.joints:
            table.add_row(escape(run.config), verdict, "-", "-", "-", "-")
            continue
        joint, stats = max(run.joints.items(), key=lambda kv: kv[1].max_error)
        effort = max((a.effort_percent for a in run.actuators.values()), default=0.0)
        speed = max((a.velocity_percent for a in run.actuators.values()), default=0.0)
        error = _num(stats.max_error, 3) + ("" if shown else f" {stats.units}")
        table.add_row(escape(run.config), verdict, escape(joint), error, f"{effort:.0f}%",
                      f"{speed:.0f}%")
    return table


def overall_verdict(runs: list[RunResult]) -> str:
    """``fail`` if any run fails, else ``inconclusive`` if any checked nothing, else ``pass``."""
    verdicts = {run.verdict for run in runs}
    return next(v for v in ("fail", "inconclusive", "pass") if v in verdicts)


def numbered(path: str, index: int, count: int) -> str:
    """``out.csv`` for one run; ``out.1.csv``, ``out.2.csv``... for several."""
    if count == 1:
        return path
    p = Path(path)
    return str(p.with_name(f"{p.stem}.{index}{p.suffix}"))


def write_csv(run: RunResult, path: str) -> None:
    """time, per joint ref/pos/error, per actuator demanded and applied effort and speed."""
    series = run.series
    if series is None:
        raise ValueError("the run kept no time series")
    header = ["time"]
    for j in series.joints:
        header += [f"{j}.ref", f"{j}.pos", f"{j}.error"]
    for a in series.actuators:
        header += [f"{a}.effort_demand", f"{a}.effort", f"{a}.velocity"]
    steps = len(series.effort)
    handle = io.StringIO(newline="")
    writer = csv.writer(handle)
    writer.writerow(header)
    for k, t in enumerate(series.time):
        row = [repr(float(t))]
        for v in range(len(series.joints)):
            ref, pos = float(series.q_ref[k, v]), float(series.q[k, v])
            row += [repr(ref), repr(pos), repr(pos - ref)]
        for i in range(len(series.actuators)):
            if k < steps:
                row += [repr(float(series.effort_demand[k, i])),
                        repr(float(series.effort[k, i]))]
            else:
                row += ["", ""]
            row.append(repr(float(series.velocity[k, i])))
        writer.writerow(row)
    # One atomic write: an interrupted run leaves the old file or none, never half a file.
    write_atomic(path, handle.getvalue().encode("utf-8"), report=True)
