"""Stopping cleanly on Ctrl-C (SIGINT) and SIGTERM.

The ``txtool`` command answers a signal with one line and exit ``128 + signal`` (130, 143) at
every moment after its code starts, in three stages:

- while the modules load: ``txtool/__init__.py`` calls :func:`exit_on_signals` as its first
  step when the process is the command (:func:`started_as_command`): a signal ends the process
  at once, as nothing is written yet;
- while the command runs: the command line installs :func:`stop_on_signals`: the first signal
  raises :class:`Stopped` where the program is, so every ``finally`` runs (a temporary file is
  removed). :class:`Stopped` is not a ``KeyboardInterrupt``, so click does not turn it into
  "Aborted!" and exit 1. Further signals are ignored while the program unwinds, and
  :func:`held` delays one that arrives in a step that must not be cut in two (creating a
  temporary file and recording its name);
- while an asyncio event loop runs (``txtool lsp``): a signal raised inside one of the loop's
  callbacks would be caught and logged by asyncio and the loop would go on serving, so the
  process ends from the loop instead, between two callbacks: no handler is midway then, and
  its temporary files are gone (:func:`_leave_from_loop`);
- once the command has finished: :func:`exit_on_signals` again.

Library use installs nothing: Ctrl-C stays a KeyboardInterrupt. This module imports little, as
it is loaded before everything else.
"""

from __future__ import annotations

import os
import signal
import sys

TYPE_CHECKING = False  # not typing's: importing typing would delay the first handler
if TYPE_CHECKING:
    from collections.abc import Callable
    from types import FrameType, TracebackType

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


def started_as_command() -> bool:
    """Whether this process is the ``txtool`` command: its console script, or
    ``python -m txtool`` (whose ``argv[0]`` is ``-m`` while the package loads)."""
    first = sys.argv[0] if sys.argv else ""
    if os.path.basename(first) == "txtool":
        return True
    given = getattr(sys, "orig_argv", [])
    return first == "-m" and any(
        (option, name) == ("-m", "txtool") or option == "-mtxtool"
        for option, name in zip(given, [*given[1:], ""], strict=True)
    )


def exit_on_signals() -> None:
    """Make SIGINT and SIGTERM print one line and end the process at once (no clean-up runs:
    for the moments when nothing is being written)."""
    _install(_exit_now)


def stop_on_signals() -> None:
    """Make SIGINT and SIGTERM raise :class:`Stopped` (from the main thread only)."""
    _State.received, _State.holding, _State.pending = None, 0, False
    _install(_on_signal)


def _install(handler: Callable[[int, FrameType | None], None]) -> None:
    for number in SIGNALS:
        try:
            signal.signal(number, handler)
        except ValueError:  # not the main thread: signals are not ours to handle
            return


class left_to_the_main_thread:  # a class, not a contextlib generator (see held)
    """Make threads that leave SIGINT and SIGTERM to the main thread: a thread started
    meanwhile blocks them from its first instruction, so the system delivers them to the main
    thread, which runs Python's handlers. One delivered to a thread blocked in a read would
    wait for the main thread to run Python again, which an event loop asleep in its selector
    never does (``txtool lsp`` would not end). A signal meanwhile waits until the end."""

    def __enter__(self) -> None:
        if hasattr(signal, "pthread_sigmask"):  # (POSIX)
            signal.pthread_sigmask(signal.SIG_BLOCK, SIGNALS)

    def __exit__(self, kind: type[BaseException] | None, error: BaseException | None,
                 trace: TracebackType | None) -> None:
        if hasattr(signal, "pthread_sigmask"):
            signal.pthread_sigmask(signal.SIG_UNBLOCK, SIGNALS)


def received() -> int | None:
    """The signal that stopped the run, if one did."""
    return _State.received


def stop_if_received() -> None:
    """Raise :class:`Stopped` again if a signal came and the program still goes on: C code that
    calls back into Python (an extension's import, a lookup) can clear the exception raised
    there. Called before reading or writing a file, which must not start after a signal."""
    if _State.received is not None and not _State.holding:
        raise Stopped(_State.received)


def _exit_now(number: int, frame: FrameType | None) -> None:
    try:
        os.write(2, Stopped(number).line.encode() + b"\n")
    finally:
        os._exit(128 + number)


def _on_signal(number: int, frame: FrameType | None) -> None:
    if _State.received is not None:
        return  # already stopping: let the clean-up finish
    _State.received = number
    if _leave_from_loop(number):
        return
    if _State.holding:
        _State.pending = True
        return
    raise Stopped(number)


def _leave_from_loop(number: int) -> bool:
    """Whether an asyncio event loop runs here; if one does, it is asked to end the process
    as its next callback. Ending it at once instead would not wait for a server's handler to
    finish (a temporary folder would be left), and a loop that serves standard input keeps a
    thread blocked reading it, which a normal exit would wait for until the editor closes it."""
    asyncio = sys.modules.get("asyncio")  # not imported: no loop can be running
    if asyncio is None:
        return False
    try:
        loop = asyncio.get_running_loop()
    except RuntimeError:
        return False
    loop.call_soon_threadsafe(_exit_now, number, None)
    return True


class held:  # a class, not a contextlib generator: contextlib would delay the first handler
    """Run a step whole: a signal arriving meanwhile takes effect when it ends."""

    def __enter__(self) -> None:
        _State.holding += 1

    def __exit__(self, kind: type[BaseException] | None, error: BaseException | None,
                 trace: TracebackType | None) -> None:
        _State.holding -= 1
        if kind is None and not _State.holding and _State.pending:
            _State.pending = False
            raise Stopped(_State.received or signal.SIGINT)
