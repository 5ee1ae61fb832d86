"""Which files ``txtool validate`` checks when given folders."""

from __future__ import annotations

import os
from collections.abc import Iterable, Iterator
from pathlib import Path

from lxml import etree

from txtool.io.xmlio import SAFE_OPTIONS, InputError

SUFFIXES = (".urdf", ".xacro")  # ``.urdf.xacro`` ends with ``.xacro``
XML_ROOTS = frozenset({"robot", "ros2_control", "transmission"})


def expand_paths(paths: Iterable[str]) -> Iterator[str]:
    """Files to lint, in a stable order: given files as they are, folders searched recursively.

    A given file is always checked, whatever its name; a missing one is passed on so that
    loading reports it. ``-`` (stdin) is passed on as well. Each file is produced once. A
    folder holding nothing to check is an :class:`~txtool.io.xmlio.InputError`: a CI step given
    the wrong folder must not pass silently.
    """
    seen: set[object] = set()
    for path in paths:
        found = _walk(path) if path != "-" and os.path.isdir(path) else iter([path])
        empty = True
        for candidate in found:
            empty = False
            key = _identity(candidate)
            if key not in seen:
                seen.add(key)
                yield candidate
        if empty:
            raise InputError(
                f"{path}: no .urdf, .xacro or robot .xml file in this folder (or its subfolders)"
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


def _walk(folder: str) -> Iterator[str]:
    for root, dirs, files in os.walk(folder):
        dirs[:] = sorted(d for d in dirs if not d.startswith("."))
        for name in sorted(files):
            path = os.path.join(root, name)
            if is_candidate(path):
                yield path


def is_candidate(path: str) -> bool:
    """A robot description by its name, or an ``.xml`` whose root says it is one."""
    name = path.lower()
    if name.endswith(SUFFIXES):
        return True
    return name.endswith(".xml") and root_tag(Path(path)) in XML_ROOTS


def root_tag(path: Path) -> str | None:
    """The local name of the root element, reading no further than it; None if unreadable."""
    try:
        with path.open("rb") as handle:
            events = etree.iterparse(handle, events=("start",), **SAFE_OPTIONS)
            for _, element in events:
                tag = element.tag
                return tag.rsplit("}", 1)[-1] if isinstance(tag, str) else None
    except (etree.XMLSyntaxError, OSError):
        return None
    return None
