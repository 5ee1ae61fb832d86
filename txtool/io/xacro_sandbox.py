"""Untrusted xacro expansion: a child process, an empty environment, bounded in every way.

The parent (:func:`expand_in_sandbox`) starts ``python -E -s`` with no environment variable
but the ROS package paths ``$(find)`` reads (``AMENT_PREFIX_PATH``, ``ROS_PACKAGE_PATH``,
``CMAKE_PREFIX_PATH``), sends the request on its standard input (the values of the variables
``xacro-env`` allows ride along in it) and reads back one JSON header line and the expanded
text. The child (:func:`main`) sets its limits before it reads the file:

- wall time: :data:`DEFAULT_TIMEOUT` seconds (``TXTOOL_XACRO_TIMEOUT``), the parent kills it
  then; CPU time the same, as a backstop;
- memory: :data:`DEFAULT_MEMORY_MB` MiB of address space (``TXTOOL_XACRO_MEMORY_MB``);
- nodes: :data:`MAX_NODES` XML nodes created by macro calls, blocks and includes (a macro
  fan-out is stopped while it grows, before memory runs out);
- output: :data:`MAX_OUTPUT` bytes of expanded text;
- no file may be written (``RLIMIT_FSIZE`` 0), no core dump.

and expands with :class:`txtool.io.xacro_guard.XacroGuard` installed. Exceeding a limit is one
line, ``path: xacro: expansion exceeded ... (a safety limit)``.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from typing import Any

from txtool.io.xmlio import MAX_BYTES, InputError, XacroOptions

DEFAULT_TIMEOUT = 30.0
DEFAULT_MEMORY_MB = 2048
MAX_NODES = 2_000_000
MAX_OUTPUT = MAX_BYTES
PACKAGE_VARIABLES = ("AMENT_PREFIX_PATH", "ROS_PACKAGE_PATH", "CMAKE_PREFIX_PATH")
_BOOT = "import sys; sys.path.insert(0, sys.argv[1]); from txtool.io.xacro_sandbox import main; main()"


class XacroLimit(InputError):
    """An untrusted expansion went past a safety limit."""

    def __init__(self, path: str, what: str) -> None:
        super().__init__(f"{path}: xacro: expansion exceeded {what} (a safety limit)")


def _limit_from_environment(name: str, default: float) -> float:
    value = os.environ.get(name)
    if value is None:
        return default
    try:
        number = float(value)
    except ValueError:
        number = -1.0
    if not number > 0:
        raise InputError(f"{name}={value!r}: expected a positive number")
    return number


def limits() -> tuple[float, int]:
    """(seconds, MiB) from ``TXTOOL_XACRO_TIMEOUT`` and ``TXTOOL_XACRO_MEMORY_MB``: the job's
    environment sets them, never a file in the repository."""
    seconds = _limit_from_environment("TXTOOL_XACRO_TIMEOUT", DEFAULT_TIMEOUT)
    memory = int(_limit_from_environment("TXTOOL_XACRO_MEMORY_MB", DEFAULT_MEMORY_MB))
    return seconds, memory


def expand_in_sandbox(path: str, display: str, options: XacroOptions) -> str:
    """The expanded text of ``path``; :class:`XacroError` or :class:`XacroLimit` if none."""
    from txtool.io.xacro import XacroError

    seconds, memory = limits()
    request = {
        "path": os.path.abspath(path), "display": display,
        "args": options.args, "pkg_dirs": options.pkg_dirs, "pkg_paths": options.pkg_paths,
        "env_names": options.env,
        "env": {name: os.environ[name] for name in options.env if name in os.environ},
        "seconds": seconds, "memory": memory,
    }
    source_root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    environment = {k: os.environ[k] for k in PACKAGE_VARIABLES if k in os.environ}
    child = subprocess.Popen(
        [sys.executable, "-E", "-s", "-X", "utf8", "-c", _BOOT, source_root],
        stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL,
        env=environment, close_fds=True,
    )
    try:
        output, _ = child.communicate(json.dumps(request).encode("utf-8"), timeout=seconds)
    except subprocess.TimeoutExpired:
        child.kill()
        child.communicate()
        raise XacroLimit(display, f"{seconds:g} seconds") from None
    except BaseException:
        child.kill()
        child.wait()
        raise
    header, _, text = output.partition(b"\n")
    try:
        reply = json.loads(header)
    except ValueError:
        raise XacroLimit(display, f"{memory} MiB of memory, or stopped abnormally "
                         f"(exit status {child.returncode})") from None
    if "limit" in reply:
        raise XacroLimit(display, reply["limit"])
    if "error" in reply:
        raise XacroError(display, reply["error"], reply.get("line", 1))
    if len(text) > MAX_OUTPUT:
        raise XacroLimit(display, f"{MAX_OUTPUT} bytes of output")
    return text.decode("utf-8")


# -- the child ------------------------------------------------------------------------------

def _set_limits(seconds: float, memory_mb: int) -> None:
    try:
        import resource
    except ImportError:  # not POSIX: the parent's timeout still holds
        return
    cpu = int(seconds) + 1
    for limit, value in ((resource.RLIMIT_CPU, cpu), (resource.RLIMIT_FSIZE, 0),
                         (resource.RLIMIT_CORE, 0), (resource.RLIMIT_AS, memory_mb << 20)):
        soft, hard = resource.getrlimit(limit)
        if hard != resource.RLIM_INFINITY:
            value = min(value, hard)
        try:
            resource.setrlimit(limit, (value, hard))
        except (ValueError, OSError):
            pass


def _count_clones() -> None:
    """Count the nodes xacro creates (cloneNode for macro bodies and blocks, parsed includes)."""
    import xml.dom.minidom as minidom

    from txtool.io.xacro_guard import NodeLimit

    original = minidom._clone_node  # type: ignore[attr-defined]
    budget = MAX_NODES

    def clone(node: Any, deep: bool, new_owner: Any) -> Any:
        nonlocal budget
        budget -= 1
        if budget < 0:
            raise NodeLimit
        return original(node, deep, new_owner)

    minidom._clone_node = clone  # type: ignore[attr-defined]


def _line_of(path: str, needle: str | None) -> int:
    if not needle:
        return 1
    try:
        with open(path, "rb") as handle:
            data = handle.read(MAX_BYTES)
    except OSError:
        return 1
    index = data.find(needle.encode("utf-8", "replace"))
    return data.count(b"\n", 0, index) + 1 if index >= 0 else 1


def _answer(header: dict[str, Any], text: str = "") -> None:
    out = sys.stdout.buffer
    out.write(json.dumps(header).encode("utf-8") + b"\n")
    out.write(text.encode("utf-8"))
    out.flush()


def main() -> None:
    """The child: read the request, expand under the guard, answer header + text."""
    import io

    request = json.loads(sys.stdin.buffer.read())
    _set_limits(request["seconds"], request["memory"])
    sys.stderr = io.StringIO()  # xacro.warning(...) and friends: nobody reads it
    from txtool.io.xacro import XacroError, expand_text
    from txtool.io.xacro_guard import NodeLimit, Refusal, XacroGuard

    options = XacroOptions(
        args=tuple(tuple(pair) for pair in request["args"]),  # type: ignore[misc]
        pkg_dirs=tuple(request["pkg_dirs"]),
        pkg_paths=tuple(tuple(pair) for pair in request["pkg_paths"]),  # type: ignore[misc]
        env=tuple(request["env_names"]),
    )
    path, display = request["path"], request["display"]
    _count_clones()
    try:
        guard = XacroGuard(path, options, request["env"])
        text = expand_text(path, display, options, guard)
    except Refusal as exc:
        _answer({"error": exc.reason, "line": _line_of(path, exc.needle)})
        return
    except XacroError as exc:
        _answer({"error": exc.reason, "line": exc.line})
        return
    except (NodeLimit, MemoryError, RecursionError) as exc:
        what = {NodeLimit: f"{MAX_NODES} XML nodes", MemoryError: f"{request['memory']} MiB "
                "of memory", RecursionError: "Python's recursion limit (macros nested too deep)"}
        _answer({"limit": what[type(exc)]})
        return
    except Exception as exc:  # reported as the parent reports its own internal errors
        _answer({"error": f"internal error in the xacro sandbox: {type(exc).__name__}: {exc}"})
        return
    if len(text.encode("utf-8")) > MAX_OUTPUT:
        _answer({"limit": f"{MAX_OUTPUT} bytes of output"})
        return
    _answer({"ok": True}, text)
