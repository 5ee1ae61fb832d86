"""Controller configurations checked against the robot they control (rules TX5xx).

A controller YAML file is paired with robot files: one ``--controllers`` names with the robot
files of the run, and one a folder walk finds (under the walked folders, or in the package of
a robot file the walk found; a controller file is decided from its content:
:func:`~txtool.io.controller_yaml.read_controller_file`) with the walk's robot files. Of those,
it is judged against the robot having most of the joints it claims (:func:`pick_robot`). What the
robot provides is read from its expanded tree as the managers' hardware reads it: ROS 1, each
transmission joint's ``<hardwareInterface>`` classes and the ``JointStateInterface`` the
transmission loader's interface providers register with them (ros-controls/ros_control
transmission_interface/src/joint_state_interface_provider.cpp); ROS 2, each ``<ros2_control>``
joint's ``command_interface`` and ``state_interface`` names (exported by the resource manager).
"""

from __future__ import annotations

import dataclasses
import os
import re
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

from lxml import etree

from txtool.io.controller_yaml import MAX_BYTES, ControllerFile, read_controller_file
from txtool.io.launch_spawners import Spawn, launch_files, spawns_in
from txtool.io.load import load
from txtool.io.xmlio import InputError, Source, parse_bytes, read_regular
from txtool.lint.discover import scan
from txtool.lint.problem import InputFailure, Problem
from txtool.model.controllers import (
    HW,
    ROS1,
    STATE,
    Claim,
    Controller,
    known_type,
    ros1_claims,
    ros2_claims,
)
from txtool.model.robot import children, components, joint_elements

if TYPE_CHECKING:
    from txtool.lint.config import Settings

YAML_SUFFIXES = (".yaml", ".yml")
MAX_SCANNED = 200  # YAML files looked at per walked folder or package


def ros1_interface(text: str) -> str:
    """A ``<hardwareInterface>`` text as the class its provider registers:
    ``EffortJointInterface`` and ``hardware_interface/EffortJointInterface`` are
    ``hardware_interface::EffortJointInterface``."""
    name = text.strip().replace("/", "::")
    return name if "::" in name else HW + name


@dataclass
class Provision:
    """What a robot gives its controllers: its joint names, and per joint the interfaces."""

    joints: frozenset[str]
    ros1: dict[str, set[str]] = field(default_factory=dict)
    ros2_command: dict[str, set[str]] = field(default_factory=dict)
    ros2_state: dict[str, set[str]] = field(default_factory=dict)
    # Where a <hardwareInterface> of the robot's xacro files is an expression (``path:line``;
    # ur_description's ${transmission_hw_interface}): a launch file's arguments choose it.
    chosen_by_arguments: str | None = None

    def has(self, generation: str) -> bool:
        """Whether the robot says what it provides for ``generation`` at all (a ROS 1 robot
        without transmissions is driven by a RobotHW written in C++: nothing to check)."""
        return bool(self.ros1) if generation == ROS1 else bool(self.ros2_state or
                                                                 self.ros2_command)

    def provides(self, generation: str, claim: Claim) -> bool:
        if generation == ROS1:
            return claim.interface in self.ros1.get(claim.joint, ())
        table = self.ros2_command if claim.command else self.ros2_state
        return claim.interface in table.get(claim.joint, ())

    def driven(self, generation: str, joint: str) -> bool:
        if generation == ROS1:
            return joint in self.ros1
        return joint in self.ros2_command or joint in self.ros2_state


def provision_of(root: etree._Element) -> Provision:
    """What the robot ``root`` (expanded) provides."""
    provision = Provision(frozenset(joint_elements(root)))
    for transmission in root.iter("{*}transmission"):
        for joint in children(transmission, "joint"):
            named = [ros1_interface(e.text or "") for e in children(joint, "hardwareInterface")
                     if (e.text or "").strip()]
            if named:
                provision.ros1.setdefault(joint.get("name", ""), set()).update([*named, STATE])
    for component in components(root):
        for joint in component.joints:
            provision.ros2_command.setdefault(joint.name, set()).update(joint.command_interfaces)
            provision.ros2_state.setdefault(joint.name, set()).update(joint.state_interfaces)
    return provision


def controllers_of(file: ControllerFile, exported: frozenset[str] = frozenset()
                   ) -> list[Controller]:
    """The controllers of ``file``, each with the joint interfaces it claims of the robot.

    A ROS 2 "joint" with a ``/`` (``pid_controller/joint1``) is a chained controller's
    reference interface, which the robot does not provide: such claims are left out."""
    claims = ros1_claims if file.generation == ROS1 else ros2_claims
    return [
        Controller(e.name, e.type, file.generation, e.line, e.column, e.params,
                   known_type(e.type, file.generation, exported),
                   tuple(c for c in claims(e.type, e.params)
                         if file.generation == ROS1 or "/" not in c.joint))
        for e in file.entries
    ]


@dataclass
class ControllerContext:
    """What a TX5xx rule looks at: one controller file with the robot it controls."""

    path: str  # the controller file, where the findings are
    robot: str
    generation: str
    controllers: list[Controller]
    provision: Provision
    # The spawners of the launch files of the controller file's package and the robot's.
    spawns: tuple[Spawn, ...] = ()

    def problem(self, code: str, controller: Controller, message: str) -> Problem:
        """A finding at the controller's name."""
        return Problem(self.path, controller.line, controller.column, code, message,
                       end_line=controller.line,
                       end_column=controller.column + max(len(controller.name), 1))


def package_root(path: str) -> str | None:
    """The folder of the nearest ``package.xml`` above ``path`` (as given, with a trailing
    separator; ``""`` for the current folder): the findings name files as the walk does."""
    return _package_of_folder(os.path.dirname(path))


_PACKAGE_OF: dict[str, str | None] = {}  # folder -> its package's folder, as found


def forget_packages() -> None:
    """Look for each folder's ``package.xml`` again (a long-running caller's files change)."""
    _PACKAGE_OF.clear()


def _package_of_folder(folder: str) -> str | None:
    # One look per folder (a walk finds many robot files in few folders), up the tree in a
    # loop (a folder may be a thousand deep); a relative path is looked up to the current
    # folder, not above it.
    passed = []
    found: str | None = None
    while folder not in _PACKAGE_OF:
        passed.append(folder)
        if os.path.isfile(os.path.join(folder or ".", "package.xml")):
            found = os.path.join(folder, "") if folder not in ("", ".") else ""
            break
        parent = os.path.dirname(folder)
        if folder in ("", ".") or parent == folder:
            break
        folder = parent
    else:
        found = _PACKAGE_OF[folder]
    if len(_PACKAGE_OF) > 4096:
        _PACKAGE_OF.clear()
    _PACKAGE_OF.update(dict.fromkeys(passed, found))
    return found


# Folders of a colcon or catkin workspace that hold copies of its packages' files.
BUILD_FOLDERS = frozenset({"build", "install", "log", "devel"})
IGNORE_MARKERS = ("COLCON_IGNORE", "CATKIN_IGNORE", "AMENT_IGNORE")


def controller_files_under(top: str, *, one_package: bool = False) -> list[str]:
    """The YAML files under the folder ``top`` that define controllers, in path order: at most
    :data:`MAX_SCANNED` YAML files looked at; hidden folders, a workspace's build, install and
    log folders and ignored packages passed over; with ``one_package``, the package at ``top``
    alone (no folder holding another ``package.xml``)."""
    found: list[str] = []
    scanned = 0
    start = top or "."
    for folder, subfolders, entries in scan(start):  # (no recursion: folders may nest deep)
        files = [entry.name for entry in entries]
        subfolders[:] = [d for d in subfolders
                         if not d.name.startswith(".") and d.name not in BUILD_FOLDERS]
        if any(marker in files for marker in IGNORE_MARKERS) or (
                one_package and folder != start and "package.xml" in files):
            subfolders[:] = []
            continue
        for name in files:
            if not name.endswith(YAML_SUFFIXES):
                continue
            scanned += 1
            if scanned > MAX_SCANNED:
                return found
            path = os.path.join(folder, name)
            if top in ("", "."):  # the current folder: named as the walk names its files
                path = os.path.normpath(path)
            try:
                data = read_regular(path, MAX_BYTES)
                # Every controller names its type: most other YAML files are passed unparsed.
                if b"type" in data and read_controller_file(path, data) is not None:
                    found.append(path)
            except InputError:
                continue  # a YAML file that is no controller configuration of ours to judge
    return found


def exported_controllers(package: str | None) -> frozenset[str]:
    """The controller types the packages beside ``package`` (its workspace folder) export
    with pluginlib (``<export><controller_interface plugin="..."/>``)."""
    if package is None:
        return frozenset()
    names: set[str] = set()
    parent = Path(package).resolve().parent
    for manifest in sorted(parent.glob("*/package.xml"))[:MAX_SCANNED]:
        names.update(_exported_in(manifest))
    return frozenset(names)


# ROS 2 packages export plugins from CMake: pluginlib_export_plugin_description_file(
# controller_interface FILE.xml) (ros/pluginlib pluginlib/cmake/
# pluginlib_export_plugin_description_file.cmake).
_CMAKE_EXPORT = re.compile(
    rb"pluginlib_export_plugin_description_file\s*\(\s*controller_interface\s+\"?([^\s\")]+)")


def _exported_in(manifest: Path) -> Iterator[str]:
    """The controller classes a package exports: in ``package.xml`` (ROS 1,
    ``<controller_interface plugin="${prefix}/FILE.xml"/>``) or its ``CMakeLists.txt``."""
    folder = manifest.parent
    descriptions = []
    try:
        root = parse_bytes(read_regular(str(manifest)), str(manifest)).getroot()
        for export in children(root, "export"):
            for element in children(export, "controller_interface"):
                plugin = (element.get("plugin") or "").replace("${prefix}", str(folder))
                descriptions.append(plugin)
    except (InputError, OSError):
        return
    try:
        cmake = read_regular(str(folder / "CMakeLists.txt"))
    except (InputError, OSError):
        cmake = b""
    descriptions += [str(folder / m.decode(errors="replace")) for m in _CMAKE_EXPORT.findall(cmake)]
    for plugin in descriptions:
        try:
            description = parse_bytes(read_regular(plugin), plugin).getroot()
        except (InputError, OSError):
            continue
        for cls in description.iter("{*}class"):
            if cls.get("name") or cls.get("type"):
                yield cls.get("name") or cls.get("type", "")


def robot_provision(robot: str, settings: Settings, source: Source | None = None
                    ) -> Provision | None:
    """What the robot file at ``robot`` provides (as ``source`` holds it, when given: an
    editor's buffer), or None when it cannot be read (its own check says why)."""
    try:
        if source is None:
            source = load(robot, xacro=settings.xacro, expand=not settings.no_xacro,
                          warn_unused=False)
    except InputError:
        return None
    provision = provision_of(source.root)
    if source.expanded:
        from txtool.lint.fragments import included_files

        for path in (robot, *included_files(robot, settings.xacro)):
            where = _expression_interface(path)
            if where is not None:
                provision.chosen_by_arguments = where
                break
    return provision


_EXPRESSION_INTERFACE = re.compile(rb"<hardwareInterface>\s*[^<]*\$[({]")


def _expression_interface(path: str) -> str | None:
    """``path:line`` of the first ``<hardwareInterface>`` whose text is a xacro expression."""
    try:
        data = read_regular(path)
    except InputError:
        return None
    match = _EXPRESSION_INTERFACE.search(data)
    if match is None:
        return None
    line = data.count(b"\n", 0, match.start()) + 1
    return f"{shown(path)}:{line}"


def shown(path: str) -> str:
    """``path`` as a message names another file: from the current folder, unless outside it."""
    relative = os.path.relpath(path)
    return path if relative.startswith("..") else relative


def pick_robot(controllers: list[Controller], generation: str,
               robots: dict[str, Provision | None], near: str = "") -> str | None:
    """The robot file the controllers are for: of the robots that say what they provide for
    ``generation``, the one having the most of the joints the controllers claim, and at least
    one of them when they claim any; of equals, the nearest to the controller file ``near``
    (the longest common folder: its own package before a sibling, a sibling before another
    robot of the workspace), then the first. None when no robot fits (the controllers are for
    a robot not checked). When a candidate could not be read (a xacro robot whose expansion
    needs a package or an argument the run lacks), the best of the others is chosen only if it
    has every claimed joint: the file may be that unread robot's."""
    claimed = {joint for c in controllers for joint in c.joints}
    folder = os.path.dirname(os.path.abspath(near)) if near else ""
    best, rank = None, (-1, -1)
    for path, provision in robots.items():
        if provision is None or not provision.has(generation):
            continue
        shared = os.path.commonpath([folder, os.path.abspath(path)]) if folder else ""
        here = (len(claimed & provision.joints), len(shared.split(os.sep)) if shared else 0)
        if here > rank and (here[0] or not claimed):
            best, rank = path, here
    unread = any(provision is None for provision in robots.values())
    return None if unread and rank[0] < len(claimed) else best


def controller_problems(
    robots: list[tuple[str, Settings]], walked: list[tuple[str, Settings]],
    folders: list[str], named: tuple[str, ...], settings_for: Callable[[str], Settings],
) -> Iterator[list[Problem] | InputFailure]:
    """The TX5xx findings of each controller file: those ``named`` (``--controllers``),
    judged against the ``robots`` checked; and those found in the walked ``folders`` and in
    the packages of the robot files the walks found (``walked``), judged against those robot
    files. Each file is judged against the robot having most of the joints it claims. A named
    file that cannot be read is an :class:`InputFailure`."""
    _PACKAGE_OF.clear()  # files may have changed since the last run
    pairs: dict[str, list[tuple[str, Settings]]] = {}
    for path in named:
        pairs.setdefault(path, []).extend(robots)
    stated = {os.path.realpath(path) for path in named}
    if walked:
        packages = {package_root(robot) for robot, _ in walked} - {None}
        found = [path for top in folders for path in controller_files_under(top)]
        found += [path for package in sorted(packages)  # type: ignore[type-var]
                  for path in controller_files_under(package, one_package=True)]
        seen = set(stated)
        for path in found:
            real = os.path.realpath(path)
            if real not in seen:
                seen.add(real)
                pairs[path] = walked
    provisions: dict[str, Provision | None] = {}
    for path, candidates in pairs.items():
        try:
            file = read_controller_file(path)
        except InputError as exc:
            yield InputFailure(path, str(exc))
            continue
        if file is None:
            continue
        for robot, settings in candidates:
            if robot not in provisions:
                provisions[robot] = robot_provision(robot, settings)
        controllers = controllers_of(file, exported_controllers(package_root(path)))
        chosen = pick_robot(controllers, file.generation,
                            {robot: provisions[robot] for robot, _ in candidates}, near=path)
        if chosen is None:
            continue
        ctx = ControllerContext(path, chosen, file.generation, controllers, provisions[chosen],
                                spawns_near(path, chosen))
        yield judged(ctx, settings_for(path))


def spawns_near(*files: str) -> tuple[Spawn, ...]:
    """The spawners of the launch files of the packages holding ``files``, each file once."""
    packages = dict.fromkeys(p for p in map(package_root, files) if p is not None)
    launches = dict.fromkeys(launch for package in packages for launch in launch_files(package))
    return tuple(spawn for launch in launches for spawn in spawns_in(launch))


def judged(ctx: ControllerContext, settings: Settings) -> list[Problem]:
    """The findings of the enabled TX5xx rules, stamped with their name and severity."""
    from txtool.rules import all_rules

    problems = []
    for code, rule in all_rules().items():
        check = getattr(rule.module, "check_controllers", None)
        if check is None or code not in settings.enabled:
            continue
        configured = settings.severity.get(code)
        problems.extend(
            dataclasses.replace(p, severity=configured or p.loader_severity or rule.severity,
                                name=rule.name, fixable=False)
            for p in check(ctx)
        )
    return sorted(problems)


def refusal(ctx: ControllerContext, claim: Claim) -> str:
    """What the controller manager says when it refuses a controller for ``claim``."""
    if ctx.generation != ROS1:
        kind = "command" if claim.command else "state"
        return f"{kind} interface '{claim.joint}/{claim.interface}' is not available"
    if not any(claim.interface in given for given in ctx.provision.ros1.values()):
        return f"This controller requires a hardware interface of type '{claim.interface}'"
    return f"Could not find resource '{claim.joint}' in '{claim.interface}'"


def accepted(ctx: ControllerContext, controller: Controller) -> bool:
    """Whether the robot gives the controller every joint and interface it claims."""
    provision = ctx.provision
    return all(claim.joint in provision.joints and provision.provides(ctx.generation, claim)
               for claim in controller.claims)


def alternative_to(ctx: ControllerContext, controller: Controller, joint: str
                   ) -> Controller | None:
    """Another controller of the file that drives ``joint`` with what the robot provides.

    A file that holds, for the same joints, a controller the robot accepts and one it refuses
    is a file of alternatives (ur_gazebo's position and effort trajectory controllers, for a
    robot whose ``<hardwareInterface>`` is a xacro argument): a launch file spawns some of
    them, and the manager refuses the other only if it is loaded with this robot."""
    for other in ctx.controllers:
        if other is not controller and joint in other.joints and accepted(ctx, other):
            return other
    return None


def controller_interface_problems(ctx: ControllerContext, code: str, *, command: bool
                                  ) -> Iterator[Problem]:
    """TX501/TX502: for each controller, each command (or state) interface it claims of driven
    joints that the robot does not provide, once for all such joints (a joint that is missing
    or not driven at all is TX500's); a warning where the robot's interface is a xacro
    expression, or where another controller of the file drives the joint as the robot is."""
    provision = ctx.provision
    generation = ctx.generation
    if not provision.has(generation):
        return
    for controller in ctx.controllers:
        missing: dict[str, list[Claim]] = {}
        for claim in controller.claims:
            if (claim.command == command and provision.driven(generation, claim.joint)
                    and not provision.provides(generation, claim)):
                missing.setdefault(claim.interface, []).append(claim)
        for claims in missing.values():
            yield _missing_interface(ctx, code, controller, claims)


def _missing_interface(ctx: ControllerContext, code: str, controller: Controller,
                       claims: list[Claim]) -> Problem:
    provision = ctx.provision
    first = claims[0]
    if ctx.generation == ROS1:
        table, what = provision.ros1, "hardware interface"
    else:
        table = provision.ros2_command if first.command else provision.ros2_state
        what = "command interface" if first.command else "state interface"
    shown = ", ".join(sorted(table.get(first.joint, set()))) or "none"
    joints = "', '".join(claim.joint for claim in claims)
    subject = f"joint '{joints}' has" if len(claims) == 1 else f"joints '{joints}' have"
    message = (f"controller '{controller.name}' ({controller.type}): {subject} no {what} "
               f"'{first.interface}' (it has: {shown}); ")
    chosen = provision.chosen_by_arguments if ctx.generation == ROS1 else None
    other = None if chosen else alternative_to(ctx, controller, first.joint)
    if chosen is not None:
        message += (f"the robot's hardwareInterface is a xacro expression ({chosen}) that a "
                    "launch file's arguments may set (check the robot with those "
                    "--xacro-arg); as expanded here, the controller manager refuses the "
                    "controller")
    elif other is not None:
        message += (f"'{other.name}' of this file drives the joint as the robot is, so this "
                    "one may be an alternative for a robot built otherwise: loaded with this "
                    "robot, the controller manager refuses it")
    else:
        message += "the controller manager refuses the controller"
    problem = ctx.problem(code, controller, f"{message}: {refusal(ctx, first)}")
    if chosen is None and other is None:
        return problem
    return dataclasses.replace(problem, loader_severity="warning")


def ros1_controller_file(path: str) -> ControllerFile:
    """The ROS 1 controller configuration at ``path``; :class:`~txtool.io.xmlio.InputError`
    for a file that cannot be read, is not YAML, or is no ROS 1 controller configuration."""
    file = read_controller_file(path)
    if file is None or file.generation != ROS1:
        raise InputError(f"{path}: no ROS 1 controller configuration (a controller namespace "
                         "with a type)")
    return file


def _flow(value: object) -> str:
    """A parameter value as YAML's flow style writes it."""
    return f"[{', '.join(map(str, value))}]" if isinstance(value, list) else str(value)


def ros2_needs(file: ControllerFile, converted: etree._Element) -> tuple[list[str], list[str]]:
    """What each controller of the ROS 1 controller ``file`` becomes in ROS 2, and whether the
    ``converted`` robot's ``<ros2_control>`` joints provide what it claims there: (notes,
    warnings), each a line ``path:line:col: ...``."""
    from txtool.model.controllers import ros2_equivalent

    provision = provision_of(converted)
    notes: list[str] = []
    warnings: list[str] = []
    for controller in controllers_of(file):
        where = (f"{file.path}:{controller.line}:{controller.column}: controller "
                 f"'{controller.name}' ({controller.type})")
        equivalent = ros2_equivalent(controller)
        if equivalent is None:
            notes.append(f"{where}: no ros2_controllers type does its work; port it")
            continue
        said = ", ".join(f"{k}: {_flow(v)}" for k, v in equivalent.params.items())
        head = f"{where} is {equivalent.type} in ROS 2" + (f" ({said})" if said else "")
        if equivalent.note:
            head += f"; {equivalent.note}"
        lacking = [f"{c.joint}/{c.interface} ({'command' if c.command else 'state'})"
                   for c in equivalent.claims if not provision.provides("ros2", c)]
        if lacking:
            warnings.append(f"{head}; the converted <ros2_control> lacks " + ", ".join(lacking))
        else:
            notes.append(f"{head}; the converted <ros2_control> provides what it claims")
    return notes, warnings
