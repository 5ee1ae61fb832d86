"""Controller configuration files (YAML) as the controller managers read them.

ROS 2 (``controller_manager`` of ros2_control): a node's parameters sit under
``NODE: ros__parameters:``; the manager's own node lists each controller as
``NAME: {type: PLUGIN}`` among its parameters, and a controller's parameters are its own node's
(``NAME: ros__parameters: ...``, or ``/**/NAME`` and namespaced keys), where it may name its
``type`` too. ROS 1
(``controller_manager`` of ros_control): the file is loaded onto the parameter server and a
controller is a namespace holding ``type`` (``NAME: {type: PLUGIN, joints: [...]}``, at any
depth of namespaces). Outside the ROS 2 manager's own list, a ``type`` is taken for a
controller's only when it names one (:func:`_names_a_controller`).

The text is read with PyYAML's safe loader only (no tags that build objects) and within
:data:`MAX_BYTES`; positions come from the safe loader's node tree (``yaml.compose`` with
``SafeLoader``, which builds no objects either).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from txtool.io.xmlio import InputError, read_regular

MAX_BYTES = 1 << 20  # a controller configuration is a few kilobytes


@dataclass(frozen=True)
class Entry:
    """One controller of a file: its name, type, parameters and where its name is written."""

    name: str
    type: str
    params: dict[str, Any] = field(compare=False)
    line: int
    column: int


@dataclass(frozen=True)
class ControllerFile:
    path: str
    generation: str  # "ros1" or "ros2"
    entries: tuple[Entry, ...]


def read_controller_file(path: str, data: bytes | None = None) -> ControllerFile | None:
    """The controllers of the YAML file at ``path``, or None when it defines none.

    Raises :class:`~txtool.io.xmlio.InputError` (``path:line: reason``) for a file that cannot
    be read or is not YAML.
    """
    import yaml  # only controller configurations need it

    if data is None:
        data = read_regular(path, MAX_BYTES)
    try:
        text = data.decode("utf-8")
        document = yaml.safe_load(text)
        node = yaml.compose(text, Loader=yaml.SafeLoader)
    except UnicodeDecodeError:
        raise InputError(f"{path}: not UTF-8 text") from None
    except RecursionError:  # PyYAML composes nested collections recursively
        raise InputError(f"{path}: nested too deeply to be a controller configuration") from None
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        where = f"{path}:{mark.line + 1}" if mark is not None else path
        reason = getattr(exc, "problem", None) or str(exc).splitlines()[0]
        raise InputError(f"{where}: not valid YAML: {reason}") from None
    if not isinstance(document, dict):
        return None
    positions = _positions(node)
    if _has_ros2_parameters(document):
        entries = _ros2_entries(document, positions)
        generation = "ros2"
    else:
        entries = list(_ros1_entries(document, (), positions))
        generation = "ros1"
    if not entries:
        return None
    return ControllerFile(path, generation, tuple(entries))


Positions = dict[tuple[str, ...], tuple[int, int]]


def _positions(node: Any) -> Positions:
    """Where each mapping key is written, by its path of keys (1-based line and column)."""
    found: Positions = {}
    stack = [((), node)]
    seen: set[int] = set()  # an alias is the node it names: each node once, or aliases of
    while stack:            # aliases would make the walk exponential in the file's size
        path, current = stack.pop()
        if current is None or current.id != "mapping" or id(current) in seen:
            continue
        seen.add(id(current))
        for key, value in current.value:
            if key.id != "scalar":
                continue
            here = (*path, str(key.value))
            found.setdefault(here, (key.start_mark.line + 1, key.start_mark.column + 1))
            stack.append((here, value))
    return found


def _has_ros2_parameters(document: dict[Any, Any]) -> bool:
    return any(isinstance(v, dict) and "ros__parameters" in v for v in document.values())


def _names_a_controller(type_: str) -> bool:
    """Whether a ``type`` outside the manager's own list names a controller plugin (a
    ``PACKAGE/CLASS`` with "controller" or "broadcaster" in it): other nodes' parameters have
    a ``type`` too (filter chains' ``filters/MeanFilter``)."""
    lowered = type_.lower()
    return "/" in type_ and ("controller" in lowered or "broadcaster" in lowered)


def _node_name(key: Any) -> str:
    """A node key's last name: ``/robot/controller_manager`` and ``/**/arm`` name
    ``controller_manager`` and ``arm``."""
    return str(key).rstrip("/").rsplit("/", 1)[-1]


def _ros2_entries(document: dict[Any, Any], positions: Positions) -> list[Entry]:
    own: dict[str, dict[str, Any]] = {}
    for key, value in document.items():
        if isinstance(value, dict) and isinstance(value.get("ros__parameters"), dict):
            own.setdefault(_node_name(key), value["ros__parameters"])
    entries = []
    for key, value in document.items():
        if _node_name(key) != "controller_manager" or not isinstance(value, dict):
            continue
        listed = value.get("ros__parameters")
        if not isinstance(listed, dict):
            continue
        for name, spec in listed.items():
            if not isinstance(spec, dict) or not isinstance(spec.get("type"), str):
                continue
            params = {k: v for k, v in spec.items() if k != "type"}
            params.update(own.get(str(name), {}))
            line, column = positions.get((str(key), "ros__parameters", str(name)), (1, 1))
            entries.append(Entry(str(name), spec["type"].strip(), params, line, column))
    # A controller may name its type among its own parameters instead: the spawner reads it
    # from the parameter file and sets NAME.type on the manager (ros-controls/ros2_control
    # controller_manager/controller_manager/controller_manager_services.py:498 @53b9999).
    listed = {entry.name for entry in entries}
    for key in document:
        name = _node_name(key)
        own_type = own.get(name, {}).get("type") if name != "controller_manager" else None
        if isinstance(own_type, str) and _names_a_controller(own_type) and name not in listed:
            listed.add(name)
            line, column = positions.get((str(key),), (1, 1))
            params = {k: v for k, v in own[name].items() if k != "type"}
            entries.append(Entry(name, own_type.strip(), params, line, column))
    return entries


def _ros1_entries(document: dict[Any, Any], path: tuple[str, ...], positions: Positions,
                  seen: set[int] | None = None):
    seen = set() if seen is None else seen
    for name, value in document.items():
        if not isinstance(value, dict) or id(value) in seen:
            continue  # an alias of a mapping already read (YAML anchors share it)
        seen.add(id(value))
        here = (*path, str(name))
        kind = value.get("type")
        if isinstance(kind, str) and _names_a_controller(kind):
            line, column = positions.get(here, (1, 1))
            yield Entry(str(name), kind.strip(), dict(value), line, column)
        else:
            yield from _ros1_entries(value, here, positions, seen)
