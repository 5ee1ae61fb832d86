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
from txtool.io.xmlio import InputError, Source, local
from txtool.mechanics.inertia import reflected_inertia
from txtool.mechanics.maps import TransmissionMap, from_transmission
from txtool.model.numbers import parse_strict
from txtool.model.robot import children
from txtool.model.semantics import NotLoadable, loader_of
from txtool.simulate.model import RobotModel

DRAKE_TAGS = ("rotor_inertia", "gear_ratio")


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
    # Per block: DoF indices, actuator indices, the map (None for a direct actuator).
    blocks: list[tuple[list[int], list[int], TransmissionMap | None]] = field(
        default_factory=list)

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
               convention: str = "ros2") -> Drive:
    """The drive of ``source``'s transmissions on ``robot``'s joints."""
    found = _select(source.path, read_source(source), loader)
    maps = []
    for item in found:
        t = item.transmission
        conv = "ros1" if convention == "loader" and loader_of(t) == "ros1" else "ros2"
        try:
            maps.append(from_transmission(t, conv))
        except NotLoadable as exc:
            raise InputError(f"{_where(source.path, item)}: transmission '{t.name}' cannot be "
                             f"loaded: {exc}") from None
    drive = assemble(source.path, maps, robot, found)
    drive.drake = read_drake_tags(source.path, found)
    drive.xml_order = {f.transmission.name: (tuple(j.name for j in f.transmission.joints),
                                             tuple(a.name for a in f.transmission.actuators))
                       for f in found if loader_of(f.transmission) == "ros2"}
    return drive


def _select(path: str, found: list[Found], loader: str) -> list[Found]:
    loaders = {loader_of(f.transmission) for f in found}
    if loader == "auto":
        if len(loaders) > 1:
            raise InputError(f"{path}: has both ROS 1 and ROS 2 transmissions; choose one with "
                             "--loader ros1|ros2")
        return found
    return [f for f in found if loader_of(f.transmission) == loader]


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
        info = robot.info.get(joint)
        if info is None:
            why = "is not a joint of the robot"
        elif joint in robot.mimic:
            why = "is a mimic joint (it follows its leader and takes no transmission)"
        else:
            why = f"is a {info.type} joint"
        raise InputError(f"{where}: transmission '{tmap.name}': joint '{joint}' {why}")
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
