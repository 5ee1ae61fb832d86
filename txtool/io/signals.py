"""Stopping cleanly on Ctrl-C (SIGINT) and SIGTERM.

The command line installs :func:`stop_on_signals`: the first signal raises :class:`Stopped`
where the program is, so every ``finally`` runs (a temporary file is removed) and the CLI exits
130 or 143 with one line. :class:`Stopped` is not a ``KeyboardInterrupt``, so click does not
turn it into "Aborted!" and exit 1. Further signals are ignored while the program unwinds, and
:func:`held` delays one that arrives in a step that must not be cut in two (creating a temporary
file and recording its name). Library use installs nothing: Ctrl-C stays a KeyboardInterrupt.
"""

from __future__ import annotations

import signal
import threading
from collections.abc import Iterator
from contextlib import contextmanager
from types import FrameType

SIGNALS = (signal.SIGINT, signal.SIGTERM)


class Stopped(BaseException):
    """SIGINT or SIGTERM arrived; the process exits ``128 + signal``."""

    def __init__(self, number: int) -> None:
        super().__init__(number)
        self.number = number

    @property
    def exit_code(self) -> int:
        return 128 + self.number

    @property
    def line(self) -> str:
        return "txtool: interrupted" if self.number == signal.SIGINT else "txtool: terminated"


class _State:
    received: int | None = None  # the first signal
    holding = 0
    pending = False


def stop_on_signals() -> None:
    """Make SIGINT and SIGTERM raise :class:`Stopped` (from the main thread only)."""
    if threading.current_thread() is not threading.main_thread():
        return
    _State.received, _State.holding, _State.pending = None, 0, False
    for number in SIGNALS:
        signal.signal(number, _on_signal)


def received() -> int | None:
    """The signal that stopped the run, if one did."""
    return _State.received


def _on_signal(number: int, frame: FrameType | None) -> None:
    if _State.received is not None:
        return  # already stopping: let the clean-up finish
    _State.received = number
    if _State.holding:
        _State.pending = True
        return
    raise Stopped(number)


@contextmanager
def held() -> Iterator[None]:
    """Run a step whole: a signal arriving meanwhile takes effect when it ends."""
    _State.holding += 1
    try:
        yield
    except BaseException:
        _State.holding -= 1
        raise
    _State.holding -= 1
    if not _State.holding and _State.pending:
        _State.pending = False
        raise Stopped(_State.received or signal.SIGINT)
