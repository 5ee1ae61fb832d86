"""What a ``package.xml`` says about the programs that read a package's robot files.

Two things, both read with the safe XML parser (no entities, DTD or network):

* the enclosing package's build system (REP 140 formats 1-3): ``<buildtool_depend>catkin``
  makes a ROS 1 package; ``<export><build_type>ament_cmake`` (or ``ament_python``), or a
  ``<buildtool_depend>ament_cmake``, a ROS 2 one (:func:`package_of`);
* the transmission types packages register with pluginlib: a package exports
  ``<export><transmission_interface plugin="${prefix}/plugins.xml"/>``, and that library
  description lists ``<class name=... type=... base_class_type="transmission_interface::...">``
  (pluginlib looks a class up by its ``name``, else its ``type``). Such a type is a known type
  wherever its package can be found: in the workspace or repository the file belongs to, on
  ``AMENT_PREFIX_PATH`` (``<prefix>/share/<pkg>``) or ``ROS_PACKAGE_PATH``
  (:func:`exported_transmission_types`).

Package folders are found as ``$(find pkg)`` finds them (:mod:`txtool.io.packages`).
"""

from __future__ import annotations

import os
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

from lxml import etree

from txtool.io.packages import crawl, enclosing_manifest, workspace_roots
from txtool.io.xmlio import InputError, local, parse_bytes, read_regular

MAX_MANIFEST = 1024 * 1024
# The base classes of ros_control's and ros2_control's transmission plugins
# (transmission_interface::TransmissionLoader in both; RequisiteProvider in ROS 1).
BASE_PREFIX = "transmission_interface::"
ROS1_BUILD = frozenset({"catkin"})
ROS2_BUILD = frozenset({"ament_cmake", "ament_python"})


@dataclass(frozen=True)
class PackageInfo:
    """The package a file belongs to: its name, manifest and build system."""

    name: str
    manifest: str
    format: int
    build_type: str | None  # "catkin", "ament_cmake", "ament_python" or None when unsaid
    # The manifest names build types of both generations (REP 149 conditions on
    # $ROS_VERSION): one source tree built under ROS 1 and ROS 2.
    both: bool = False

    @property
    def ros1(self) -> bool:
        return self.build_type in ROS1_BUILD

    @property
    def ros2(self) -> bool:
        return self.build_type in ROS2_BUILD


def read_small(path: str, limit: int = MAX_MANIFEST) -> bytes | None:
    """The bytes of a regular file of at most ``limit`` bytes, else None: a package.xml or a
    plugin description a pull request made a FIFO or a device is passed over, never read."""
    try:
        return read_regular(path, limit)
    except (OSError, InputError):
        return None


def _read_manifest(path: Path) -> etree._Element | None:
    data = read_small(str(path))
    if data is None:
        return None
    try:
        return parse_bytes(data, str(path)).getroot()
    except InputError:
        return None


def _children(element: etree._Element, name: str) -> list[etree._Element]:
    return [c for c in element if isinstance(c.tag, str) and local(c) == name]


def _text(element: etree._Element) -> str:
    return (element.text or "").strip()


@lru_cache(maxsize=256)
def read_package(manifest: str) -> PackageInfo | None:
    """The :class:`PackageInfo` of one ``package.xml``; None when it is no readable manifest."""
    root = _read_manifest(Path(manifest))
    if root is None or local(root) != "package":
        return None
    names = _children(root, "name")
    try:
        version = int((root.get("format") or "1").strip())
    except ValueError:
        version = 1
    return PackageInfo(
        name=_text(names[0]) if names else "",
        manifest=manifest,
        format=version,
        build_type=_build_type(root),
        both=_both_generations(root),
    )


def _build_type(root: etree._Element) -> str | None:
    """``<export><build_type>`` first (REP 140, what colcon reads), then the build tool."""
    for export in _children(root, "export"):
        for element in _children(export, "build_type"):
            if _text(element):
                return _text(element)
    tools = [_text(e) for e in _children(root, "buildtool_depend")]
    for tool in tools:
        if tool in ROS1_BUILD or tool in ROS2_BUILD:
            return tool
    return None


def _both_generations(root: etree._Element) -> bool:
    named = {_text(e) for e in _children(root, "buildtool_depend")}
    for export in _children(root, "export"):
        named.update(_text(e) for e in _children(export, "build_type"))
    return bool(named & ROS1_BUILD) and bool(named & ROS2_BUILD)


def package_of(path: str) -> PackageInfo | None:
    """The package whose ``package.xml`` encloses ``path`` (nearest first), if any."""
    folder = os.path.dirname(os.path.abspath(path))
    return _package_in(folder)


@lru_cache(maxsize=1024)
def _package_in(folder: str) -> PackageInfo | None:
    manifest = enclosing_manifest(os.path.join(folder, "_"))
    return read_package(str(manifest)) if manifest is not None else None


@dataclass(frozen=True)
class ExportedType:
    """A transmission type a package registers with pluginlib."""

    name: str
    package: str
    description: str  # the plugin description file that lists it

    def describe(self) -> str:
        return f"exported by package '{self.package}' ({os.path.basename(self.description)})"


@lru_cache(maxsize=1024)
def exports_of(manifest: str) -> tuple[ExportedType, ...]:
    """The transmission types the package of ``manifest`` exports (none for most packages)."""
    head = read_small(manifest)
    if head is None:
        return ()
    if b"transmission_interface" not in head or b"plugin" not in head:
        return ()  # the common case, without an XML parse
    root = _read_manifest(Path(manifest))
    if root is None:
        return ()
    package = _text(_children(root, "name")[0]) if _children(root, "name") else ""
    folder = os.path.dirname(manifest)
    found: list[ExportedType] = []
    for export in _children(root, "export"):
        for element in _children(export, "transmission_interface"):
            plugin = (element.get("plugin") or "").strip().replace("${prefix}", folder)
            if plugin:
                found.extend(_classes(plugin, package))
    return tuple(found)


def _classes(description: str, package: str) -> list[ExportedType]:
    root = _read_manifest(Path(description))
    if root is None:
        return []
    libraries = [root] if local(root) == "library" else _children(root, "library")
    found = []
    for library in libraries:
        for element in _children(library, "class"):
            base = (element.get("base_class_type") or "").strip()
            name = (element.get("name") or element.get("type") or "").strip()
            if base.startswith(BASE_PREFIX) and name:
                found.append(ExportedType(name, package, description))
    return found


def _prefix_manifests(variable: str) -> Iterable[str]:
    for prefix in filter(None, os.environ.get(variable, "").split(os.pathsep)):
        share = os.path.join(prefix, "share")
        try:
            entries = sorted(os.scandir(share), key=lambda e: e.name)
        except OSError:
            continue
        for entry in entries:
            manifest = os.path.join(entry.path, "package.xml")
            if os.path.isfile(manifest):
                yield manifest


@lru_cache(maxsize=64)
def _exports_below(root: str) -> tuple[ExportedType, ...]:
    return tuple(t for manifest in crawl(root) for t in exports_of(str(manifest)))


def exported_transmission_types(near: str | None) -> Mapping[str, ExportedType]:
    """Every transmission type registered with pluginlib by a package of the workspace or
    repository holding ``near`` (or its package's neighbours), then of ``AMENT_PREFIX_PATH``
    and ``ROS_PACKAGE_PATH``; the first registration of a name wins."""
    found: dict[str, ExportedType] = {}
    roots: list[str] = []
    if near is not None:
        roots = workspace_roots(near)
        manifest = enclosing_manifest(near)
        if not roots and manifest is not None and len(manifest.parent.parts) > 2:
            roots = [str(manifest.parent.parent)]  # the package's siblings (never all of /)
    roots += [os.path.abspath(r) for r in
              filter(None, os.environ.get("ROS_PACKAGE_PATH", "").split(os.pathsep))]
    for root in roots:
        for exported in _exports_below(root):
            found.setdefault(exported.name, exported)
    for manifest in _env_manifests(os.environ.get("AMENT_PREFIX_PATH", "")):
        for exported in exports_of(manifest):
            found.setdefault(exported.name, exported)
    return found


@lru_cache(maxsize=8)
def _env_manifests(value: str) -> tuple[str, ...]:
    return tuple(_prefix_manifests("AMENT_PREFIX_PATH")) if value else ()


# The <gazebo> plugin files that name a program reading the robot's transmissions.
PLUGIN_MARKERS = (b"gazebo_ros_control.so", b"gazebo_ros2_control.so", b"ros2_control-system")
DESCRIPTION_SUFFIXES = (".urdf", ".xacro", ".gazebo")
MAX_SCANNED = 500


@lru_cache(maxsize=256)
def plugin_files(package_folder: str) -> tuple[str, ...]:
    """The robot description files of a package (``.urdf``, ``.xacro``, ``.gazebo``; at most
    :data:`MAX_SCANNED`, each within the manifest size limit) whose bytes name a ``<gazebo>``
    plugin that reads transmissions, in path order."""
    found: list[str] = []
    scanned = 0
    for folder, subfolders, files in os.walk(package_folder):
        subfolders[:] = sorted(d for d in subfolders if not d.startswith("."))
        for name in sorted(files):
            if not name.endswith(DESCRIPTION_SUFFIXES):
                continue
            scanned += 1
            if scanned > MAX_SCANNED:
                return tuple(found)
            path = os.path.join(folder, name)
            data = read_small(path)
            if data is None:
                continue
            if any(marker in data for marker in PLUGIN_MARKERS):
                found.append(path)
    return tuple(found)


def read_description(path: str) -> etree._Element | None:
    """A description file's root element, safely parsed; None when it cannot be read."""
    return _read_manifest(Path(path))
