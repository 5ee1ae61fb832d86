"""Which files ``txtool validate`` checks when given folders.

In a folder, recursively: ``*.urdf``, ``*.xacro`` and ``.xml`` files whose root is a robot
description. Passed over, as ruff and colcon do: hidden folders; folders holding
``COLCON_IGNORE``, ``AMENT_IGNORE`` or ``CATKIN_IGNORE`` (colcon's ``build/``, ``install/`` and
``log/`` carry one); what ``.gitignore`` files ignore (unless told not to); and what an exclude
pattern names (see :class:`Excludes`). A file named on the command line is always checked. A
device, FIFO or socket named ``*.urdf`` or ``*.xacro`` is passed on, so that loading refuses it (an
``.xml`` one is never opened to read its root, so passed over).
"""

from __future__ import annotations

import os
import stat
from collections.abc import Callable, Iterable, Iterator
from operator import attrgetter
from pathlib import Path

from lxml import etree

from txtool.io.packages import is_ignored
from txtool.io.xmlio import SAFE_OPTIONS, InputError
from txtool.lint.patterns import Excludes, absolute_folder

SUFFIXES = (".urdf", ".xacro")  # ``.urdf.xacro`` ends with ``.xacro``
XML_ROOTS = frozenset({"robot", "ros2_control", "transmission"})
SEMANTIC = (".srdf.xacro",)  # MoveIt's semantic description: no transmission loader reads it

# (path, is_folder, is_link) -> True when the path found in a folder walk must be passed over.
Skip = Callable[[str, bool, bool], bool]
_NAME = attrgetter("name")


def expand_paths(
    paths: Iterable[str],
    *,
    skip: Skip | None = None,
    gitignore: Callable[[str], bool] = lambda folder: True,
) -> Iterator[str]:
    """Files to lint, in a stable order: given files as they are, folders searched recursively.

    ``skip`` passes over what a folder walk finds (exclude patterns); ``gitignore`` says per
    folder given whether its walk respects ``.gitignore``. A given file is always checked,
    whatever its name and patterns; a missing one is passed on so that loading reports it.
    ``-`` (stdin) is passed on as well. Each file is produced once. A folder holding nothing to
    check is an :class:`~txtool.io.xmlio.InputError`: a CI step given the wrong folder must not
    pass silently.
    """
    seen: set[object] = set()
    for path in paths:
        if path != "-" and os.path.isdir(path):
            found = _walk(path, skip, GitIgnores(path) if gitignore(path) else None)
        else:
            found = iter([path])
        empty = True
        for candidate in found:
            empty = False
            key = _identity(candidate)
            if key not in seen:
                seen.add(key)
                yield candidate
        if empty:
            raise InputError(
                f"{path}: no .urdf, .xacro or robot .xml file to check in this folder (or its "
                "subfolders, leaving out ignored and excluded ones)"
            )


def _identity(path: str) -> object:
    """The file itself (device and inode, through links), else the path as given."""
    if path == "-":
        return path
    try:
        status = os.stat(path)
    except OSError:
        return os.path.abspath(path)
    return (status.st_dev, status.st_ino)


def _walk(folder: str, skip: Skip | None, gitignores: GitIgnores | None) -> Iterator[str]:
    for root, dirs, files in scan(folder):
        if is_ignored(root) and root != folder:
            dirs[:] = []
            continue
        kept = []
        for entry in sorted(dirs, key=_NAME):
            path = entry.path
            if entry.name.startswith(".") or is_ignored(path):
                continue
            if gitignores is not None and gitignores.ignored(path, True):
                continue
            if skip is not None and skip(path, True, entry.is_symlink()):
                continue
            kept.append(entry)
        dirs[:] = kept
        for entry in sorted(files, key=_NAME):
            path = entry.path
            if not is_candidate(path):
                continue
            if gitignores is not None and gitignores.ignored(path, False):
                continue
            if skip is None or not skip(path, False, entry.is_symlink()):
                yield path


def scan(top: str) -> Iterator[tuple[str, list[os.DirEntry[str]], list[os.DirEntry[str]]]]:
    """``os.walk(top)`` (top-down, unreadable folders passed over, linked folders listed but not
    entered) with the folder's entries instead of their names.

    An entry knows from the folder listing whether it is a symbolic link, where a name would
    cost a system call per file to ask (the configuration that applies depends on it).
    Changing the folder list in place prunes the walk, as with ``os.walk``.
    """
    stack = [top]
    while stack:
        root = stack.pop()
        try:
            with os.scandir(root) as listing:
                entries = list(listing)
        except OSError:
            continue
        dirs, files = [], []
        for entry in entries:
            try:
                is_dir = entry.is_dir()
            except OSError:
                is_dir = False
            (dirs if is_dir else files).append(entry)
        yield root, dirs, files
        stack.extend(entry.path for entry in reversed(dirs) if not entry.is_symlink())


class GitIgnores:
    """The ``.gitignore`` files that apply in a repository, read once per folder.

    A folder's own ``.gitignore`` applies to what lies below it, together with those of its
    ancestors up to the repository's top (the folder holding ``.git``); outside a repository
    only the folders walked count.
    """

    def __init__(self, start: str) -> None:
        self._by_folder: dict[str, tuple[Excludes, ...]] = {}
        self._absolute: dict[str, str] = {}
        start = os.path.abspath(start)
        self._top = next(
            (str(f) for f in (Path(start), *Path(start).parents) if (f / ".git").exists()), start
        )

    def ignored(self, path: str, is_folder: bool) -> bool:
        found = self._rules(absolute_folder(path, self._absolute))
        return bool(found) and any(rules.matches(path, is_folder) for rules in found)

    def _rules(self, folder: str) -> tuple[Excludes, ...]:
        if folder not in self._by_folder:
            parent = os.path.dirname(folder)
            inherited: tuple[Excludes, ...] = ()
            if folder != self._top and parent != folder:
                inherited = self._rules(parent)
            self._by_folder[folder] = inherited + _own_gitignore(folder)
        return self._by_folder[folder]


def _own_gitignore(folder: str) -> tuple[Excludes, ...]:
    try:
        text = Path(folder, ".gitignore").read_text(encoding="utf-8", errors="replace")
    except OSError:
        return ()
    lines = tuple(line for line in text.splitlines() if line.strip())
    return (Excludes(folder, lines),) if lines else ()


def is_candidate(path: str) -> bool:
    """A robot description by its name (not an SRDF), or an ``.xml`` whose root says it is one."""
    name = path.lower()
    if name.endswith(SUFFIXES):
        return not name.endswith(SEMANTIC)
    return name.endswith(".xml") and root_tag(Path(path)) in XML_ROOTS


def root_tag(path: Path) -> str | None:
    """The local name of the root element, reading no further than it; None if unreadable.

    Only a regular file is opened: a FIFO would block, a device never end.
    """
    try:
        if not stat.S_ISREG(os.stat(path).st_mode):
            return None
        with path.open("rb") as handle:
            events = etree.iterparse(handle, events=("start",), **SAFE_OPTIONS)
            for _, element in events:
                tag = element.tag
                return tag.rsplit("}", 1)[-1] if isinstance(tag, str) else None
    except (etree.XMLSyntaxError, OSError):
        return None
    return None
