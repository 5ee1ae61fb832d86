"""What the language server says of controller configurations (TX5xx), without the protocol.

An opened robot file or controller YAML file belongs to a family of packages: its own package
and the packages beside it of the same stem (:func:`related`: ``rrbot_description``,
``rrbot_control``, ``rrbot_gazebo``). The family is checked as a ``txtool validate`` walk of
those packages pairs their files (:func:`txtool.lint.controller_files.controller_problems`):
each controller file is judged against the family's robot having most of the joints its
controllers claim. The editor's
buffers stand for the files it has open; the others are read from disk. Each finding is
placed in the controller file, at the controller's name, and in the robot file judged, at
each ``<joint>`` of its ``<transmission>`` or ``<ros2_control>`` (else the robot's own joint)
written literally in that file which the finding names.

The work is bounded: at most :data:`MAX_PACKAGES` packages, :data:`MAX_ROBOTS` robot files
and :data:`~txtool.lint.controller_files.MAX_SCANNED` YAML files per package.
"""

from __future__ import annotations

import itertools
import os
import re
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field

from txtool.commands.lsp_document import (
    Options,
    encode,
    is_robot_file,
    load_buffer,
    settings_for,
)
from txtool.io.controller_yaml import ControllerFile, read_controller_file
from txtool.io.xmlio import InputError, local, parse_bytes, read_regular
from txtool.lint.controller_files import (
    YAML_SUFFIXES,
    ControllerContext,
    Provision,
    controller_files_under,
    controllers_of,
    exported_controllers,
    forget_packages,
    judged,
    package_root,
    pick_robot,
    robot_provision,
    spawns_near,
)
from txtool.lint.discover import expand_paths
from txtool.lint.problem import Note, Problem

MAX_PACKAGES = 8  # packages of a family
MAX_ROBOTS = 16  # robot files of a family, the editor's buffers first


@dataclass
class Family:
    """The files of a family and the findings of its controller files, by path: every
    controller file and robot file found has an entry (empty when it has no finding), so that
    a finding fixed is cleared."""

    folders: list[str] = field(default_factory=list)
    controller_files: list[str] = field(default_factory=list)
    robots: list[str] = field(default_factory=list)
    findings: dict[str, list[Problem]] = field(default_factory=dict)


def is_controller_candidate(path: str) -> bool:
    """Whether the file may be a controller configuration (a YAML file)."""
    return path.endswith(YAML_SUFFIXES)


def family_folders(path: str) -> list[str]:
    """The package folders of the family of the file at ``path`` (absolute): its package and
    those beside it of its family (:func:`related`); none when it is in no package (its
    folder may be any folder: no walk starts there)."""
    package = package_root(path)
    if package is None:
        return []
    package = package.rstrip(os.sep) or os.sep
    name, parent = os.path.basename(package), os.path.dirname(package)
    try:
        names = sorted(os.listdir(parent))
    except OSError:
        names = []
    beside = [os.path.join(parent, other) for other in names
              if other != name and related(name, other)
              and os.path.isfile(os.path.join(parent, other, "package.xml"))]
    return [package, *beside[:MAX_PACKAGES - 1]]


def related(one: str, other: str) -> bool:
    """Whether two package names are of one family: one starts with the other's stem, its name
    without the last ``_`` part (``rrbot_description`` and ``rrbot_control``; ``ur_description``
    and ``ur_robot_driver``)."""
    def stem(name: str) -> str:
        return name.rpartition("_")[0] or name

    return one.startswith(stem(other) + "_") or other.startswith(stem(one) + "_")


def family_findings(path: str, buffers: Mapping[str, str], root: str, options: Options,
                    serves: Callable[[str], bool] = lambda folder: True) -> Family:
    """The TX5xx findings of the family of the file at ``path`` (absolute); ``buffers``: the
    text of each file the editor has open, by path; ``serves``: whether a package folder may
    be read (over TCP, only inside the client's folders)."""
    forget_packages()  # a package.xml may have come or gone since the last check
    folders = [folder for folder in family_folders(path) if serves(folder)]
    family = Family(folders)
    files = _controller_files(folders, buffers)
    family.controller_files = list(files)
    if not files:
        return family
    family.robots = _robots(folders, buffers)
    provisions = {robot: _provision(robot, buffers, root, options) for robot in family.robots}
    family.findings = {file: [] for file in [*family.controller_files, *family.robots]}
    for path, file in files.items():
        for problem, robot, joints in _judged(file, provisions, root, options):
            family.findings[path].append(problem)
            family.findings[robot].extend(_in_robot(problem, robot, joints, buffers))
    return family


def inside(path: str, folders: Sequence[str]) -> bool:
    return any(path.startswith(os.path.join(folder, "")) for folder in folders)


def _controller_files(folders: Sequence[str], buffers: Mapping[str, str]
                      ) -> dict[str, ControllerFile]:
    """The family's controller files by path: those on disk (an opened one read from its
    buffer) and the opened YAML buffers in its folders that define controllers."""
    found: dict[str, None] = {}
    for folder in folders:
        found.update(dict.fromkeys(controller_files_under(folder)))
    for path in buffers:
        if is_controller_candidate(path) and inside(path, folders):
            found[path] = None
    read = {path: _controllers(path, buffers) for path in found}
    return {path: file for path, file in read.items() if file is not None}


def _controllers(path: str, buffers: Mapping[str, str]) -> ControllerFile | None:
    """The controllers of the file, as its buffer (else the disk) holds them; None for no
    controller configuration, or one that cannot be read (as YAML) as it stands."""
    data = buffers[path].encode("utf-8") if path in buffers else None
    try:
        return read_controller_file(path, data)
    except InputError:
        return None


def _robots(folders: Sequence[str], buffers: Mapping[str, str]) -> list[str]:
    opened = [path for path, text in buffers.items() if inside(path, folders)
              and is_robot_file(path, text)]
    found: dict[str, None] = dict.fromkeys(opened)
    for folder in folders:
        walk = expand_paths([folder], report=lambda where, reason: None)
        try:
            found.update(dict.fromkeys(itertools.islice(walk, MAX_ROBOTS)))
        except InputError:  # a package holding no robot file (a *_control package)
            continue
    robots = [path for path in found if path in buffers or os.path.isfile(path)]
    return robots[:MAX_ROBOTS]


def _provision(robot: str, buffers: Mapping[str, str], root: str, options: Options
               ) -> Provision | None:
    try:
        settings = settings_for(robot, root, options)
        if robot not in buffers:
            return robot_provision(robot, settings)
        return robot_provision(robot, settings, load_buffer(robot, buffers[robot], settings))
    except (InputError, OSError):  # the robot's own diagnostics say why
        return None


def _judged(file: ControllerFile, provisions: dict[str, Provision | None], root: str,
            options: Options) -> list[tuple[Problem, str, list[str]]]:
    """The findings of the controller file, each with the robot judged and the joints of it
    the finding names."""
    path = file.path
    controllers = controllers_of(file, exported_controllers(package_root(path)))
    chosen = pick_robot(controllers, file.generation, provisions, near=path)
    provision = provisions.get(chosen) if chosen is not None else None
    if chosen is None or provision is None:
        return []
    try:
        settings = settings_for(path, root, options)
    except (InputError, OSError):  # a robot's diagnostics say why
        return []
    ctx = ControllerContext(path, chosen, file.generation, controllers, provision,
                            spawns_near(path, chosen))
    by_place = {(c.line, c.column): c for c in controllers}
    found = []
    for problem in judged(ctx, settings):
        controller = by_place.get((problem.line, problem.column))
        if controller is None:
            found.append((problem, chosen, []))
            continue
        joints = [joint for joint in controller.joints if f"'{joint}'" in problem.message]
        found.append((problem, chosen, joints))
    return found


def _in_robot(problem: Problem, robot: str, joints: list[str], buffers: Mapping[str, str]
              ) -> list[Problem]:
    """The finding placed in the robot file judged, at each joint it names written there,
    with the controller's place as the related one."""
    here = Note(problem.path, problem.line, problem.column, "the controller")
    message = f"{os.path.basename(problem.path)}:{problem.line}: {problem.message}"
    return [Problem(robot, line, column, problem.code, message, end_line=line,
                    end_column=column + len("<joint"), severity=problem.severity,
                    name=problem.name, fixable=False, related=(here,))
            for joint in joints for line, column in _joint_places(robot, joint, buffers)]


def _joint_places(robot: str, joint: str, buffers: Mapping[str, str]) -> list[tuple[int, int]]:
    """1-based (line, column) of each ``<joint name=JOINT>`` of a ``<transmission>`` or
    ``<ros2_control>`` written in the robot file as it stands (else of the robot's joint)."""
    try:
        data = (encode(buffers[robot])[0] if robot in buffers else read_regular(robot))
        tree = parse_bytes(data, robot)
    except InputError:
        return []
    text = buffers[robot] if robot in buffers else data.decode("utf-8", errors="replace")
    lines = text.splitlines()
    named = [e for e in tree.getroot().iter("{*}joint") if e.get("name") == joint]
    driving = [e for e in named if e.getparent() is not None
               and local(e.getparent()) in ("transmission", "ros2_control")]
    start = re.compile(r"<(?:[\w.-]+:)?joint\b[^>]*\bname\s*=\s*[\"']" + re.escape(joint))
    places = []
    for element in driving or named:
        line = element.sourceline or 1
        found = start.search(lines[line - 1]) if line <= len(lines) else None
        places.append((line, found.start() + 1 if found else 1))
    return places
