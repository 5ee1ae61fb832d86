"""Where ``$(find pkg)`` points: ROS packages found the way the real xacro finds them.

The order, first match wins:

1. ``--pkg-path NAME:=DIR`` (command line, then configuration): DIR, as given;
2. ``--pkg-dir DIR`` (command line, then configuration): the package below DIR (DIR itself
   included) whose ``package.xml`` has ``<name>NAME</name>``. A folder that merely is called
   NAME is not the package;
3. ``AMENT_PREFIX_PATH``, as ROS 2 xacro resolves it: ``substitution_args._eval_find`` calls
   ``ament_index_python.get_package_share_directory`` (ros/xacro, branch ros2,
   xacro/substitution_args.py), which takes the first prefix, in order, holding the marker
   ``PREFIX/share/ament_index/resource_index/packages/NAME`` and answers ``PREFIX/share/NAME``
   (ament/ament_index, ament_index_python/packages.py ``get_package_share_directory``,
   resources.py ``get_resource``; search_paths.py ``get_search_paths`` drops prefixes that do
   not exist). So in a sourced colcon workspace a package resolves to its install space, not
   to its sources, as it does when the robot is launched;
4. ``ROS_PACKAGE_PATH``, as ROS 1 xacro resolves it (roslaunch's ``$(find)`` asks rospkg's
   ``RosPack.get_path``): each folder crawled for ``package.xml`` files, named by their
   ``<name>``, the first folder of the variable winning (ros-infrastructure/rospkg,
   src/rospkg/rospack.py ``list_by_path`` and ``ManifestManager._update_location_cache``).
   rospkg passes over folders holding ``CATKIN_IGNORE`` or ``rospack_nosubdirs``, and follows
   symbolic links;
5. with no sourced environment naming it: the package whose ``package.xml`` encloses the file
   being expanded, then every package of the workspace or repository the file belongs to:
   below the nearest ancestor holding ``.git``, and below the ``src`` folder of a
   colcon/catkin workspace (as ``colcon build`` would find them). A workspace is known by the
   marks its build tools leave beside ``src`` (:func:`is_workspace`), never by the name ``src``
   alone: a clone in ``~/src/robot`` is not a workspace of everything in ``~/src``;
6. ``CMAKE_PREFIX_PATH``: ``<prefix>/share/<pkg>`` holding a ``package.xml`` (where catkin and
   colcon install packages; a fallback of txtool's, which neither xacro reads).

Crawls other than ROS_PACKAGE_PATH's skip folders holding ``COLCON_IGNORE``, ``AMENT_IGNORE``
or ``CATKIN_IGNORE`` (colcon's ``build/``, ``install/`` and ``log/`` carry one; a folder given
with ``--pkg-dir`` is crawled even if it carries one itself). Every crawl skips hidden
folders, follows symbolic links (each real folder once), does not descend into a package
(packages do not nest) and stops after :data:`MAX_FOLDERS` folders, so a file in a huge tree
costs a bounded look.

For an untrusted expansion (``confine``, the folders the command line names), the crawls of
the repository and of the configuration's ``pkg-dirs`` follow no link out of the folder
crawled, and :func:`locate_package` says whether the package came from outside the checkout's
say (the command line, the ROS environment): only such a package may widen what is read.
"""

from __future__ import annotations

import os
import re
from collections.abc import Iterator, Mapping
from dataclasses import dataclass, field
from functools import lru_cache
from pathlib import Path

from txtool.io.xmlio import InputError, read_regular

IGNORE_MARKERS = ("COLCON_IGNORE", "AMENT_IGNORE", "CATKIN_IGNORE")
ROSPKG_MARKERS = ("CATKIN_IGNORE", "rospack_nosubdirs")  # rospkg's list_by_path
MAX_FOLDERS = 20_000
AMENT_INDEX = os.path.join("share", "ament_index", "resource_index", "packages")
# ament_index_python's get_package_prefix refuses other names (REP 127, with its exemptions).
_AMENT_NAME = re.compile(r"[a-zA-Z0-9][a-zA-Z0-9_-]+", re.ASCII)
_NAME = re.compile(rb"<name>\s*([^<\s]+)\s*</name>")
_COMMENT = re.compile(rb"<!--.*?-->", re.DOTALL)
MANIFEST_BYTES = 1024 * 1024  # a package.xml is a few KiB; a larger file is no manifest


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
    """The ``<name>`` of a ``package.xml`` (read as bytes, no XML parser: it may be hostile).

    The first ``<name>`` outside comments in the file's first 64 KiB: in every package.xml
    format it is a child of ``<package>`` written before any ``<export>``.
    """
    try:
        head = read_regular(str(manifest), MANIFEST_BYTES)[: 64 * 1024]
    except (OSError, InputError):
        return None  # not a regular file of a manifest's size (a FIFO would block)
    match = _NAME.search(_COMMENT.sub(b"", head))
    return match.group(1).decode("utf-8", "replace") if match else None


def folder_package_name(folder: str | Path) -> str | None:
    """The package ``folder`` is: the ``<name>`` of its ``package.xml``; None if it is none.

    A folder is a ROS package by its manifest, never by its own name: colcon, catkin, rospkg
    and ament all name a package by ``package.xml``'s ``<name>``.
    """
    return package_name(Path(folder) / "package.xml")


def is_ignored(folder: str, markers: tuple[str, ...] = IGNORE_MARKERS) -> bool:
    return any(os.path.exists(os.path.join(folder, marker)) for marker in markers)


def crawl(
    root: str, markers: tuple[str, ...] = IGNORE_MARKERS, *, skip_ignored_root: bool = True,
    confined: bool = False,
) -> Iterator[Path]:
    """``package.xml`` files below ``root`` (root itself included), not inside a package;
    ``confined``: none reached through a link that leads out of ``root``."""
    budget = MAX_FOLDERS
    stack = [root]
    seen: set[str] = set()
    inside = os.path.realpath(root)
    while stack and budget > 0:
        folder = stack.pop()
        real = os.path.realpath(folder)
        if real in seen:  # a symbolic link back up, or two links to one folder
            continue
        if confined and not is_within(real, inside):
            continue
        seen.add(real)
        budget -= 1
        if is_ignored(folder, markers) and (skip_ignored_root or folder != root):
            continue
        manifest = os.path.join(folder, "package.xml")
        if os.path.isfile(manifest):
            yield Path(manifest)
            continue
        try:
            entries = sorted(os.scandir(folder), key=lambda e: e.name, reverse=True)
        except OSError:
            continue
        stack.extend(e.path for e in entries if not e.name.startswith(".") and _is_dir(e))


def is_within(real: str, folder: str) -> bool:
    """Whether the resolved path ``real`` is the resolved ``folder`` or below it: by path
    components, so that ``/home/u/repo-old`` is not inside ``/home/u/repo``."""
    return real == folder or real.startswith(folder.rstrip(os.sep) + os.sep)


def _is_dir(entry: os.DirEntry[str]) -> bool:
    try:
        return entry.is_dir()  # through symbolic links, as colcon and rospkg crawl
    except OSError:
        return False


@lru_cache(maxsize=64)
def packages_below(
    root: str, markers: tuple[str, ...] = IGNORE_MARKERS, skip_ignored_root: bool = True,
    confined: bool = False,
) -> Mapping[str, str]:
    """Package name -> folder for every package below ``root`` (first found wins)."""
    found: dict[str, str] = {}
    for manifest in crawl(root, markers, skip_ignored_root=skip_ignored_root, confined=confined):
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
    roots += [str(c) for c in ancestors if c.name == "src" and is_workspace(c.parent)][:1]
    if len(roots) == 2 and not Path(roots[0]).is_relative_to(roots[1]):
        return roots[:1]  # the repository holds the workspace: one crawl covers both
    return roots


# What the build tools leave in a workspace's top folder, beside ``src``: colcon puts a
# COLCON_IGNORE in each folder it creates (build, install, log); catkin_make writes
# .catkin_workspace; catkin_tools' `catkin init` makes .catkin_tools; catkin's devel space
# holds a .catkin file.
WORKSPACE_MARKS = (
    os.path.join("build", "COLCON_IGNORE"), os.path.join("install", "COLCON_IGNORE"),
    os.path.join("log", "COLCON_IGNORE"), ".catkin_workspace", ".catkin_tools",
    os.path.join("devel", ".catkin"),
)


def is_workspace(folder: Path) -> bool:
    """Whether ``folder`` is the top folder of a colcon or catkin workspace: a ``src`` folder
    and one of the marks its build tools leave (:data:`WORKSPACE_MARKS`)."""
    return (folder / "src").is_dir() and any(
        os.path.lexists(folder / mark) for mark in WORKSPACE_MARKS)


def find_package(
    name: str,
    *,
    near: str | None,
    pkg_paths: tuple[tuple[str, str], ...] = (),
    pkg_dirs: tuple[str, ...] = (),
) -> str:
    """The folder of package ``name`` for a file at ``near``; :class:`PackageNotFound` if none."""
    return locate_package(name, near=near, pkg_paths=pkg_paths, pkg_dirs=pkg_dirs)[0]


def locate_package(
    name: str,
    *,
    near: str | None,
    pkg_paths: tuple[tuple[str, str], ...] = (),
    pkg_dirs: tuple[str, ...] = (),
    confine: tuple[str, ...] | None = None,
) -> tuple[str, bool]:
    """(folder, given): :func:`find_package`'s answer, and whether it came from outside the
    repository's say (``--pkg-dir``/``--pkg-path``, listed in ``confine``, or the ROS
    environment). With ``confine`` (an untrusted expansion), the other crawls follow no link
    out of the folder they crawl."""
    search = Search(name)
    trusted = None if confine is None else {os.path.abspath(f) for f in confine}
    for pkg, folder in pkg_paths:
        if pkg == name:
            return folder, trusted is None or os.path.abspath(folder) in trusted
    if pkg_paths:
        search.looked.append("--pkg-path " + ", ".join(pkg for pkg, _ in pkg_paths))
    hit = _in_pkg_dirs(name, pkg_dirs, search, trusted)
    if hit is not None:
        return hit
    found = _in_ament_index(name, search) or _in_package_path(name, search)
    if found is not None:
        return found, True
    found = _near_file(name, near, search, trusted is not None) if near is not None else None
    if found is not None:
        return found, trusted is None
    return _in_cmake_prefixes(name, search) or _raise(name, search), True


def _in_pkg_dirs(name: str, roots: tuple[str, ...], search: Search,
                 trusted: set[str] | None) -> tuple[str, bool] | None:
    for root in roots:
        given = trusted is None or os.path.abspath(root) in trusted
        hit = packages_below(root, IGNORE_MARKERS, False, not given).get(name)
        if hit:
            return hit, given
        search.looked.append(f"--pkg-dir {root}{_namesake(root, name)}")
    return None


def _namesake(root: str, name: str) -> str:
    """Why a folder called ``name`` in ``root`` is not the package, for the message."""
    if not os.path.isdir(root):
        return " (no such folder)"
    folder = os.path.join(root, name)
    if not os.path.isdir(folder):
        return ""
    own = folder_package_name(folder)
    if own is None:
        return f" (its folder '{name}' holds no package.xml)"
    return f" (its folder '{name}' is package '{own}')"


def _prefixes(variable: str, search: Search, unit: str = "prefixes") -> list[str]:
    prefixes = [p for p in os.environ.get(variable, "").split(os.pathsep) if p]
    search.looked.append(f"{variable} ({len(prefixes)} {unit})" if prefixes
                         else f"{variable} (unset)")
    return prefixes


def _in_ament_index(name: str, search: Search) -> str | None:
    prefixes = _prefixes("AMENT_PREFIX_PATH", search)
    if not prefixes or not _AMENT_NAME.fullmatch(name):
        return None
    for prefix in prefixes:
        if os.path.isfile(os.path.join(prefix, AMENT_INDEX, name)):
            return os.path.join(prefix, "share", name)
    return None


def _in_package_path(name: str, search: Search) -> str | None:
    for root in _prefixes("ROS_PACKAGE_PATH", search, "folders"):
        hit = packages_below(os.path.abspath(root), ROSPKG_MARKERS).get(name)
        if hit:
            return hit
    return None


def _in_cmake_prefixes(name: str, search: Search) -> str | None:
    if not _AMENT_NAME.fullmatch(name):
        return None
    for prefix in _prefixes("CMAKE_PREFIX_PATH", search):
        candidate = os.path.join(prefix, "share", name)
        if folder_package_name(candidate) == name:
            return candidate
    return None


def _near_file(name: str, near: str, search: Search, confined: bool = False) -> str | None:
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
        hit = packages_below(root, IGNORE_MARKERS, True, confined).get(name)
        if hit:
            return hit
    return None


def _raise(name: str, search: Search) -> str:
    raise PackageNotFound(name, search.looked)
