"""All transmissions of one config as whole-robot block matrices.

Each transmission's maps come from :mod:`txtool.mechanics.maps`; they are linear (affine for
position), so the matrices are read off by applying the maps to unit vectors. A joint that no
transmission of the config drives gets a direct actuator named like the joint (identity map).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from lxml import etree

from txtool.dialects.read import Found, read_source
from txtool.dialects.translate import interface_kind
from txtool.io.xmlio import InputError, Source, local
from txtool.mechanics.convention import effort_convention
from txtool.mechanics.inertia import reflected_inertia
from txtool.mechanics.maps import TransmissionMap, from_effective
from txtool.model.distro import Distro
from txtool.model.numbers import parse_strict
from txtool.model.readers import Assumption, Placement, placement_of
from txtool.model.robot import children
from txtool.model.semantics import NotLoadable, effective, loader_of, ros2_values_differ
from txtool.simulation.model import RobotModel

DRAKE_TAGS = ("rotor_inertia", "gear_ratio")
GROUP = 3  # transmissions left out for one reason that are listed in one note


@dataclass
class Drive:
    """Actuator space of one config, bound to the model's DoF order."""

    path: str
    joints: tuple[str, ...]
    actuators: tuple[str, ...]
    transmission_of: tuple[str, ...]  # per actuator; "" for a direct actuator
    pos_j2a: np.ndarray  # (na, nv): x_a = pos_j2a @ x + pos_j2a_c
    pos_j2a_c: np.ndarray
    pos_a2j: np.ndarray  # (nv, na): x = pos_a2j @ x_a + pos_a2j_c
    pos_a2j_c: np.ndarray
    vel_j2a: np.ndarray
    vel_a2j: np.ndarray
    eff_j2a: np.ndarray
    eff_a2j: np.ndarray
    direct: tuple[str, ...]
    maps: list[TransmissionMap] = field(default_factory=list)
    drake: dict[str, dict[str, tuple[float, int]]] = field(default_factory=dict)
    # ROS 2 transmissions: (joints, actuators) in XML order, the order of their parameters.
    xml_order: dict[str, tuple[tuple[str, ...], tuple[str, ...]]] = field(default_factory=dict)
    # ROS 1 transmissions: the <role> of each joint and actuator that has one, in XML order.
    roles: dict[str, dict[str, str]] = field(default_factory=dict)
    # Per block: DoF indices, actuator indices, the map (None for a direct actuator).
    blocks: list[tuple[list[int], list[int], TransmissionMap | None]] = field(
        default_factory=list)
    notes: list[str] = field(default_factory=list)  # transmissions left out, and why
    skipped: dict[str, str] = field(default_factory=dict)  # transmission name -> why
    names: tuple[str, ...] = ()  # every transmission read (simulated or not)
    unread: dict[str, str] = field(default_factory=dict)  # read by no reader of the file: why
    # Per joint of a simulated transmission: how it is commanded (position, velocity, effort).
    commands: dict[str, frozenset[str]] = field(default_factory=dict)

    @property
    def na(self) -> int:
        return len(self.actuators)

    def reflected_inertia(self, rotor: np.ndarray) -> np.ndarray:
        """Joint-space rotor inertia of the whole robot (``rotor``: one value per actuator)."""
        inertia = np.zeros((len(self.joints), len(self.joints)))
        for columns, rows, tmap in self.blocks:
            block = np.diag(rotor[rows]) if tmap is None else reflected_inertia(tmap, rotor[rows])
            inertia[np.ix_(columns, columns)] += block
        return inertia

    def actuators_of(self, joint: str) -> list[int]:
        v = self.joints.index(joint)
        return [int(i) for i in np.nonzero(self.vel_j2a[:, v])[0]]


def read_drive(source: Source, robot: RobotModel, *, loader: str = "auto",
               readers: Assumption, convention: str | None = None,
               skip: tuple[str, ...] = ()) -> Drive:
    """The drive of ``source``'s transmissions on ``robot``'s joints.

    Effort maps follow ``convention`` (``ros1``, ``ros2``), else each transmission's own
    loader (:func:`txtool.mechanics.convention.effort_convention`).

    ``readers``: the programs that read the file (:func:`txtool.lint.config.readers_of`, as
    ``validate`` decides them). A transmission none of them reads is left out and named in
    ``unread`` (its joints are driven directly); numbers are read as the one ROS 2 distribution
    among them reads them.

    A transmission that cannot be simulated (``--skip``, a custom type or a loader refusal, a
    joint that is mimic, fixed, locked, absent or already driven, an actuator already taken)
    is left out with a note; its joints are driven directly.
    """
    every = read_source(source)
    read = [f for f in every if _reads(readers, f)]
    kept_ids = {id(f) for f in read}
    unread = {f.transmission.name: _unread_why(f, readers) for f in every
              if id(f) not in kept_ids}
    found, notes = _select(source.path, read, loader)
    distro = _one_ros2_distro(readers)
    skipped: dict[str, str] = {}
    where: dict[str, str] = {f.transmission.name: _where(source.path, f) for f in every}
    maps, kept = [], []
    owner: dict[str, str] = {}
    taken: set[str] = set()
    for item in found:
        t = item.transmission
        reading = distro
        if distro is None and ros2_values_differ(t):
            reading = Distro.JAZZY
            notes.append(f"{where[t.name]}: transmission '{t.name}': ROS 2 distributions read "
                         "its numbers differently (Humble with istringstream, Jazzy and later "
                         "with from_chars) and nothing says which one reads the file: it is "
                         "simulated as Jazzy and later read it (--ros-distro humble: as Humble "
                         "reads it)")
        why = _why_not(item, robot, owner, taken, convention, skip, reading)
        if isinstance(why, str):
            skipped[t.name] = why
            continue
        for joint in why.joints:
            owner[joint] = t.name
        taken.update(why.actuators)
        maps.append(why)
        kept.append(item)
    drive = assemble(source.path, maps, robot, kept)
    drive.drake = read_drake_tags(source.path, kept)
    drive.xml_order = {f.transmission.name: (tuple(j.name for j in f.transmission.joints),
                                             tuple(a.name for a in f.transmission.actuators))
                       for f in kept if loader_of(f.transmission) == "ros2"}
    drive.roles = {f.transmission.name: {m.name: m.role for m in (*f.transmission.joints,
                                                                  *f.transmission.actuators)
                                         if m.role}
                   for f in kept if loader_of(f.transmission) == "ros1"}
    notes += _skip_notes(source.path, unread, where) + _skip_notes(source.path, skipped, where)
    if found and not maps:
        notes.append("no transmission can be simulated: every joint is driven directly")
    drive.notes, drive.skipped, drive.unread = notes, skipped, unread
    drive.names = tuple(item.transmission.name for item in found)
    drive.commands = command_kinds(kept)
    return drive


def _reads(readers: Assumption, item: Found) -> bool:
    """Whether some reader of the file reads this transmission (every one when the readers
    are not decided: each is then read by the loader of its dialect)."""
    return readers.reads(placement_of(item.element))


def _unread_why(item: Found, readers: Assumption) -> str:
    if placement_of(item.element) is Placement.TOP_LEVEL:
        where = ("it stands outside every <ros2_control> block, and the file's readers read "
                 "only the transmissions inside one")
    else:
        where = ("it stands inside a <ros2_control> block, and the file's readers read only "
                 "top-level transmissions")
    return f"read by no reader of the file: {where} ({readers.explain()})"


def _one_ros2_distro(readers: Assumption) -> Distro | None:
    """The ROS 2 distribution whose parser reads the file's numbers, when one alone does."""
    ros2 = [d for d in readers.distros if d.ros2]
    return ros2[0] if len(ros2) == 1 else None


COMMANDS = ("position", "velocity", "effort")


def command_kinds(kept: list[Found]) -> dict[str, frozenset[str]]:
    """How each joint of these transmissions is commanded: its ROS 1 hardware interfaces or
    ROS 2 command interfaces, as kinds (``hardware_interface/EffortJointInterface`` and
    ``effort`` are both ``effort``). Joints that declare none are left out."""
    kinds: dict[str, frozenset[str]] = {}
    for item in kept:
        for joint in item.transmission.joints:
            declared = {kind for kind in map(interface_kind, joint.interfaces) if kind in COMMANDS}
            if declared:
                kinds[joint.name] = kinds.get(joint.name, frozenset()) | declared
    return kinds


def _skip_notes(path: str, skipped: dict[str, str], where: dict[str, str]) -> list[str]:
    """One note per transmission left out; one per reason when three or more share it."""
    by_reason: dict[str, list[str]] = {}
    for name, why in skipped.items():
        by_reason.setdefault(why, []).append(name)
    notes = []
    for why, names in by_reason.items():
        if len(names) < GROUP:
            notes += [f"{where[n]}: transmission '{n}' is not simulated: {why}" for n in names]
        else:
            notes.append(f"{path}: {len(names)} transmissions are not simulated: {why}: "
                         + ", ".join(names))
    return notes


def _why_not(item: Found, robot: RobotModel, owner: dict[str, str], taken: set[str],
             convention: str | None, skip: tuple[str, ...], distro: Distro | None = None
             ) -> TransmissionMap | str:
    """The transmission's map, or why it cannot be simulated."""
    t = item.transmission
    if t.name in skip:
        return "skipped with --skip"
    conv = effort_convention(t, convention)
    try:
        tmap = from_effective(effective(t, distro), conv)
    except NotLoadable as exc:
        if t.kind == "other":
            return f"{exc}"
        loader = "ros_control" if loader_of(t) == "ros1" else "ros2_control"
        return f"{loader}'s transmission loader refuses it: {exc}"
    for joint in tmap.joints:
        if joint in robot.joints:
            if joint in owner:
                return f"joint '{joint}' is already driven by transmission '{owner[joint]}'"
            continue
        info = robot.info.get(joint)
        if info is None:
            return f"joint '{joint}' is not a joint of the robot"
        if joint in robot.mimic:
            return (f"joint '{joint}' is a mimic joint (it follows its leader "
                    f"'{info.mimic}' and takes no transmission)")
        if joint in robot.locked:
            return f"joint '{joint}' is locked (it moves no mass)"
        return f"joint '{joint}' is a {info.type} joint"
    for actuator in tmap.actuators:
        if actuator in taken:
            return f"actuator '{actuator}' is already driven by another transmission"
    return tmap


def _select(path: str, found: list[Found], loader: str) -> tuple[list[Found], list[str]]:
    loaders = {loader_of(f.transmission) for f in found}
    if loader == "auto":
        if len(loaders) > 1:
            note = ("has both ROS 1 and ROS 2 transmissions: the ROS 2 ones are simulated "
                    "(--loader ros1 for the others)")
            return [f for f in found if loader_of(f.transmission) == "ros2"], [note]
        return found, []
    return [f for f in found if loader_of(f.transmission) == loader], []


def _where(path: str, item: Found | None) -> str:
    location = item.transmission.location if item is not None else None
    return f"{path}:{location.line}" if location is not None and location.line else path


def assemble(path: str, maps: list[TransmissionMap], robot: RobotModel,
             found: list[Found] | None = None) -> Drive:
    """Stack ``maps`` (plus direct actuators for uncovered joints) into robot-wide matrices."""
    nv = robot.nv
    owner: dict[str, str] = {}
    blocks: list[tuple[list[int], list[str], str, TransmissionMap | None]] = []
    for k, tmap in enumerate(maps):
        where = _where(path, found[k] if found else None)
        columns = [_joint_index(where, robot, tmap, j, owner) for j in tmap.joints]
        blocks.append((columns, list(tmap.actuators), tmap.name, tmap))
    direct = tuple(j for j in robot.joints if j not in owner)
    taken = {a for _, names, _, _ in blocks for a in names}
    for joint in direct:
        name = joint if joint not in taken else f"{joint}/direct"
        blocks.append(([robot.joints.index(joint)], [name], "", None))
    actuators = [a for _, names, _, _ in blocks for a in names]
    seen: set[str] = set()
    for a in actuators:
        if a in seen:
            raise InputError(f"{path}: actuator '{a}' is driven by more than one transmission")
        seen.add(a)
    return _matrices(path, robot, blocks, actuators, nv, direct, maps)


def _joint_index(where: str, robot: RobotModel, tmap: TransmissionMap, joint: str,
                 owner: dict[str, str]) -> int:
    if joint not in robot.joints:
        raise InputError(f"{where}: transmission '{tmap.name}': joint '{joint}' is not a "
                         "moving joint of the model")
    if joint in owner:
        raise InputError(f"{where}: joint '{joint}' is in transmissions '{owner[joint]}' and "
                         f"'{tmap.name}'")
    owner[joint] = tmap.name
    return robot.joints.index(joint)


def _matrices(path: str, robot: RobotModel, blocks: list, actuators: list[str], nv: int,
              direct: tuple[str, ...], maps: list[TransmissionMap]) -> Drive:
    na = len(actuators)
    m = {k: np.zeros((na, nv)) for k in ("pos_j2a", "vel_j2a", "eff_j2a")}
    m.update({k: np.zeros((nv, na)) for k in ("pos_a2j", "vel_a2j", "eff_a2j")})
    c_j2a, c_a2j = np.zeros(na), np.zeros(nv)
    row = 0
    owners: list[str] = []
    placed: list[tuple[list[int], list[int], TransmissionMap | None]] = []
    for columns, names, tname, tmap in blocks:
        rows = list(range(row, row + len(names)))
        row += len(names)
        owners.extend([tname] * len(names))
        placed.append((columns, rows, tmap))
        ix_a, ix_j = np.ix_(rows, columns), np.ix_(columns, rows)
        if tmap is None:
            for key in m:
                if key.endswith("j2a"):
                    m[key][rows[0], columns[0]] = 1.0
                else:
                    m[key][columns[0], rows[0]] = 1.0
            continue
        for quantity, key in (("position", "pos"), ("velocity", "vel"), ("effort", "eff")):
            j2a, j2a_c = probe(tmap.joint_to_actuator, quantity, len(columns))
            a2j, a2j_c = probe(tmap.actuator_to_joint, quantity, len(names))
            m[f"{key}_j2a"][ix_a] = j2a
            m[f"{key}_a2j"][ix_j] = a2j
            if key == "pos":
                c_j2a[rows], c_a2j[columns] = j2a_c, a2j_c
    return Drive(path, robot.joints, tuple(actuators), tuple(owners), m["pos_j2a"], c_j2a,
                 m["pos_a2j"], c_a2j, m["vel_j2a"], m["vel_a2j"], m["eff_j2a"], m["eff_a2j"],
                 direct, list(maps), blocks=placed)


def probe(function: object, quantity: str, n: int) -> tuple[np.ndarray, np.ndarray]:
    """Matrix and constant of the affine map ``function(quantity, .)`` on n values."""
    constant = np.asarray(function(quantity, np.zeros(n)), dtype=float)  # type: ignore[operator]
    images = np.asarray(function(quantity, np.eye(n)), dtype=float)  # type: ignore[operator]
    return (images - constant).T, constant


def read_drake_tags(path: str, found: list[Found]) -> dict[str, dict[str, tuple[float, int]]]:
    """``<drake:rotor_inertia value=".."/>`` and ``<drake:gear_ratio>`` per actuator name."""
    tags: dict[str, dict[str, tuple[float, int]]] = {}
    for item in found:
        for actuator in children(item.element, "actuator"):
            for child in actuator:
                name = local(child)
                if name not in DRAKE_TAGS or not _is_drake(child):
                    continue
                line = child.sourceline or 0
                value = _drake_value(child)
                if value is None or not math.isfinite(value) or value < 0:
                    where = f"{path}:{line}" if line else path
                    raise InputError(f"{where}: drake:{name} needs a finite non-negative number "
                                     f"in value=")
                tags.setdefault(actuator.get("name", ""), {})[name] = (value, line)
    return tags


def _is_drake(element: etree._Element) -> bool:
    namespace = etree.QName(element).namespace or ""
    return element.prefix == "drake" or "drake" in namespace


def _drake_value(element: etree._Element) -> float | None:
    text = element.get("value")
    if text is None:
        text = element.text
    return parse_strict(text)
