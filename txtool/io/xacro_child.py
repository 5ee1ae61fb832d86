"""The xacro sandbox's child process: one request per line, one answer each.

Started by :mod:`txtool.io.xacro_sandbox` as ``python -I -S`` with an empty environment. For
each request it sets the limits the parent sent (CPU time, memory, no file written, no core
dump) and expands with a new :class:`txtool.io.xacro_guard.XacroGuard` installed (its budgets
of nodes and work are the file's own). What it imports is imported before the first
request's limits are set.

It ends as soon as the parent does, even in the middle of a request: it watches a pipe whose
other end only the parent holds (:func:`main`'s ``lifeline``), and its closing means the
parent is gone, however it ended (``kill -9`` included).
"""

from __future__ import annotations

import base64
import contextlib
import io
import json
import os
import signal
import sys
import threading
from typing import Any

from txtool.io import targets
from txtool.io import xacro as xacro_support
from txtool.io.xacro import expand_text
from txtool.io.xacro_eval import WorkLimit
from txtool.io.xacro_guard import MAX_NODES, NodeLimit, Refusal, XacroGuard
from txtool.io.xacro_sandbox import MAX_OUTPUT, PACKAGE_VARIABLES
from txtool.io.xmlio import MAX_BYTES, XacroError, XacroOptions


# The functions marked 'no cover' run only in the child the sandbox starts with no environment,
# no site and isolated (-I -S): no coverage measurement reaches it. tests/hardening drives them
# end to end (bounds, limits, lone surrogates, the parent's end).
def _set_limits(seconds: float, memory_mb: int) -> None:  # pragma: no cover
    """This request's limits: CPU time from now on, address space, no file written."""
    try:
        import resource
    except ImportError:  # not POSIX: the parent's timeout still holds
        return
    usage = resource.getrusage(resource.RUSAGE_SELF)
    cpu = int(usage.ru_utime + usage.ru_stime + seconds) + 2
    for limit, value in ((resource.RLIMIT_CPU, cpu), (resource.RLIMIT_FSIZE, 0),
                         (resource.RLIMIT_CORE, 0), (resource.RLIMIT_AS, memory_mb << 20)):
        _soft, hard = resource.getrlimit(limit)
        if hard != resource.RLIM_INFINITY:
            value = min(value, hard)
        with contextlib.suppress(ValueError, OSError):
            resource.setrlimit(limit, (value, hard))


def _line_of(path: str, needle: str | None, data: bytes | None = None) -> int:
    """The line of ``needle`` in ``data``, else in the file at ``path``; 1 if not found."""
    if not needle:
        return 1
    if data is None:
        try:
            with open(path, "rb") as handle:
                data = handle.read(MAX_BYTES)
        except OSError:
            return 1
    index = data.find(needle.encode("utf-8", "replace"))
    return data.count(b"\n", 0, index) + 1 if index >= 0 else 1


def _answer(header: dict[str, Any], text: str = "") -> None:  # pragma: no cover
    try:
        data = text.encode("utf-8")
    except UnicodeEncodeError as exc:  # a lone surrogate, made by an expression: not text
        character = f"U+{ord(text[exc.start]):04X}"
        header = {"error": f"the expansion holds {character}, a lone surrogate, which is no "
                  "character of an XML document"}
        data = b""
    if len(data) > MAX_OUTPUT:
        header, data = {"limit": f"{MAX_OUTPUT} bytes of output"}, b""
    header["size"] = len(data)
    out = sys.stdout.buffer
    out.write(json.dumps(header).encode("utf-8") + b"\n")
    out.write(data)
    out.flush()


def _end_with_parent(descriptor: int) -> None:  # pragma: no cover
    """End when the parent's end of the pipe ``descriptor`` closes (the parent ended).

    The pipe is set to signal this process (SIGIO, whose default action ends it) when it turns
    readable, which only its closing does: the kernel ends the child at once, with no thread
    (a thread's stack and malloc arena would count against the memory limit) and whatever
    the child is doing."""
    import fcntl
    import select

    if hasattr(fcntl, "F_SETOWN") and hasattr(os, "O_ASYNC"):
        signal.signal(signal.SIGIO, signal.SIG_DFL)
        fcntl.fcntl(descriptor, fcntl.F_SETOWN, os.getpid())
        flags = fcntl.fcntl(descriptor, fcntl.F_GETFL)
        fcntl.fcntl(descriptor, fcntl.F_SETFL, flags | os.O_ASYNC | os.O_NONBLOCK)
        if select.select([descriptor], [], [], 0)[0]:  # the parent ended before this was set
            os._exit(1)
        return

    def watch() -> None:  # elsewhere: a thread that waits for the end of file
        with contextlib.suppress(OSError):
            while os.read(descriptor, 1):
                pass
        os._exit(1)

    threading.Thread(target=watch, daemon=True).start()


def main(lifeline: int | None = None) -> None:  # pragma: no cover
    """The child: answer each request line with a header line and the expanded text;
    ``lifeline``: the pipe to watch for the parent's end."""
    if lifeline is not None:
        _end_with_parent(lifeline)
    sys.stderr = io.StringIO()  # xacro.warning(...) and friends: nobody reads it
    for line in sys.stdin.buffer:
        request = json.loads(line)
        sys.stderr = io.StringIO()
        header, text = _expand(request)
        _answer(header, text)
        if header.get("retire"):
            return


def _expand(request: dict[str, Any]) -> tuple[dict[str, Any], str]:
    xacro_support.MAX_READ = request["max_read"]  # the parent's: one limit, set in one place
    _set_limits(request["seconds"], request["memory"])
    for variable in PACKAGE_VARIABLES:  # what $(find) reads, as the parent has them now
        os.environ.pop(variable, None)
    os.environ.update(request["package_paths"])
    options = XacroOptions(
        args=tuple(tuple(pair) for pair in request["args"]),  # type: ignore[misc]
        pkg_dirs=tuple(request["pkg_dirs"]),
        pkg_paths=tuple(tuple(pair) for pair in request["pkg_paths"]),  # type: ignore[misc]
        env=tuple(request["env_names"]),
        readable=tuple(request["readable"]),
    )
    path, display = request["path"], request["display"]
    given = request.get("data")
    data = None if given is None else base64.b64decode(given)
    targets.forget_inputs()
    try:
        guard = XacroGuard(path, options, request["env"])
        text = expand_text(path, display, options, guard, data)
        # what it read (the top file and its includes): no output of the command replaces them
        return {"ok": True, "inputs": targets.inputs_read()}, text
    except Refusal as exc:
        return {"refused": exc.reason, "line": _line_of(path, exc.needle, data)}, ""
    except XacroError as exc:
        return {"error": exc.reason, "line": exc.line, "missing": exc.missing}, ""
    except (NodeLimit, WorkLimit, MemoryError, RecursionError) as exc:
        what = {NodeLimit: f"{MAX_NODES} XML nodes",
                MemoryError: f"{request['memory']} MiB of memory",
                RecursionError: "Python's recursion limit (macros or expressions nested too "
                "deep)", WorkLimit: str(exc)}
        return {"limit": what[type(exc)], "retire": True}, ""
    except Exception as exc:  # reported as the parent reports its own internal errors
        return {"error": f"internal error in the xacro sandbox: {type(exc).__name__}: {exc}",
                "retire": True}, ""
