"""Which files ``txtool validate`` checks when given folders.

In a folder, recursively: ``*.urdf``, ``*.xacro`` and ``.xml`` files whose root is a robot
description. Passed over, as ruff and colcon do: hidden folders; folders holding
``COLCON_IGNORE``, ``AMENT_IGNORE`` or ``CATKIN_IGNORE`` (colcon's ``build/``, ``install/`` and
``log/`` carry one); what ``.gitignore`` files ignore (unless told not to); and what an exclude
pattern names (see :class:`Excludes`). A file named on the command line is checked unless its
root element says it describes no robot (a launch file, a ``package.xml``, an SDF world: see
:func:`describes_robot`), whatever its name, or the caller passes it over (``--force-exclude``). A
device, FIFO or socket named ``*.urdf`` or ``*.xacro`` is passed on, so that loading refuses it (an
``.xml`` one is never opened to read its root, so passed over).
"""

from __future__ import annotations

import errno
import os
import stat
from collections.abc import Callable, Iterable, Iterator
from operator import attrgetter
from pathlib import Path

from lxml import etree

from txtool.io.packages import IGNORE_MARKERS
from txtool.io.xmlio import SAFE_OPTIONS, InputError, read_regular
from txtool.lint.patterns import Excludes, absolute_folder

SUFFIXES = (".urdf", ".xacro")  # ``.urdf.xacro`` ends with ``.xacro``
XML_ROOTS = frozenset({"robot", "ros2_control", "transmission"})
SEMANTIC = (".srdf.xacro",)  # MoveIt's semantic description: no transmission loader reads it
# A xacro library may have any root (``<root xmlns:xacro=...>``): its namespace says what it is.
XACRO_NAMESPACES = frozenset({"http://www.ros.org/wiki/xacro", "http://ros.org/wiki/xacro"})

# (path, is_folder, is_link) -> True when the path found in a folder walk must be passed over.
Skip = Callable[[str, bool, bool], bool]
_NAME = attrgetter("name")


# (path, reason): something a walk could not read; reported as one line, the walk goes on.
Report = Callable[[str, str], None]
# A .gitignore over this is refused unread: each of its lines is matched against every path.
MAX_GITIGNORE_BYTES = 256 * 1024


def expand_paths(
    paths: Iterable[str],
    *,
    skip: Skip | None = None,
    gitignore: Callable[[str], bool] = lambda folder: True,
    report: Report | None = None,
    pass_over: Callable[[str], bool] | None = None,
) -> Iterator[str]:
    """Files to lint, in a stable order: given files as they are, folders searched recursively.

    ``skip`` passes over what a folder walk finds (exclude patterns); ``gitignore`` says per
    folder given whether its walk respects ``.gitignore``. A given file is checked whatever its
    name and patterns, unless ``pass_over`` says otherwise; a missing one is passed on so that
    loading reports it.
    ``-`` (stdin) is passed on as well. Each file is produced once. A folder holding nothing to
    check is an :class:`~txtool.io.xmlio.InputError`: a CI step given the wrong folder must not
    pass silently. What a walk cannot read (a folder it may not list, a symbolic link that
    loops, a ``.gitignore`` that is no regular file) goes to ``report`` and the walk goes on
    (without ``report``: an :class:`~txtool.io.xmlio.InputError`).
    """
    tell = report or _raise
    seen: set[object] = set()
    for path in paths:
        if path != "-" and os.path.isdir(path):
            ignores = GitIgnores(path, tell) if gitignore(path) else None
            found = _walk(path, skip, ignores, tell)
        elif path != "-" and pass_over is not None and pass_over(path):
            continue
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


def _raise(path: str, reason: str) -> None:
    raise InputError(f"{path}: {reason}")


def _identity(path: str) -> object:
    """The file itself (device and inode, through links), else the path as given."""
    if path == "-":
        return path
    try:
        status = os.stat(path)
    except OSError:
        return os.path.abspath(path)
    return (status.st_dev, status.st_ino)


def _walk(
    folder: str, skip: Skip | None, gitignores: GitIgnores | None, report: Report
) -> Iterator[str]:
    for _root, dirs, files in scan(folder, report):
        kept = []
        for entry in sorted(dirs, key=_NAME):
            path = entry.path
            if entry.name.startswith("."):
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


def scan(
    top: str, report: Report | None = None
) -> Iterator[tuple[str, list[os.DirEntry[str]], list[os.DirEntry[str]]]]:
    """``os.walk(top)`` (top-down, linked folders listed but not entered) with the folder's
    entries instead of their names; a folder holding ``COLCON_IGNORE``, ``AMENT_IGNORE`` or
    ``CATKIN_IGNORE`` (``top`` aside) is passed over, known from its listing.

    An entry knows from the folder listing whether it is a symbolic link, where a name would
    cost a system call per file to ask (the configuration that applies depends on it).
    Changing the folder list in place prunes the walk, as with ``os.walk``. A folder that
    cannot be listed and a symbolic link that loops go to ``report`` (None: passed over).
    """
    stack = [top]
    while stack:
        root = stack.pop()
        try:
            with os.scandir(root) as listing:
                entries = sorted(listing, key=_NAME)
        except OSError as exc:
            if report is not None:
                report(root, f"cannot list this folder: {_reason(exc)}")
            continue
        if root != top and any(entry.name in IGNORE_MARKERS for entry in entries):
            continue
        dirs, files = [], []
        for entry in entries:
            try:
                is_dir = entry.is_dir()
            except OSError:
                is_dir = False
            if not is_dir and report is not None and entry.is_symlink() and _loops(entry.path):
                report(entry.path, "symbolic link loop (too many levels of symbolic links)")
                continue
            (dirs if is_dir else files).append(entry)
        yield root, dirs, files
        stack.extend(entry.path for entry in reversed(dirs) if not entry.is_symlink())


def _loops(path: str) -> bool:
    try:
        os.stat(path)
    except OSError as exc:
        return exc.errno == errno.ELOOP
    return False


def _reason(exc: OSError) -> str:
    return (exc.strerror or str(exc)).lower()


class GitIgnores:
    """The ``.gitignore`` files that apply in a repository, read once per folder.

    A folder's own ``.gitignore`` applies to what lies below it, together with those of its
    ancestors up to the repository's top (the folder holding ``.git``); outside a repository
    only the folders walked count.
    """

    def __init__(self, start: str, report: Report = _raise) -> None:
        self._by_folder: dict[str, tuple[Excludes, ...]] = {}
        self._absolute: dict[str, str] = {}
        self._report = report
        start = os.path.abspath(start)
        self._top = next(
            (str(f) for f in (Path(start), *Path(start).parents) if (f / ".git").exists()), start
        )

    def ignored(self, path: str, is_folder: bool) -> bool:
        found = self._rules(absolute_folder(path, self._absolute))
        return bool(found) and any(rules.matches(path, is_folder) for rules in found)

    def _rules(self, folder: str) -> tuple[Excludes, ...]:
        """The rules of ``folder`` and its ancestors up to the top, each folder read once
        (iteratively: a tree may be deeper than Python's recursion limit)."""
        chain = []
        while folder not in self._by_folder:
            chain.append(folder)
            parent = os.path.dirname(folder)
            if folder == self._top or parent == folder:
                break
            folder = parent
        inherited = self._by_folder.get(folder, ()) if folder not in chain else ()
        for each in reversed(chain):
            inherited = self._by_folder[each] = inherited + self._own(each)
        return inherited

    def _own(self, folder: str) -> tuple[Excludes, ...]:
        path = os.path.join(folder, ".gitignore")
        if not os.path.lexists(path):
            return ()
        try:  # a FIFO would block, a link to /dev/zero never end: regular files only
            text = read_regular(path, MAX_GITIGNORE_BYTES).decode("utf-8", "replace")
        except InputError as exc:
            reason = str(exc).removeprefix(f"{path}: ")
            shown = os.path.relpath(path)  # as the walk names files, when below this folder
            self._report(path if shown.startswith("..") else shown, reason)
            return ()
        lines = tuple(line for line in text.splitlines() if line.strip())
        return (Excludes(folder, lines),) if lines else ()


def is_candidate(path: str) -> bool:
    """A robot description by its name (not an SRDF), or an ``.xml`` whose root says it is one."""
    name = path.lower()
    if name.endswith(SUFFIXES):
        return not name.endswith(SEMANTIC)
    return name.endswith(".xml") and root_tag(Path(path)) in XML_ROOTS


def describes_robot(path: str) -> bool:
    """Whether a file named on the command line is one to check: False only when its root
    element is known and is no robot description's (``<launch>``, ``<package>``, ``<sdf>``...),
    unless the root declares the xacro namespace (a macro library may have any root). A file
    that cannot be read or parsed is one to check: loading it says what is wrong."""
    root = _root(Path(path))
    if root is None:
        return True
    return _local(root.tag) in XML_ROOTS or not XACRO_NAMESPACES.isdisjoint(root.nsmap.values())


def root_tag(path: Path) -> str | None:
    """The local name of the root element, reading no further than it; None if unreadable."""
    root = _root(path)
    return None if root is None else _local(root.tag)


def _local(tag: str) -> str:
    return tag.rsplit("}", 1)[-1]


def _root(path: Path) -> etree._Element | None:
    """The root element as its start tag reads (no children); None if unreadable.

    Only a regular file is opened: a FIFO would block, a device never end.
    """
    try:
        if not stat.S_ISREG(os.stat(path).st_mode):
            return None
        with path.open("rb") as handle:
            events = etree.iterparse(handle, events=("start",), **SAFE_OPTIONS)
            for _, element in events:
                return element if isinstance(element.tag, str) else None
    except (etree.XMLSyntaxError, OSError):
        return None
    return None
