"""What ``txtool simulate`` does once its arguments are parsed: run, render, write, exit code."""

from __future__ import annotations

import json
import time
from dataclasses import replace

from rich.console import Console
from rich.progress import BarColumn, Progress, TaskProgressColumn, TextColumn, TimeRemainingColumn

from txtool.simulation import json_report, plot, report
from txtool.simulation.jobs import execute
from txtool.simulation.result import RunResult
from txtool.simulation.run import Options, exit_code
from txtool.views import render

SHOW_AFTER = 1.0  # seconds: shorter runs get no progress bar


class LazyProgress:
    """A rich progress bar on stderr that appears only once a run has taken over a second."""

    def __init__(self, console: Console, what: str) -> None:
        self.console = console
        self.what = what
        self.started = time.perf_counter()
        self.bar: Progress | None = None
        self.task = 0

    def __call__(self, done: int, total: int) -> None:
        if self.bar is None:
            if not self.console.is_terminal or time.perf_counter() - self.started < SHOW_AFTER:
                return
            self.bar = Progress(TextColumn(self.what), BarColumn(), TaskProgressColumn(),
                                TimeRemainingColumn(), console=self.console, transient=True)
            self.bar.start()
            self.task = self.bar.add_task(self.what, total=total, completed=done)
        self.bar.update(self.task, completed=done, total=total)

    def close(self) -> None:
        if self.bar is not None:
            self.bar.stop()


def nothing_drawn(runs: list[RunResult]) -> str:
    """Why no run has a time series to write: each was judged without being simulated."""
    whys = [run.coverage.why_nothing() if run.verdict == "inconclusive"
            else "its fault shows without a run" for run in runs]
    shown = "; ".join(dict.fromkeys(whys))
    return f"nothing was simulated ({shown})" if len(runs) == 1 else \
        f"none of the {len(runs)} configs was simulated ({shown})"


def main(options: Options, *, output: str = "text", csv_path: str | None = None,
         plot_path: str | None = None, plot_joints: tuple[str, ...] = (),
         console: Console | None = None,
         err_console: Console | None = None) -> tuple[list[RunResult], int]:
    """Run every config, print the report, write the optional files; (runs, exit code)."""
    if console is None:
        # The terminal's width (--color never too), or wide enough for the tables in a pipe.
        console = render.console()
    err_console = err_console or Console(stderr=True, emoji=False)
    if plot_path is not None:
        plot.require(plot_path)
    keep = csv_path is not None or plot_path is not None
    options = replace(options, keep_series=keep)
    what = "simulating" if len(options.configs) <= 1 else "configs"
    progress = LazyProgress(err_console, what)
    try:
        runs = execute(options, progress)
    finally:
        progress.close()
    # The files first: an interrupted or failed write prints no verdict.
    if csv_path is not None:
        for index, run in enumerate(runs, 1):
            if run.series is not None:  # an inconclusive run simulated nothing
                report.write_csv(run, report.numbered(csv_path, index, len(runs)))
    if plot_path is not None and any(run.series is not None for run in runs):
        plot.plot(runs, plot_path, plot_joints)
    for path, option in ((csv_path, "--csv"), (plot_path, "--plot")):
        if path is not None and all(run.series is None for run in runs):
            err_console.print(f"txtool: {path}: not written ({option}): {nothing_drawn(runs)}",
                              soft_wrap=True, highlight=False, markup=False)
    if output == "json":
        console.file.write(json.dumps(json_report.document(runs), indent=2,
                                      ensure_ascii=False) + "\n")
    else:
        report.render_text(runs, console)
    return runs, exit_code(runs)
