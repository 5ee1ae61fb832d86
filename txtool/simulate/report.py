"""Rendering of simulate runs: rich tables, the JSON document, the CSV time series."""

from __future__ import annotations

import csv
import io
import math
from pathlib import Path
from typing import Any

from rich.console import Console
from rich.markup import escape
from rich.table import Table

from txtool.io.xmlio import write_atomic
from txtool.simulate.result import RunResult


def _num(value: float | None, digits: int = 4) -> str:
    if value is None:
        return "-"
    if math.isinf(value):
        return "none" if value > 0 else "-inf"
    return f"{value:.{digits}g}"


def _pct(value: float, limit: float) -> str:
    if math.isinf(limit):
        return "-"
    return "inf" if limit == 0 else f"{100 * value / limit:.0f}%"


def render_text(runs: list[RunResult], console: Console) -> None:
    """One run: its tables and verdict; several: a comparison table and each verdict."""
    if len(runs) == 1:
        render_run(runs[0], console)
        return
    console.print(comparison_table(runs))
    for run in runs:
        console.print(f"{escape(run.config)}: {verdict_line(run)}", soft_wrap=True)
        for reason in run.reasons[1:]:
            console.print(f"  - {escape(reason)}", soft_wrap=True)
    failed = [run.config for run in runs if not run.passed]
    if failed:
        console.print(f"[bold red]FAIL[/]: {len(failed)} of {len(runs)} configs fail: "
                      + ", ".join(escape(c) for c in failed), soft_wrap=True)
    else:
        console.print(f"[bold green]PASS[/]: all {len(runs)} configs track the reference")


def render_run(run: RunResult, console: Console) -> None:
    console.print(f"[bold]simulate[/] {escape(run.robot)} with {escape(run.config)}: "
                  f"{run.steps} steps of {run.dt:g} s ({run.duration:g} s), "
                  f"reference {escape(run.reference)}")
    console.print(joint_table(run))
    console.print(actuator_table(run))
    for note in run.notes:
        console.print(f"note: {escape(note)}", soft_wrap=True)
    console.print(verdict_line(run), soft_wrap=True)
    for reason in run.reasons[1:]:
        console.print(f"  - {escape(reason)}", soft_wrap=True)


def verdict_line(run: RunResult) -> str:
    if run.passed:
        worst = max(run.joints.items(), key=lambda kv: kv[1].max_error)
        return (f"[bold green]PASS[/]: largest tracking error {worst[1].max_error:.3g} "
                f"{worst[1].units} on '{escape(worst[0])}', no limit exceeded")
    more = f" (and {len(run.reasons) - 1} more)" if len(run.reasons) > 1 else ""
    return f"[bold red]FAIL[/]: {escape(run.reasons[0])}{more}"


def joint_table(run: RunResult) -> Table:
    table = Table(title="joints", title_justify="left")
    table.add_column("joint", no_wrap=True)
    for name in ("max error", "RMS error", "max at (s)", "limit margin"):
        table.add_column(name, justify="right")
    for name, j in run.joints.items():
        margin = "-" if j.limit_margin is None else f"{_num(j.limit_margin, 3)} {j.units}"
        table.add_row(escape(name), f"{_num(j.max_error, 3)} {j.units}",
                      f"{_num(j.rms_error, 3)} {j.units}", f"{j.max_error_time:.3f}", margin)
    return table


def actuator_table(run: RunResult) -> Table:
    table = Table(title="actuators (efforts as demanded, before saturation)",
                  title_justify="left")
    table.add_column("actuator", no_wrap=True)
    table.add_column("transmission", no_wrap=True)
    for name in ("peak effort", "RMS effort", "effort limit", "effort %", "peak speed",
                 "speed limit", "speed %", "saturated", "first violation"):
        table.add_column(name, justify="right")
    for name, a in run.actuators.items():
        first = "-" if a.first_violation is None else f"{a.first_violation:.3f} s"
        table.add_row(
            escape(name), escape(a.transmission or "(direct)"), _num(a.peak_effort, 3),
            _num(a.rms_effort, 3), _num(a.effort_limit, 3), _pct(a.peak_effort, a.effort_limit),
            _num(a.peak_velocity, 3), _num(a.velocity_limit, 3),
            _pct(a.peak_velocity, a.velocity_limit), f"{100 * a.saturated_fraction:.1f}%", first,
        )
    return table


def comparison_table(runs: list[RunResult]) -> Table:
    table = Table(title="comparison", title_justify="left")
    for name in ("config", "verdict", "worst joint", "max error", "peak effort %",
                 "peak speed %"):
        table.add_column(name, justify="right" if "%" in name or "error" in name else "left")
    for run in runs:
        joint, stats = max(run.joints.items(), key=lambda kv: kv[1].max_error)
        effort = max((a.effort_percent for a in run.actuators.values()), default=0.0)
        speed = max((a.velocity_percent for a in run.actuators.values()), default=0.0)
        verdict = "[green]pass[/]" if run.passed else "[red]fail[/]"
        table.add_row(escape(run.config), verdict, escape(joint),
                      f"{_num(stats.max_error, 3)} {stats.units}", f"{effort:.0f}%",
                      f"{speed:.0f}%")
    return table


def _finite(value: float | None) -> float | None:
    return None if value is None or not math.isfinite(value) else value


def run_json(run: RunResult) -> dict[str, Any]:
    """The documented JSON of one run (infinite limits are null)."""
    return {
        "verdict": run.verdict,
        "reasons": list(run.reasons),
        "robot": run.robot,
        "config": run.config,
        "reference": run.reference,
        "notes": list(run.notes),
        "joints": {
            name: {"max_error": j.max_error, "rms_error": j.rms_error,
                   "max_error_time": j.max_error_time, "limit_margin": j.limit_margin,
                   "units": j.units}
            for name, j in run.joints.items()
        },
        "actuators": {
            name: {"peak_effort": a.peak_effort, "effort_limit": _finite(a.effort_limit),
                   "rms_effort": a.rms_effort, "peak_velocity": a.peak_velocity,
                   "velocity_limit": _finite(a.velocity_limit),
                   "saturated_fraction": a.saturated_fraction,
                   "first_violation": a.first_violation, "transmission": a.transmission or None}
            for name, a in run.actuators.items()
        },
        "steps": run.steps,
        "dt": run.dt,
        "duration": run.duration,
    }


def document(runs: list[RunResult]) -> dict[str, Any]:
    """One run: its JSON; several: ``{"verdict", "runs": [...]}``. Non-finite numbers: null."""
    if len(runs) == 1:
        return _clean(run_json(runs[0]))
    return _clean({"verdict": "pass" if all(r.passed for r in runs) else "fail",
                   "runs": [run_json(r) for r in runs]})


def _clean(value: Any) -> Any:
    if isinstance(value, float):
        return _finite(value)
    if isinstance(value, dict):
        return {k: _clean(v) for k, v in value.items()}
    if isinstance(value, list):
        return [_clean(v) for v in value]
    return value


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
    write_atomic(path, handle.getvalue().encode("utf-8"))
