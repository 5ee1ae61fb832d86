"""Which files of a folder walk are fragments: files that another checked file includes.

A fragment (``arm.transmission.xacro``, ``robot.gazebo.xacro``) is written for the scope of
the file that ``<xacro:include>``s it: it uses the properties and arguments its includer
defines, and xacro never reads it alone. Its includer's expansion checks it; expanded alone it
may fail ("name 'side' is not defined") where nothing is wrong (see TX002).

The includes are read without expanding anything, as xacro resolves them (ros/xacro
``xacro/__init__.py``, ``get_include_files`` and ``abs_filename_spec``): a relative name is
relative to the including file's folder, ``$(find pkg)`` is the package's folder (found as for
the expansion, see :func:`~txtool.io.packages.find_package`), ``$(dirname)`` the including
file's folder, and any other ``$(...)`` or ``${...}`` (``${side}_arm.transmission.xacro``)
stands for any text within one folder name, like the glob patterns xacro also takes. A name
whose file part is nothing but such placeholders and a suffix (``$(arg extras)``,
``${robot}.urdf.xacro``) could be any file and marks none.
"""

from __future__ import annotations

import os
import re
from collections.abc import Iterable, Iterator

from txtool.io.packages import PackageNotFound, find_package
from txtool.io.xmlio import MAX_BYTES, InputError, XacroOptions, is_xacro, read_regular

_COMMENT = re.compile(rb"<!--.*?-->", re.DOTALL)
# xacro takes <xacro:include> and a bare <include> (ros/xacro ``is_include``).
_INCLUDE = re.compile(rb"<(?:xacro:)?include\b[^>]*?\bfilename\s*=\s*(?:\"([^\"]*)\"|'([^']*)')")
_FIND = re.compile(r"^\$\(find\s+([\w.-]+)\s*\)")
_ARG = re.compile(r"\$\(arg\s+([\w.-]+)\s*\)")
_PLACEHOLDER = re.compile(r"\$\{[^}]*\}|\$\([^)]*\)|[*?]|\[[^\]/]*\]")
_ANY = "\0"  # a placeholder, until the name becomes a pattern
# $(find NAME) from a folder, with the options that say where packages are: the folder or None
Packages = dict[tuple[str, str, XacroOptions], "str | None"]


def fragments(work: Iterable[tuple[str, XacroOptions]], walked: Iterable[str]) -> frozenset[str]:
    """The ``walked`` files (as given) that a xacro file of ``work`` (path and the options
    its expansion takes) includes."""
    targets = {_key(path): path for path in walked if is_xacro(path)}
    if not targets:
        return frozenset()
    by_folder: dict[str, set[str]] = {}
    for key in targets:
        by_folder.setdefault(os.path.dirname(key), set()).add(key)
    found: set[str] = set()
    packages: Packages = {}
    for path, options in work:
        if not is_xacro(path) or path == "-":
            continue
        own = _key(path)
        for pattern in _included(path, options, packages):
            found.update(key for key in _matches(pattern, by_folder) if key != own)
    return frozenset(targets[key] for key in found)


def included_files(path: str, options: XacroOptions, limit: int = 200) -> list[str]:
    """The files ``path`` includes, directly or through other includes (existing files whose
    names hold no placeholder; at most ``limit``), in the order found."""
    packages: Packages = {}
    found: list[str] = []
    seen = {_key(path)}
    pending = [path]
    while pending and len(found) < limit:
        for name in _included(pending.pop(0), options, packages):
            if _ANY not in name and _key(name) not in seen and os.path.isfile(name):
                seen.add(_key(name))
                found.append(name)
                pending.append(name)
    return found[:limit]


def _key(path: str) -> str:
    return os.path.realpath(path)


def _included(path: str, options: XacroOptions, packages: Packages) -> Iterator[str]:
    """The included names of ``path``, absolute, placeholders marked :data:`_ANY`."""
    try:
        data = read_regular(path, MAX_BYTES)
    except InputError:
        return
    folder = os.path.dirname(os.path.abspath(path))
    for match in _INCLUDE.finditer(_COMMENT.sub(b"", data)):
        raw = (match.group(1) or match.group(2) or b"").decode("utf-8", "replace").strip()
        name = _resolved(raw, path, folder, options, packages)
        if name is not None and _names_a_file(os.path.basename(name)):
            yield name


def _names_a_file(base: str) -> bool:
    """Whether a file name holds more than placeholders and a suffix (``${name}.urdf.xacro``
    could be any robot)."""
    stem = base.replace(_ANY, "")
    for suffix in (".xacro", ".urdf", ".xml"):
        stem = stem.removesuffix(suffix)
    return bool(stem.strip("._-"))


def _resolved(
    name: str, path: str, folder: str, options: XacroOptions, packages: Packages
) -> str | None:
    find = _FIND.match(name)
    if find is not None:
        package = _package(find.group(1), path, folder, options, packages)
        if package is None:
            return None
        name = package + name[find.end():]
    given = dict(options.args)
    name = _ARG.sub(lambda arg: given.get(arg.group(1), arg.group(0)), name)
    name = _PLACEHOLDER.sub(_ANY, name.replace("$(dirname)", folder))
    if not os.path.isabs(name):
        name = os.path.join(folder, name)
    return os.path.normpath(name)


def _package(
    name: str, path: str, folder: str, options: XacroOptions, packages: Packages
) -> str | None:
    """``$(find name)`` for a file in ``folder``, looked up once per folder."""
    key = (name, folder, options)
    if key not in packages:
        try:
            packages[key] = find_package(name, near=path, pkg_paths=options.pkg_paths,
                                         pkg_dirs=options.pkg_dirs)
        except PackageNotFound:
            packages[key] = None
    return packages[key]


def _matches(pattern: str, by_folder: dict[str, set[str]]) -> Iterator[str]:
    """The walked files (by :func:`_key`) that ``pattern`` names."""
    first = pattern.find(_ANY)
    if first < 0:
        key = _key(pattern)
        if key in by_folder.get(os.path.dirname(key), ()):
            yield key
        return
    head = pattern[:first].rpartition(os.sep)[0]
    pattern = _key(head) + pattern[len(head):]
    one_name = f"[^{re.escape(os.sep)}]*"
    regex = re.compile(one_name.join(re.escape(part) for part in pattern.split(_ANY)) + r"\Z")
    folder = os.path.dirname(pattern)
    if _ANY in folder:
        candidates: Iterable[str] = (key for keys in by_folder.values() for key in keys)
    else:
        candidates = by_folder.get(folder, ())
    yield from (key for key in candidates if regex.match(key))
