"""Beam Bots (BB) names for a URDF's links, joints and actuators, made as BB's importer makes them.

Cited from beam-bots/bb (Apache-2.0):

* ``lib/bb/urdf/parser.ex:125-144`` @23b6bde: links and joints are the ``<link>`` and ``<joint>``
  children of ``<robot>``.
* ``lib/bb/urdf/importer.ex`` @64ab268: ``prepare/1`` (:93-98) drops joints whose parent link
  is not defined (:117-135, "URDF world anchor?"), then renames a joint whose name a link or an
  earlier joint already has to ``<name>_joint`` (``<name>_joint_2``, ... on a further clash,
  :137-173); ``atom_name/1`` (:485-493) turns every byte outside ``[A-Za-z0-9_]`` into ``_``
  and puts ``_`` before a leading digit.
* ``lib/bb/dsl/uniqueness_transformer.ex:7-11`` @107cca2: link, joint, sensor and actuator names
  must be unique across the whole robot.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field, replace

from lxml import etree

from txtool.io.xmlio import local

_NOT_ATOM_BYTE = re.compile(rb"[^A-Za-z0-9_]")
_PLAIN_ATOM = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")


def atom_name(name: str) -> str:
    """BB's atom for a URDF name, as text (``weird-name.1`` -> ``weird_name_1``).

    BB's regex works on the UTF-8 bytes, so a two-byte character becomes two underscores.
    """
    text = _NOT_ATOM_BYTE.sub(b"_", name.encode("utf-8")).decode("ascii")
    return "_" + text if text[:1].isdigit() else text


def elixir_atom(text: str) -> str:
    """An atom literal: ``:weird_name_1``, or quoted where the text is no plain identifier."""
    if _PLAIN_ATOM.fullmatch(text):
        return ":" + text
    escaped = text.replace("\\", "\\\\").replace('"', '\\"')
    return f':"{escaped}"'


@dataclass(frozen=True)
class UrdfJoint:
    """A ``<joint>`` child of ``<robot>`` with what the topology needs."""

    name: str
    type: str
    parent: str | None
    child: str | None
    element: etree._Element
    bb_name: str = ""  # its name in BB


@dataclass
class RobotNames:
    """The robot's links and joints, under the names BB's importer gives them."""

    links: dict[str, str] = field(default_factory=dict)  # URDF link name -> BB name
    joints: dict[str, str] = field(default_factory=dict)  # kept URDF joint -> BB name
    dropped: dict[str, str] = field(default_factory=dict)  # URDF joint -> its missing parent
    urdf_joints: list[UrdfJoint] = field(default_factory=list)  # the kept ones, in order

    def taken(self) -> set[str]:
        """BB names already used by links and joints."""
        return set(self.links.values()) | set(self.joints.values())


def robot_names(root: etree._Element) -> RobotNames:
    names = RobotNames()
    if local(root) != "robot":
        return names
    for link in root.iterchildren("{*}link"):
        name = link.get("name", "")
        names.links.setdefault(name, atom_name(name))
    used = set(names.links)
    for element in root.iterchildren("{*}joint"):
        joint = _urdf_joint(element)
        if joint.parent not in names.links:
            names.dropped[joint.name] = joint.parent or ""
            continue
        renamed = joint.name
        if renamed in used:
            renamed = unique_name(joint.name + "_joint", used)
        used.add(renamed)
        names.joints.setdefault(joint.name, atom_name(renamed))
        names.urdf_joints.append(replace(joint, bb_name=atom_name(renamed)))
    return names


def unique_name(base: str, used: set[str]) -> str:
    """``base``, or ``base_2``, ``base_3``, ... : the first one not in ``used``."""
    if base not in used:
        return base
    n = 2
    while f"{base}_{n}" in used:
        n += 1
    return f"{base}_{n}"


def _urdf_joint(element: etree._Element) -> UrdfJoint:
    parent = next(element.iterchildren("{*}parent"), None)
    child = next(element.iterchildren("{*}child"), None)
    return UrdfJoint(
        name=element.get("name", ""),
        type=element.get("type", "fixed"),  # BB's parser defaults a missing type to fixed
        parent=parent.get("link") if parent is not None else None,
        child=child.get("link") if child is not None else None,
        element=element,
    )
