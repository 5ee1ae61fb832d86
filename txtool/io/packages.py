"""Where ``$(find pkg)`` points: ROS packages found the way a ROS workspace finds them.

The order, first match wins:

1. ``--pkg-path NAME:=DIR`` (command line, then configuration);
2. ``--pkg-dir DIR``: DIR/NAME, or a package below DIR whose ``package.xml`` names it;
3. the package whose ``package.xml`` encloses the file being expanded;
4. every package of the workspace or repository the file belongs to: below the nearest
   ancestor holding ``.git``, else below the ``src`` folder of a colcon/catkin workspace;
5. ``AMENT_PREFIX_PATH`` (``<prefix>/share/<pkg>``, as ament_index does), ``ROS_PACKAGE_PATH``
   (folders crawled for packages, as rospack does) and ``CMAKE_PREFIX_PATH``
   (``<prefix>/share/<pkg>``, where catkin installs packages).

Crawls skip hidden folders and folders holding ``COLCON_IGNORE``, ``AMENT_IGNORE`` or
``CATKIN_IGNORE`` (colcon's ``build/``, ``install/`` and ``log/`` carry one), do not descend
into a package (packages do not nest), and stop after :data:`MAX_FOLDERS` folders, so a file in
a huge tree costs a bounded look. A package is named by the ``<name>`` of its ``package.xml``.
"""

from __future__ import annotations

import os
import re
from collections.abc import Iterator, Mapping
from dataclasses import dataclass, field
from functools import lru_cache
from pathlib import Path

IGNORE_MARKERS = ("COLCON_IGNORE", "AMENT_IGNORE", "CATKIN_IGNORE")
MAX_FOLDERS = 20_000
_NAME = re.compile(rb"<name>\s*([^<\s]+)\s*</name>")


class PackageNotFound(Exception):
    """``$(find NAME)`` found nothing; the message lists every place that was searched."""

    def __init__(self, name: str, looked: list[str]) -> None:
        where = "; ".join(looked) if looked else "nowhere"
        super().__init__(
            f"package '{name}' not found (looked in: {where}); "
            f"give --pkg-dir DIR or --pkg-path {name}:=DIR"
        )
        self.name = name
        self.looked = looked


@dataclass
class Search:
    """One lookup: where it looked, in order, for the message when nothing matches."""

    name: str
    looked: list[str] = field(default_factory=list)


def package_name(manifest: Path) -> str | None:
    """The ``<name>`` of a ``package.xml`` (read as bytes, no XML parser: it may be hostile)."""
    try:
        with manifest.open("rb") as handle:
            head = handle.read(64 * 1024)
    except OSError:
        return None
    match = _NAME.search(head)
    return match.group(1).decode("utf-8", "replace") if match else None


def is_ignored(folder: str) -> bool:
    return any(os.path.exists(os.path.join(folder, marker)) for marker in IGNORE_MARKERS)


def crawl(root: str) -> Iterator[Path]:
    """``package.xml`` files below ``root`` (root itself included), not inside a package."""
    budget = MAX_FOLDERS
    stack = [root]
    while stack and budget > 0:
        folder = stack.pop()
        budget -= 1
        if is_ignored(folder):
            continue
        manifest = os.path.join(folder, "package.xml")
        if os.path.isfile(manifest):
            yield Path(manifest)
            continue
        try:
            entries = sorted(os.scandir(folder), key=lambda e: e.name, reverse=True)
        except OSError:
            continue
        stack.extend(
            e.path for e in entries
            if not e.name.startswith(".") and e.is_dir(follow_symlinks=False)
        )


@lru_cache(maxsize=64)
def packages_below(root: str) -> Mapping[str, str]:
    """Package name -> folder for every package below ``root`` (first found wins)."""
    found: dict[str, str] = {}
    for manifest in crawl(root):
        name = package_name(manifest)
        if name and name not in found:
            found[name] = str(manifest.parent)
    return found


def enclosing_manifest(path: str) -> Path | None:
    """The ``package.xml`` of the package that holds ``path``, if any."""
    folder = Path(os.path.abspath(path)).parent
    for candidate in (folder, *folder.parents):
        manifest = candidate / "package.xml"
        if manifest.is_file():
            return manifest
    return None


def workspace_roots(path: str) -> list[str]:
    """The repository (``.git``) and the workspace ``src`` folder that ``path`` belongs to.

    Both, nearest first: in a colcon workspace each repository under ``src`` is often a git
    checkout of its own, and a package may ``$(find)`` one from its neighbour.
    """
    folder = Path(os.path.abspath(path)).parent
    ancestors = (folder, *folder.parents)
    roots = [str(c) for c in ancestors if (c / ".git").exists()][:1]
    roots += [str(c) for c in ancestors if c.name == "src"][:1]
    if len(roots) == 2 and not Path(roots[0]).is_relative_to(roots[1]):
        return roots[:1]  # the repository holds the workspace: one crawl covers both
    return roots


def _in_folders(name: str, roots: tuple[str, ...], search: Search, label: str) -> str | None:
    for root in roots:
        search.looked.append(f"{label} {root}")
        direct = os.path.join(root, name)
        if os.path.isdir(direct):
            return direct
        hit = packages_below(root).get(name)
        if hit:
            return hit
    return None


def _in_prefixes(name: str, variable: str, search: Search) -> str | None:
    value = os.environ.get(variable, "")
    prefixes = [p for p in value.split(os.pathsep) if p]
    if not prefixes:
        search.looked.append(f"{variable} (unset)")
        return None
    search.looked.append(f"{variable} ({len(prefixes)} prefixes)")
    for prefix in prefixes:
        candidate = os.path.join(prefix, "share", name)
        if os.path.isfile(os.path.join(candidate, "package.xml")):
            return candidate
    return None


def _in_package_path(name: str, search: Search) -> str | None:
    roots = [p for p in os.environ.get("ROS_PACKAGE_PATH", "").split(os.pathsep) if p]
    if not roots:
        search.looked.append("ROS_PACKAGE_PATH (unset)")
        return None
    search.looked.append(f"ROS_PACKAGE_PATH ({len(roots)} folders)")
    for root in roots:
        hit = packages_below(os.path.abspath(root)).get(name)
        if hit:
            return hit
    return None


def find_package(
    name: str,
    *,
    near: str | None,
    pkg_paths: tuple[tuple[str, str], ...] = (),
    pkg_dirs: tuple[str, ...] = (),
) -> str:
    """The folder of package ``name`` for a file at ``near``; :class:`PackageNotFound` if none."""
    search = Search(name)
    for pkg, folder in pkg_paths:
        if pkg == name:
            return folder
    if pkg_paths:
        search.looked.append("--pkg-path " + ", ".join(pkg for pkg, _ in pkg_paths))
    hit = _in_folders(name, pkg_dirs, search, "--pkg-dir")
    if hit:
        return hit
    if near is not None:
        hit = _near_file(name, near, search)
        if hit:
            return hit
    return (
        _in_prefixes(name, "AMENT_PREFIX_PATH", search)
        or _in_package_path(name, search)
        or _in_prefixes(name, "CMAKE_PREFIX_PATH", search)
        or _raise(name, search)
    )


def _near_file(name: str, near: str, search: Search) -> str | None:
    manifest = enclosing_manifest(near)
    if manifest is not None:
        own = package_name(manifest)
        search.looked.append(f"the enclosing package '{own}' ({manifest})")
        if own == name:
            return str(manifest.parent)
    roots = workspace_roots(near)
    if not roots and manifest is not None and len(manifest.parent.parts) > 2:
        roots = [str(manifest.parent.parent)]  # the package's siblings (never all of /)
    for root in roots:
        search.looked.append(f"the packages below {root}")
        hit = packages_below(root).get(name)
        if hit:
            return hit
    return None


def _raise(name: str, search: Search) -> str:
    raise PackageNotFound(name, search.looked)
