"""The parts of a robot description that transmissions refer to, read with lxml.

URDF ``<joint>`` elements (type, limits, mimic, dynamics) and ROS 2 ``<ros2_control>`` components
(their joints and interfaces). Light on purpose: no yourdfpy, no pinocchio.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Iterator, Mapping
from dataclasses import dataclass
from functools import cached_property
from typing import Any, NamedTuple

from lxml import etree

from txtool.io.xmlio import local
from txtool.model.numbers import parse_strict


class JointInfo(NamedTuple):
    name: str
    type: str
    lower: float | None = None
    upper: float | None = None
    velocity: float | None = None
    effort: float | None = None
    damping: float = 0.0
    friction: float = 0.0
    mimic: str | None = None
    line: int = 0

    @property
    def is_fixed(self) -> bool:
        return self.type == "fixed"

    @property
    def is_linear(self) -> bool:
        return self.type == "prismatic"

    def position_range(self) -> tuple[float, float]:
        """The joint's position limits; +-pi where absent (continuous joints)."""
        bounded = self.lower is not None and self.upper is not None
        if self.type != "continuous" and bounded and self.lower < self.upper:
            return self.lower, self.upper
        return -math.pi, math.pi


class ComponentJoint(NamedTuple):
    name: str
    command_interfaces: tuple[str, ...]
    state_interfaces: tuple[str, ...]
    line: int = 0


@dataclass(frozen=True)
class Component:
    """One ``<ros2_control>`` element."""

    name: str
    type: str
    plugin: str | None
    joints: tuple[ComponentJoint, ...]
    line: int = 0

    def joint(self, name: str) -> ComponentJoint | None:
        return self._by_name.get(name)

    @cached_property
    def _by_name(self) -> dict[str, ComponentJoint]:
        by_name: dict[str, ComponentJoint] = {}
        for joint in self.joints:
            by_name.setdefault(joint.name, joint)  # the first of a repeated name, as before
        return by_name


def children(element: etree._Element, name: str) -> list[etree._Element]:
    """Child elements named ``name`` in any namespace (or none)."""
    # A plain loop: iterchildren("{*}" + name) sets up a tag matcher on every call. Iterated,
    # not listed at once: each child's proxy goes as the loop passes it, where a list of
    # thousands (comments in a transmission) would hold them for the garbage collector to
    # walk, whose passes grow with everything a long-lived process holds.
    found = []
    qualified = "}" + name
    for child in element:
        tag = child.tag  # a function for comments and processing instructions
        if tag == name or tag.__class__ is str and tag.endswith(qualified):
            found.append(child)
    return found


def child_index(element: etree._Element) -> dict[str, list[etree._Element]]:
    """Child elements by local name, in document order: one pass for many lookups."""
    index: dict[str, list[etree._Element]] = {}
    for child in element[:]:  # the list in one call: iterating sets up an iterator per element
        tag = child.tag
        if tag.__class__ is str:  # not a comment or processing instruction
            if tag[0] == "{":
                tag = tag.rpartition("}")[2]
            found = index.get(tag)
            if found is None:
                index[tag] = [child]
            else:
                found.append(child)
    return index


def robot_joints(root: etree._Element) -> dict[str, JointInfo]:
    """The URDF joints of a document (see :func:`joint_elements`) by name, limits included."""
    return {name: joint_info(element) for name, element in joint_elements(root).items()}


def joint_elements(
    root: etree._Element, candidates: Iterable[etree._Element] | None = None
) -> dict[str, etree._Element]:
    """The URDF ``<joint>`` elements of a document by name: any depth, outside
    ``<ros2_control>`` and ``<transmission>``, with a name and a type (of a repeated name, the
    last). ``candidates`` are the tree's ``<joint>`` elements when the caller has them."""
    joints: dict[str, etree._Element] = {}
    not_urdf = ("ros2_control", "transmission")
    root_is_urdf = local(root) not in not_urdf
    for element in root.iter("{*}joint") if candidates is None else candidates:
        parent = element.getparent()
        if parent is root:  # where URDF joints stand: no walk needed
            if not root_is_urdf:
                continue
        elif parent is not None and (parent.tag in not_urdf or _inside(element, not_urdf)):
            continue  # the first test: a transmission's or component's own joint
        name = element.get("name")
        if name is not None and element.get("type") is not None:
            joints[name] = element
    return joints


def joint_info(element: etree._Element, *, limits: bool = True) -> JointInfo:
    """One ``<joint>`` element read; with ``limits=False`` its limits and dynamics are not."""
    name = element.get("name", "")
    if limits:
        return _joint_info(element, name)
    mimic = next(element.iterchildren("{*}mimic"), None)
    return JointInfo(
        name=name, type=element.get("type", ""),
        mimic=mimic.get("joint") if mimic is not None else None,
        line=element.sourceline or 0,
    )


def _inside(element: etree._Element, names: tuple[str, ...]) -> bool:
    parent = element.getparent()
    while parent is not None:
        if parent.tag.rpartition("}")[2] in names:  # a parent is an element: its tag is a str
            return True
        parent = parent.getparent()
    return False


def ancestor(element: etree._Element, name: str) -> etree._Element | None:
    """The nearest ancestor named ``name`` in any namespace (or none), else None."""
    # A walk with string tests: lxml's iterancestors() costs more to set up than this.
    qualified = "}" + name
    parent = element.getparent()
    while parent is not None:
        tag = parent.tag  # a parent is always an element: its tag is a string
        if tag == name or tag.endswith(qualified):
            return parent
        parent = parent.getparent()
    return None


def _attr_number(element: etree._Element | None, key: str) -> float | None:
    if element is None:
        return None
    return parse_strict(element.get(key))


def _joint_info(element: etree._Element, name: str) -> JointInfo:
    kids = child_index(element)
    limit = _first(kids, "limit")
    dynamics = _first(kids, "dynamics")
    mimic = _first(kids, "mimic")
    return JointInfo(
        name=name,
        type=element.get("type", ""),
        lower=_attr_number(limit, "lower"),
        upper=_attr_number(limit, "upper"),
        velocity=_attr_number(limit, "velocity"),
        effort=_attr_number(limit, "effort"),
        damping=_attr_number(dynamics, "damping") or 0.0,
        friction=_attr_number(dynamics, "friction") or 0.0,
        mimic=mimic.get("joint") if mimic is not None else None,
        line=element.sourceline or 0,
    )


def _first(index: dict[str, list[etree._Element]], name: str) -> etree._Element | None:
    found = index.get(name)
    return found[0] if found else None


def components(
    root: etree._Element, candidates: Iterable[etree._Element] | None = None
) -> list[Component]:
    """Every ``<ros2_control>`` element (the root itself for a bare fragment), or those
    among ``candidates`` the caller collected."""
    elements = root.iter("{*}ros2_control") if candidates is None else candidates
    return [component_of(element) for element in elements]


def component_of(element: etree._Element) -> Component:
    hardware = next(iter(children(element, "hardware")), None)
    plugin = None
    if hardware is not None:
        plugin_el = next(iter(children(hardware, "plugin")), None)
        plugin = (plugin_el.text or "").strip() if plugin_el is not None else None
    joints = tuple(
        ComponentJoint(
            name=j.get("name", ""),
            command_interfaces=tuple(c.get("name", "") for c in children(j, "command_interface")),
            state_interfaces=tuple(s.get("name", "") for s in children(j, "state_interface")),
            line=j.sourceline or 0,
        )
        for j in children(element, "joint")
    )
    return Component(
        name=element.get("name", ""),
        type=element.get("type", ""),
        plugin=plugin,
        joints=joints,
        line=element.sourceline or 0,
    )


class JointsOnDemand(Mapping[str, JointInfo]):
    """:func:`robot_joints`, each joint read when first asked for: a document's transmissions
    name a few of its hundreds or thousands of joints. ``limits=False`` reads no limits or
    dynamics (as :func:`joint_info`)."""

    def __init__(self, elements: dict[str, etree._Element], *, limits: bool = True) -> None:
        self.elements = elements
        self._limits = limits
        self._read: dict[str, JointInfo] = {}

    def __getitem__(self, name: str) -> JointInfo:
        info = self._read.get(name)
        if info is None:
            info = self._read[name] = joint_info(self.elements[name], limits=self._limits)
        return info

    def get(self, name: str, default: Any = None) -> Any:  # Mapping.get, without its raise
        info = self._read.get(name)
        if info is not None:
            return info
        return self[name] if name in self.elements else default

    def __contains__(self, name: object) -> bool:
        return name in self.elements

    def __iter__(self) -> Iterator[str]:
        return iter(self.elements)

    def __len__(self) -> int:
        return len(self.elements)
