"""Untrusted xacro expansion: a child process, an empty environment, bounded in every way.

The parent (:func:`expand_in_sandbox`) starts ``python -I -S`` with an empty environment
(and no site-packages ``.pth`` file run), once per process, and sends it one request per file
on its standard input: the file, the xacro options, the values of the variables
``--xacro-env`` allows and of the ROS package paths ``$(find)`` reads (``AMENT_PREFIX_PATH``,
``ROS_PACKAGE_PATH``, ``CMAKE_PREFIX_PATH``); nothing else of the parent's environment ever
reaches it. It reads back one JSON header line and the expanded text. For each request the
child (:func:`txtool.io.xacro_child.main`) sets its limits before it reads the file:

- wall time: :data:`DEFAULT_TIMEOUT` seconds (``TXTOOL_XACRO_TIMEOUT``), the parent kills it
  then; CPU time the same, as a backstop;
- memory: :data:`DEFAULT_MEMORY_MB` MiB of address space (``TXTOOL_XACRO_MEMORY_MB``) for the
  whole command: while ``processes`` share the work (:func:`sharing`, ``validate -j N``), each
  one's worker has its share;
- nodes and work: :data:`txtool.io.xacro_guard.MAX_NODES` XML nodes created by macro calls,
  blocks and includes, :data:`txtool.io.xacro_eval.MAX_WORK` steps of evaluation and tree
  work, both the file's own (a macro fan-out is stopped while it grows);
- output: :data:`MAX_OUTPUT` bytes of expanded text;
- no file may be written (``RLIMIT_FSIZE`` 0), no core dump;
- its parent's life: the child ends when the parent does (a pipe it watches, see
  :mod:`txtool.io.xacro_child`), even when the parent is killed outright.

and expands with :class:`txtool.io.xacro_guard.XacroGuard` installed. Exceeding a limit is one
line, ``path: xacro: expansion exceeded ... (a safety limit)``. The limits' variables are read
by :func:`limits`: a value that is no number in their range is one line.
"""

from __future__ import annotations

import atexit
import base64
import contextlib
import json
import math
import os
import select
import subprocess
import sys
import time
from collections.abc import Iterator
from typing import Any

from txtool.io import targets
from txtool.io.xmlio import MAX_BYTES, InputError, XacroError, XacroOptions

DEFAULT_TIMEOUT = 30.0
DEFAULT_MEMORY_MB = 512
TIMEOUT_RANGE = (0.0, 3600.0)  # seconds: above 0, at most an hour
MEMORY_RANGE = (64, 1 << 20)  # MiB: what the child needs to start, at most a tebibyte
MAX_OUTPUT = MAX_BYTES
PACKAGE_VARIABLES = ("AMENT_PREFIX_PATH", "ROS_PACKAGE_PATH", "CMAKE_PREFIX_PATH")
_BOOT = ("import sys, json; sys.path[:0] = json.loads(sys.argv[1]); "
         "from txtool.io.xacro_child import main; main(int(sys.argv[2]))")


class XacroLimit(InputError):
    """An untrusted expansion went past a safety limit."""

    def __init__(self, path: str, what: str) -> None:
        super().__init__(f"{path}: xacro: expansion exceeded {what} (a safety limit)")


class XacroRefused(InputError):
    """An untrusted file asked for something the restricted expansion does not do."""

    def __init__(self, path: str, line: int, reason: str) -> None:
        super().__init__(f"{path}:{line}: xacro: {reason}")
        self.reason = reason


def _limit_from_environment(name: str, default: float, low: float, high: float,
                            unit: str) -> float:
    """The number in ``name``, above ``low`` (seconds) or from it (MiB) and at most ``high``;
    anything else (not a number, nan, inf, 0, negative, too large) is one line."""
    value = os.environ.get(name)
    if value is None:
        return default
    try:
        number = float(value)
    except ValueError:
        number = math.nan
    above = number > low if unit == "seconds" else number >= low
    if not (above and number <= high):  # nan compares false: refused too
        lowest = f"above {low:g}" if unit == "seconds" else f"from {low:g}"
        raise InputError(f"{name}={value!r}: expected a number of {unit} {lowest} to {high:g}")
    return number


def limits() -> tuple[float, int]:
    """(seconds, MiB) from ``TXTOOL_XACRO_TIMEOUT`` and ``TXTOOL_XACRO_MEMORY_MB``: the job's
    environment sets them, never a file in the repository. The MiB are the whole command's."""
    seconds = _limit_from_environment("TXTOOL_XACRO_TIMEOUT", DEFAULT_TIMEOUT, *TIMEOUT_RANGE,
                                      "seconds")
    memory = int(_limit_from_environment("TXTOOL_XACRO_MEMORY_MB", DEFAULT_MEMORY_MB,
                                         *MEMORY_RANGE, "MiB"))
    return seconds, memory


_sharers = 1  # processes sharing the command's memory bound (see sharing)


@contextlib.contextmanager
def sharing(processes: int) -> Iterator[None]:
    """While ``processes`` (this one and its forks) expand files at once, each worker's memory
    is its share of the command's bound, so that together they hold no more than it."""
    global _sharers
    saved, _sharers = _sharers, max(1, processes)
    try:
        yield
    finally:
        _sharers = saved


def _share(memory: int) -> int:
    return max(MEMORY_RANGE[0], memory // _sharers)


def expand_in_sandbox(path: str, display: str, options: XacroOptions, *,
                      max_read: int = MAX_BYTES, data: bytes | None = None) -> str:
    """The expanded text of ``path`` (with ``data`` read for it when given, see
    :func:`txtool.io.xacro.expand_xacro`); :class:`XacroError` or :class:`XacroLimit` if none.

    ``max_read`` is what the expansion may read in all (:data:`txtool.io.xacro.MAX_READ`)."""
    seconds, total = limits()
    memory = _share(total)
    request = {
        "path": os.path.abspath(path), "display": display,
        "args": options.args, "pkg_dirs": options.pkg_dirs, "pkg_paths": options.pkg_paths,
        "env_names": options.env, "readable": options.readable,
        "env": {name: os.environ[name] for name in options.env if name in os.environ},
        "seconds": seconds, "memory": memory, "max_read": max_read,
        "package_paths": {k: os.environ[k] for k in PACKAGE_VARIABLES if k in os.environ},
        "data": None if data is None else base64.b64encode(data).decode("ascii"),
    }
    worker = _worker()
    try:
        reply, text = worker.ask(request, seconds)
    except TimeoutError:
        _retire(worker)
        raise XacroLimit(display, f"{seconds:g} seconds") from None
    except (OSError, ValueError):
        _retire(worker)
        raise XacroLimit(display, f"{memory} MiB of memory, or stopped abnormally "
                         f"(exit status {worker.process.returncode})") from None
    except BaseException:
        _retire(worker)
        raise
    if reply.get("retire"):
        _retire(worker)
    targets.remember_inputs(reply.get("inputs", []))
    if "limit" in reply:
        raise XacroLimit(display, reply["limit"])
    if "refused" in reply:
        raise XacroRefused(display, reply.get("line", 1), reply["refused"])
    if "error" in reply:
        raise XacroError(display, reply["error"], reply.get("line", 1), reply.get("missing", ""))
    return text.decode("utf-8")


def prestart() -> None:
    """Start the worker now, so that it boots while this process loads the command's code."""
    with contextlib.suppress(InputError, OSError):
        limits()  # a bad limit is said when a file is expanded, not here
        _worker()


class _Worker:
    """One child process, reused for every file this process expands (a start costs about a
    tenth of a second); retired after a limit is hit, replaced on the next file."""

    def __init__(self) -> None:
        self.owner = os.getpid()
        watched, self.lifeline = os.pipe()  # the child's end of file: this process ended
        try:
            self.process = subprocess.Popen(
                [sys.executable, "-I", "-S", "-X", "utf8", "-c", _BOOT,
                 json.dumps(_import_path()), str(watched)],
                stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL,
                env={}, close_fds=True, pass_fds=(watched,), cwd=os.getcwd(),
            )
        except BaseException:
            os.close(self.lifeline)
            raise
        finally:
            os.close(watched)

    def ask(self, request: dict[str, Any], seconds: float) -> tuple[dict[str, Any], bytes]:
        """Send one request; the reply header and text. TimeoutError, OSError on EOF."""
        assert self.process.stdin is not None and self.process.stdout is not None
        self.process.stdin.write(json.dumps(request).encode("utf-8") + b"\n")
        self.process.stdin.flush()
        reader = _Reader(self.process.stdout.fileno(), time.monotonic() + seconds)
        reply = json.loads(reader.line())
        size = int(reply.get("size", 0))
        if size > MAX_OUTPUT:
            raise ValueError("oversized reply")
        return reply, reader.exactly(size)

    def close(self) -> None:
        with contextlib.suppress(OSError):
            if self.process.stdin is not None:
                self.process.stdin.close()
        try:
            self.process.wait(timeout=1)
        except subprocess.TimeoutExpired:
            self.process.kill()
            self.process.wait()
        if self.process.stdout is not None:
            self.process.stdout.close()
        self.release()

    def release(self) -> None:
        """Let go of the lifeline (closed, the child ends: see :mod:`txtool.io.xacro_child`)."""
        if self.lifeline >= 0:
            with contextlib.suppress(OSError):
                os.close(self.lifeline)
            self.lifeline = -1


class _Reader:
    """Reads a child's standard output against a deadline."""

    def __init__(self, fd: int, deadline: float) -> None:
        self.fd = fd
        self.deadline = deadline
        self.buffer = bytearray()

    def _more(self) -> None:
        left = self.deadline - time.monotonic()
        if left <= 0 or not select.select([self.fd], [], [], left)[0]:
            raise TimeoutError
        chunk = os.read(self.fd, 1 << 20)
        if not chunk:
            raise OSError("the xacro worker ended")
        self.buffer += chunk

    def line(self) -> bytes:
        while b"\n" not in self.buffer:
            if len(self.buffer) > 1 << 20:
                raise ValueError("oversized header")
            self._more()
        line, _, rest = bytes(self.buffer).partition(b"\n")
        self.buffer = bytearray(rest)
        return line

    def exactly(self, size: int) -> bytes:
        while len(self.buffer) < size:
            self._more()
        return bytes(self.buffer[:size])


_current: _Worker | None = None


def _worker() -> _Worker:
    global _current
    worker = _current
    if worker is None or worker.owner != os.getpid() or worker.process.poll() is not None:
        if worker is not None and worker.owner == os.getpid():
            _retire(worker)
        if _current is None or _current.owner != os.getpid():
            atexit.register(_close_current)
        _current = worker = _Worker()
    return worker


def _after_fork() -> None:
    """In a fork: the parent's worker is not this process's to keep alive."""
    if _current is not None and _current.owner != os.getpid():
        _current.release()


os.register_at_fork(after_in_child=_after_fork)


def _retire(worker: _Worker) -> None:
    global _current
    with contextlib.suppress(OSError):
        worker.process.kill()
    worker.close()
    if _current is worker:
        _current = None


def _close_current() -> None:
    if _current is not None and _current.owner == os.getpid():
        _current.close()


def _import_path() -> list[str]:
    """Where the child finds txtool, xacro, yaml and lxml: the folders this process finds them
    in (without importing them here), so that ``-I -S`` (no environment, no site-packages
    ``.pth`` file run) still works."""
    import importlib.util

    folders = [os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))]
    for name in ("xacro", "yaml", "lxml"):
        spec = importlib.util.find_spec(name)
        if spec is not None and spec.origin:
            folder = os.path.dirname(os.path.dirname(os.path.abspath(spec.origin)))
            if folder not in folders:
                folders.append(folder)
    return folders
