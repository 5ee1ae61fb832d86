"""The controllers a launch file starts: its controller_manager ``spawner`` nodes.

ROS 1 (ros-controls/ros_control controller_manager/scripts/spawner @633c374): an XML launch file's
``<node pkg="controller_manager" type="spawner" args="a b"/>`` (or ``type="controller_manager"
args="spawn a b"``) loads the controllers and starts them in one strict switch, unless
``--stopped``. ROS 2 (ros-controls/ros2_control controller_manager/controller_manager/spawner.py
@53b9999): a Python launch file's ``Node(package="controller_manager", executable="spawner",
arguments=[...])`` or an XML launch file's ``<node pkg="controller_manager" exec="spawner"
args="..."/>`` loads, configures and activates each controller named, unless ``--inactive`` or
``--load-only`` (per controller after ``--controller NAME``, or for all).

What is read is what a launch file says for certain: literal names only (a name built from a
launch argument or substitution is unknown and left out), and no spawner that runs under a
condition (``condition=`` in Python, ``if``/``unless`` on the node or an enclosing group in XML),
since a file of alternatives starts only some of them. A Python launch file is parsed, never
run. Files larger than :data:`MAX_BYTES` or that do not parse give nothing.
"""

from __future__ import annotations

import ast
import os
import re
from collections.abc import Iterator
from dataclasses import dataclass

from txtool.io.xmlio import InputError, parse_bytes, read_regular

MAX_BYTES = 1 << 20
MAX_FILES = 200  # launch files looked at per package
LAUNCH_SUFFIXES = (".launch", ".launch.xml", ".launch.py", "_launch.py", ".xml", ".py")
_SPAWNERS = {"spawner", "spawner.py"}
# Options of either spawner that take a value (the next word, unless written NAME=VALUE).
_VALUED = {"-c", "--controller-manager", "-p", "--param-file", "-n", "--namespace", "-t",
           "--controller-type", "--controller-manager-timeout", "--switch-timeout",
           "--service-call-timeout", "--controller-ros-args", "--timeout", "--shutdown-timeout",
           "--wait-for"}
_NOT_STARTED = {"--stopped", "--inactive", "--load-only"}
_SUBSTITUTION = re.compile(r"\$\([^()]*(?:\([^()]*\)[^()]*)*\)")


@dataclass(frozen=True)
class Spawn:
    """One spawner of a launch file: the controllers it starts, at ``path:line``."""

    path: str
    line: int
    started: tuple[str, ...]


def started(words: list[str | None]) -> tuple[str, ...]:
    """The controllers a spawner's arguments start (``None``: a word not known statically).
    A word not known where a controller's name or an option may stand could be
    ``--inactive``: then nothing is known to start."""
    words = [None if word is None or "$" in word else word for word in words]
    if "--controller" in words:
        return _started_per_controller(words)
    names: list[str] = []
    skip = False
    for word in words:
        if word == "--ros-args":
            break
        if skip:
            skip = False
        elif word is None or word in _NOT_STARTED:
            return ()
        elif not word.startswith("-"):
            names.append(word)
        else:
            skip = word in _VALUED
    return tuple(names)


def _started_per_controller(words: list[str | None]) -> tuple[str, ...]:
    chunks: list[list[str | None]] = []
    for word in words:
        if word == "--controller":
            chunks.append([])
        elif chunks:
            chunks[-1].append(word)
    return tuple(chunk[0] for chunk in chunks
                 if chunk and chunk[0] and None not in chunk
                 and not _NOT_STARTED.intersection(w for w in chunk[1:] if w))


def spawns_in(path: str) -> list[Spawn]:
    """The unconditional spawners of the launch file at ``path`` (none when it is no launch
    file, is too large or does not parse)."""
    try:
        data = read_regular(path, MAX_BYTES)
    except (InputError, OSError):
        return []
    if path.endswith(".py"):
        return list(_python_spawns(path, data))
    return list(_xml_spawns(path, data))


def _python_spawns(path: str, data: bytes) -> Iterator[Spawn]:
    try:
        tree = ast.parse(data, filename=os.path.basename(path))
    except (SyntaxError, ValueError, RecursionError, MemoryError):
        return
    for node in ast.walk(tree):
        if not isinstance(node, ast.Call) or _called(node.func) != "Node":
            continue
        keywords = {k.arg: k.value for k in node.keywords if k.arg}
        if ("condition" in keywords or _text(keywords.get("package")) != "controller_manager"
                or _text(keywords.get("executable")) not in _SPAWNERS):
            continue
        arguments = keywords.get("arguments")
        if isinstance(arguments, ast.List | ast.Tuple):
            words = [_text(element) for element in arguments.elts]
            yield Spawn(path, node.lineno, started(words))


def _called(func: ast.expr) -> str:
    if isinstance(func, ast.Name):
        return func.id
    return func.attr if isinstance(func, ast.Attribute) else ""


def _text(value: ast.expr | None) -> str | None:
    if isinstance(value, ast.Constant) and isinstance(value.value, str):
        return value.value
    return None


def _xml_spawns(path: str, data: bytes) -> Iterator[Spawn]:
    try:
        root = parse_bytes(data, path).getroot()
    except (InputError, ValueError):
        return
    if root.tag != "launch":
        return
    for node in root.iter("node"):
        runs = node.get("type") or node.get("exec")
        if node.get("pkg") != "controller_manager" or runs not in (*_SPAWNERS,
                                                                  "controller_manager"):
            continue
        if any(e.get("if") is not None or e.get("unless") is not None
               for e in (node, *node.iterancestors())):
            continue
        # A substitution is one unknown word, whatever spaces it holds: $(arg name)
        words: list[str | None] = list(_SUBSTITUTION.sub("$", node.get("args") or "").split())
        if runs == "controller_manager":  # ROS 1's ``controller_manager spawn a b``
            if words[:1] != ["spawn"]:
                continue
            words = words[1:]
        yield Spawn(path, node.sourceline or 1, started(words))


def launch_files(package: str) -> list[str]:
    """The launch files of the package folder ``package`` (its ``launch`` folder, at any
    depth), in path order, at most :data:`MAX_FILES`."""
    top = os.path.join(package, "launch")
    found: list[str] = []
    for folder, subfolders, files in os.walk(top):
        subfolders[:] = sorted(s for s in subfolders if not s.startswith("."))
        found += [os.path.join(folder, f) for f in sorted(files)
                  if f.endswith(LAUNCH_SUFFIXES) and not f.startswith(".")]
        if len(found) >= MAX_FILES:
            break
    return found[:MAX_FILES]
