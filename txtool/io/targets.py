"""What an output file may replace, and the temporary files an interrupted write left.

A pull request chooses the names in its tree: it can put a symbolic link where a workflow
writes its report (``report.txt -> ~/.bashrc``), or make the report's name one of the robot
descriptions the run reads. :func:`refused_target` keeps reports, tables and plots off
both; inputs rewritten in place (``migrate --write``, ``convert --write``) go through
:func:`txtool.io.xmlio.replace_if_unchanged` instead.

Each file read as an input is remembered by its identity (device and inode) for the life of
the process, so that no output of the same command replaces it by any of its names.
"""

from __future__ import annotations

import contextlib
import os
import re
import stat
import time

# How txtool.io.xmlio.write_atomic names its temporary files (tempfile.mkstemp's eight
# characters between a prefix and a suffix), and how old one must be to count as left behind
# by a process that was killed: a write takes seconds, never an hour.
TEMPORARY = re.compile(r"\.txtool-[a-z0-9_]{8}\.tmp")
STALE_AFTER = 3600.0
# What a folder walk reads (txtool.lint.discover): no report is written over such a file.
INPUT_SUFFIXES = (".urdf", ".xacro", ".xml")

_inputs: set[tuple[int, int, int]] = set()
_swept: set[str] = set()


def remember_input(status: os.stat_result) -> None:
    """Note a file read as an input (its status from ``fstat`` of the open file)."""
    _inputs.add(_key(status))


def inputs_read() -> list[tuple[int, int, int]]:
    """The identities of the inputs read so far (a xacro expansion's child sends them back)."""
    return sorted(_inputs)


def remember_inputs(identities: list[tuple[int, int, int]] | list[list[int]]) -> None:
    """Note inputs another process read for this command (a xacro expansion's includes)."""
    _inputs.update((int(a), int(b), int(c)) for a, b, c in identities)


def forget_inputs() -> None:
    """Start a command: what earlier commands of this process read is not its input."""
    _inputs.clear()


def was_read(status: os.stat_result) -> bool:
    return _key(status) in _inputs


def _key(status: os.stat_result) -> tuple[int, int, int]:
    # The status-change time tells a file apart from a later one given the same inode.
    return status.st_dev, status.st_ino, status.st_ctime_ns


def refused_target(path: str, inputs: tuple[str, ...] = (), *, report: bool = True) -> str | None:
    """Why ``path`` may not receive a new output, or None. ``inputs`` are the paths named on
    the command line; a ``report`` (not a robot description) also keeps off every existing
    file with the suffix of one (what a folder walk reads, when the inputs ran in forks)."""
    linked = _linked_folder(path)
    if linked is not None:
        return (f"passes through the symbolic link {linked}; txtool writes a new output named "
                "by a relative path only inside real folders (name a folder outside the "
                "checkout, or an absolute path)")
    try:
        status = os.lstat(path)
    except OSError:
        return None  # a new name (or a folder that is not there: the write says so)
    if stat.S_ISLNK(status.st_mode):
        return ("is a symbolic link; txtool writes a new output only to a regular file or a "
                "new name, never through a link (remove the link or name another file)")
    if _names_an_input(path, status, inputs):
        return "is an input of this command; its output is not written over it"
    if report and path.lower().endswith(INPUT_SUFFIXES) and stat.S_ISREG(status.st_mode):
        return (f"is a robot description ({os.path.splitext(path)[1]}); txtool writes a "
                "report, table or plot only to a file of another kind")
    return None


def _linked_folder(path: str) -> str | None:
    """The first folder of a relative ``path`` that is a symbolic link (a checkout can hold
    ``reports -> /home/runner``), or None. An absolute path is the workflow's own choice."""
    if os.path.isabs(path):
        return None
    folders = path.replace(os.sep, "/").split("/")[:-1]
    for depth in range(1, len(folders) + 1):
        prefix = "/".join(folders[:depth])
        if folders[depth - 1] in ("", "."):
            continue
        try:
            if stat.S_ISLNK(os.lstat(prefix).st_mode):
                return prefix
        except OSError:
            return None  # missing: the write says so
    return None


def _names_an_input(path: str, status: os.stat_result, inputs: tuple[str, ...]) -> bool:
    if was_read(status):
        return True
    for named in inputs:
        if named == "-":
            continue
        with contextlib.suppress(OSError):
            if os.path.samefile(named, path):
                return True
    return False


def sweep_stale_temporaries(folder: str) -> None:
    """Remove what a killed write left in ``folder``: regular files of this user named as
    txtool names its temporary files and older than :data:`STALE_AFTER`. Nothing else, and
    each folder once per process."""
    key = os.path.abspath(folder)
    if key in _swept:
        return
    _swept.add(key)
    now = time.time()
    uid = os.geteuid()
    try:
        with os.scandir(folder) as listing:
            stale = [entry for entry in listing if TEMPORARY.fullmatch(entry.name)]
    except OSError:
        return
    for entry in stale:
        with contextlib.suppress(OSError):
            status = entry.stat(follow_symlinks=False)
            if (stat.S_ISREG(status.st_mode) and status.st_uid == uid
                    and now - status.st_mtime > STALE_AFTER):
                os.unlink(entry.path)
