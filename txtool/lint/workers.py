"""Sharing work among forked processes, this one included.

``forked_map(function, count, processes)`` computes ``function(i)`` for every ``i`` below
``count`` in this process and ``processes - 1`` forks of it, and yields the results in order:

* Forks inherit everything loaded so far (modules, rules, the list of files), so nothing is
  pickled on the way in and a fork starts in about a millisecond.
* Indices go out in small chunks through one pipe that every process reads as it becomes free,
  so a process that drew large files simply takes fewer chunks. All chunk numbers are written
  before the first fork, so that no read can take part of one; there are at most
  :data:`MAX_CHUNKS`, which fit the pipe's buffer (else nothing is shared).
* This process works through chunks too; each fork pickles its results once, when the pipe is
  empty, and exits. A chunk whose results never arrive (a fork that died) is computed here, so
  an error in ``function`` surfaces in this process, as it would without forks.
* With ``progress``, each process tells how many indices it has done, chunk by chunk (a fork
  through a pipe of counts, read here between chunks and while the forks' results arrive), so
  a progress bar moves while the forks work, not only when their results come back.

``multiprocessing`` would cost more than it saves here: importing its pool takes about 15 ms,
and its idle parent process and helper threads compete with the workers for the CPUs.
"""

from __future__ import annotations

import contextlib
import os
import pickle
import select
import signal
from collections.abc import Callable, Iterator
from typing import Any

from txtool.io.xacro_sandbox import sharing

MAX_CHUNKS = 1024  # 4 bytes each: 4 KB, what a pipe holds at the least on Linux
_WIDTH = 4


def chunk_size(count: int) -> int:
    """Indices per chunk: small for balance, large enough for at most MAX_CHUNKS chunks."""
    return max(4, -(-count // MAX_CHUNKS))


def forked_map(function: Callable[[int], Any], count: int, processes: int,
               size: int | None = None,
               progress: Callable[[int], None] | None = None) -> Iterator[Any]:
    """``function(i)`` for ``i`` in ``range(count)``, in order, from ``processes`` processes.

    ``size`` indices go out at a time (default :func:`chunk_size`; 1 for few, long tasks);
    ``progress(indices done)`` is called as chunks are done in any process.
    """
    size = size or chunk_size(count)
    starts = range(0, count, size)
    queue = _queue(b"".join(start.to_bytes(_WIDTH, "little") for start in starts))
    if queue is None:  # a pipe too small to hold them: no sharing
        for start in starts:
            yield from _chunk(function, start, size, count)
        return
    # the xacro workers of this process and its forks share the command's memory bound
    with sharing(processes):
        children: list[tuple[int, int]] = []
        counts = _Counts(progress) if progress is not None else None
        finished = False
        try:
            for _ in range(processes - 1):
                children.append(_fork(function, queue, size, count, counts))
            if counts is not None:
                counts.forked()
            done = _work(function, queue, size, count, counts)
            for part in _collect_all([results for _, results in children], counts):
                done.update(part)
            for pid, _ in children:
                os.waitpid(pid, 0)
            children.clear()
            finished = True
        finally:
            os.close(queue)
            if counts is not None:
                counts.close()
            if not finished:  # an error or Ctrl-C here: stop the forks still running
                _stop(children)
    for start in starts:
        part = done.get(start)
        if part is None:  # a fork died before reporting it
            part = _chunk(function, start, size, count)
        yield from part


def _queue(records: bytes) -> int | None:
    """The read end of a pipe that holds ``records`` and nothing more will be written to.

    Every record is in the pipe before anyone reads, so a read of one record's width never
    returns part of one, however many processes read. None when the pipe's buffer cannot hold
    them all (Linux's holds at least 4 KB).
    """
    queue, feed = os.pipe()
    try:
        os.set_blocking(feed, False)
        written = os.write(feed, records) if records else 0
    except BlockingIOError:
        written = -1
    finally:
        os.close(feed)
    if written != len(records):
        os.close(queue)
        return None
    return queue


class _Counts:
    """Indices done in every process: this one's, and what the forks write to a pipe (one
    count of :data:`_WIDTH` bytes per chunk; a pipe's buffer holds far more than
    :data:`MAX_CHUNKS` of them, so a fork never waits on it)."""

    def __init__(self, progress: Callable[[int], None]) -> None:
        self.progress = progress
        self.total = 0
        self.parent = os.getpid()
        self.read_end, self.write_end = os.pipe()
        os.set_blocking(self.read_end, False)

    def forked(self) -> None:
        """The forks are started: only they write counts now."""
        os.close(self.write_end)
        self.write_end = -1

    def add(self, indices: int) -> None:
        """This process did ``indices`` more (a fork: tell the parent)."""
        if self.write_end >= 0 and os.getpid() != self.parent:
            os.write(self.write_end, indices.to_bytes(_WIDTH, "little"))
            return
        self.total += indices
        self.drain()

    def drain(self) -> bool:
        """Add what the forks wrote since and tell ``progress``; False once every fork has
        closed the pipe (it has ended)."""
        open_ = True
        with contextlib.suppress(BlockingIOError):
            while raw := os.read(self.read_end, _WIDTH * 256):
                self.total += sum(int.from_bytes(raw[i:i + _WIDTH], "little")
                                  for i in range(0, len(raw), _WIDTH))
            open_ = False  # an empty read: the end of the pipe
        self.progress(self.total)
        return open_

    def close(self) -> None:
        for end in (self.read_end, self.write_end):
            if end >= 0:
                with contextlib.suppress(OSError):
                    os.close(end)


def _fork(function: Callable[[int], Any], queue: int, size: int, count: int,
          counts: _Counts | None = None) -> tuple[int, int]:
    results, sink = os.pipe()
    pid = os.fork()
    if pid == 0:  # the fork: work, report, and leave without running the parent's exit code
        status = 1
        try:
            os.close(results)
            signal.signal(signal.SIGINT, signal.SIG_DFL)  # Ctrl-C ends a fork at once
            data = pickle.dumps(_work(function, queue, size, count, counts),
                                pickle.HIGHEST_PROTOCOL)
            with os.fdopen(sink, "wb") as stream:
                stream.write(data)
            status = 0
        finally:
            os._exit(status)
    os.close(sink)
    return pid, results


def _work(
    function: Callable[[int], Any], queue: int, size: int, count: int,
    counts: _Counts | None = None,
) -> dict[int, list[Any]]:
    """Take chunks from the queue until it is empty; their results by chunk start."""
    done: dict[int, list[Any]] = {}
    while True:
        raw = os.read(queue, _WIDTH)  # a pipe read takes whole records: all were written first
        if not raw:
            return done
        start = int.from_bytes(raw, "little")
        done[start] = _chunk(function, start, size, count)
        if counts is not None:
            counts.add(len(done[start]))


def _chunk(function: Callable[[int], Any], start: int, size: int, count: int) -> list[Any]:
    return [function(index) for index in range(start, min(start + size, count))]


def _collect_all(pipes: list[int], counts: _Counts | None) -> Iterator[dict[int, list[Any]]]:
    """Each fork's results, read from its pipe (closed when read), in the order of ``pipes``;
    with ``counts``, the forks' counts are read as the results are waited for."""
    if counts is None:
        for results in pipes:
            yield _collect(results)
        return
    received = {results: bytearray() for results in pipes}
    waiting = set(pipes)
    counting = True
    while waiting:
        watched = [*waiting, counts.read_end] if counting else list(waiting)
        readable, _, _ = select.select(watched, [], [])
        for end in readable:
            if end == counts.read_end:
                counting = counts.drain()
                continue
            block = os.read(end, 1 << 16)
            if block:
                received[end] += block
            else:
                waiting.discard(end)
                os.close(end)
    counts.drain()
    for results in pipes:
        yield _unpickled(bytes(received[results]))


def _collect(results: int) -> dict[int, list[Any]]:
    """A fork's results; nothing when it died before writing them all."""
    with os.fdopen(results, "rb") as stream:
        return _unpickled(stream.read())


def _unpickled(data: bytes) -> dict[int, list[Any]]:
    try:
        return pickle.loads(data) if data else {}  # type: ignore[no-any-return]
    except (pickle.UnpicklingError, EOFError, ValueError, TypeError):
        return {}


def _stop(children: list[tuple[int, int]]) -> None:
    for pid, results in children:
        with contextlib.suppress(OSError):  # already closed when its results were read
            os.close(results)
        with contextlib.suppress(ProcessLookupError, ChildProcessError):
            os.kill(pid, signal.SIGTERM)
            os.waitpid(pid, 0)
