"""A progress bar on stderr while ``validate`` checks files, for runs that take a while.

Shown only when stderr is a terminal (never in a pipe, a file or a CI log), and only once the
run has lasted :data:`DELAY` seconds with files left; it is erased when the run ends, before
the report is printed. It advances as files are done, in this process and, when several
processes share the files (``--jobs``), in the others too (they tell their counts chunk by
chunk, see :mod:`txtool.lint.workers`). No thread is started (worker processes are forked only
where no thread runs), so the bar is redrawn as files are done.
"""

from __future__ import annotations

import contextlib
import os
import sys
import time
from collections.abc import Callable, Iterator
from typing import Any, TextIO

DELAY = 1.0  # seconds: shorter runs draw nothing

Report = Callable[[int, int], None]  # (files done, files in all)


@contextlib.contextmanager
def file_progress(stream: TextIO | None = None) -> Iterator[Report | None]:
    """A function to call with (files done, files in all) as files are checked, or None where
    no bar may be drawn."""
    stream = stream or sys.stderr
    if not _draws_on(stream):
        yield None
        return
    bar = _DelayedBar(stream)
    try:
        yield bar.update
    finally:
        bar.stop()


def _draws_on(stream: TextIO) -> bool:
    if os.environ.get("TERM") == "dumb":  # a bar redrawn in place needs cursor movement
        return False
    try:
        return stream.isatty()
    except (AttributeError, ValueError):
        return False


class _DelayedBar:
    def __init__(self, stream: TextIO) -> None:
        self.stream = stream
        self.started = time.monotonic()
        self.progress: Any = None
        self.task: Any = None

    def update(self, done: int, total: int) -> None:
        if self.progress is None:
            if done >= total or time.monotonic() - self.started < DELAY:
                return
            self._start(total)
        self.progress.update(self.task, completed=done, total=total)
        self.progress.refresh()

    def _start(self, total: int) -> None:
        from rich.console import Console
        from rich.progress import BarColumn, MofNCompleteColumn, Progress, TimeElapsedColumn

        from txtool.views.plain import output_size

        width, height = output_size(self.stream)
        console = Console(file=self.stream, width=width, height=height, highlight=False,
                          emoji=False)
        self.progress = Progress("checking", BarColumn(), MofNCompleteColumn(), "files",
                                 TimeElapsedColumn(), console=console, transient=True,
                                 auto_refresh=False)
        self.progress.start()
        self.task = self.progress.add_task("checking", total=total)

    def stop(self) -> None:
        if self.progress is not None:
            self.progress.stop()
