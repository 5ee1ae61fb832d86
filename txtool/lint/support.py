"""Helpers shared by rules: members with their elements, xacro-aware scoping, type families."""

from __future__ import annotations

from collections.abc import Callable, Iterator
from dataclasses import dataclass
from typing import Any

from lxml import etree

from txtool.dialects.read import Found, enclosing_component
from txtool.io.xmlio import is_xacro_element, local
from txtool.lint.context import LintContext
from txtool.model.core import Member
from txtool.model.numbers import C_SPACE
from txtool.model.robot import JointInfo, children

# Transmission families with their own loaders (not ros_control's transmission_interface):
# pr2_mechanism / ros_ethercat parse their own XML; franka_hw registers state/model interfaces.
OWN_LOADER_FAMILIES: tuple[str, ...] = ("pr2_mechanism_model/", "sr_mechanism_model/")
KNOWN_FAMILIES: tuple[str, ...] = (*OWN_LOADER_FAMILIES, "franka_hw/")


@dataclass(frozen=True)
class MemberRef:
    """A joint or actuator of a transmission, with the element it was read from."""

    noun: str  # "joint" or "actuator"
    member: Member
    element: etree._Element


def members(found: Found) -> list[MemberRef]:
    """Joints then actuators, paired with their elements (same order as the model)."""
    known = found.memo.get("members")  # _memo inlined: rules ask this most
    return known if known is not None else _memo(found, "members", _members)


def _members(found: Found) -> list[MemberRef]:
    refs = []
    transmission = found.transmission
    for noun, models in (("joint", transmission.joints), ("actuator", transmission.actuators)):
        for member, element in zip(models, children(found.element, noun), strict=True):
            refs.append(MemberRef(noun, member, element))
    return refs


def _memo(found: Found, what: str, compute: Callable[[Found], Any]) -> Any:
    """Every rule asks the same questions of each transmission: answer each once."""
    memo = found.memo
    if what in memo:
        return memo[what]
    value = memo[what] = compute(found)
    return value


# xacro itself goes by the "xacro:" prefix; files use several namespace spellings.
is_xacro = is_xacro_element


def opaque(ctx: LintContext, element: etree._Element) -> bool:
    """True when a literal xacro element's children depend on xacro (conditionals, macro calls).

    Counting or pairing its joints and actuators would then be guesswork.
    """
    return ctx.literal and any(is_xacro(child) for child in element)


def scope(ctx: LintContext, element: etree._Element) -> tuple[etree._Element, ...] | None:
    """A key under which elements are instantiated together, or None when that is unknowable.

    After expansion every element is real (one scope). In a literal xacro file, elements under
    different macros are only comparable when the same macro holds them, and never under
    ``xacro:if`` / ``xacro:unless`` (both branches are written but only one is produced).
    """
    if not ctx.literal:
        return ()
    # Elements themselves, not id(): lxml proxies are recreated, keeping them keeps them stable.
    key: list[etree._Element] = []
    parent = element.getparent()
    while parent is not None:
        if is_xacro(parent):
            if local(parent) in ("if", "unless"):
                return None
            key.append(parent)
        parent = parent.getparent()
    return tuple(key)


def type_element(found: Found) -> etree._Element | None:
    """The element that carries the type: ``<plugin>`` (ROS 2) or ``<type>`` (ROS 1)."""
    memo = found.memo
    if "type_element" in memo:  # _memo inlined: rules ask this most
        return memo["type_element"]  # type: ignore[no-any-return]
    return _memo(found, "type_element", _type_element)  # type: ignore[no-any-return]


def _type_element(found: Found) -> etree._Element | None:
    name = "type" if found.transmission.dialect == "ros1" else "plugin"
    elements = children(found.element, name)
    return elements[0] if elements else None


def typed_ros1(found: Found) -> bool:
    """A ROS 1 transmission ros_control gets past parsing: it has a ``<type>`` element.

    With only the pre-Hydro ``type=`` attribute the parser skips it before any loader runs.
    """
    return found.transmission.dialect == "ros1" and type_element(found) is not None


def parsed(found: Found) -> bool:
    """Whether the transmission gets past its loader's parser (ROS 1: a name and a ``<type>``).

    ros_control skips a transmission without a name or type, so it takes part in no
    comparison with others; ros2_control's parser throws instead, reported on its own.
    """
    if found.transmission.dialect != "ros1":
        return True
    return bool(found.transmission.name.strip()) and typed_ros1(found)


def loaded_by_ros_control(found: Found) -> bool:
    """Whether ros_control's own parser handles this transmission (not a custom loader)."""
    kind_type = found.transmission.type
    return not kind_type.startswith(OWN_LOADER_FAMILIES)


@dataclass(frozen=True)
class NumberRef:
    """A number element a loader reads: ``field`` is "reduction" or "offset"."""

    element: etree._Element
    field: str
    noun: str
    member: str
    text: str | None  # what the loader parses (see loader_text): read once, several rules ask

    def describe(self) -> str:
        return f"{self.field} of {self.noun} '{self.member}'"


_NODES = etree.XPath("node()")
_TEXTS = etree.XPath("text()")


def all_text(element: etree._Element) -> str:
    """Every text node of the element itself (CDATA included, comments and children not)."""
    return "".join(str(node) for node in _TEXTS(element))


def loader_text(element: etree._Element) -> str | None:
    """The text TinyXML's ``GetText()`` gives the loaders: the element's first child node when
    it is text (CDATA counts as text), else None.

    A number split by a comment or CDATA section (``5<!-- x -->0``) is read up to the split only,
    and an element that starts with a comment has no text at all. Whitespace alone is not a
    node for TinyXML (tinyxml2 ``XMLDocument::Identify`` skips it before the next node or end
    tag; TinyXML 1 drops blank text), so it does not count.
    """
    for node in _NODES(element):
        if not isinstance(node, str):
            return None
        if node.strip(C_SPACE):
            return str(node)
    return None


def read_numbers(found: Found) -> list[NumberRef]:
    """The reduction and offset elements the transmission's loader reads (standard types)."""
    known = found.memo.get("read_numbers")
    return known if known is not None else _memo(found, "read_numbers", _numbers)


def _numbers(found: Found) -> list[NumberRef]:
    return list(_each_number(found))


def _each_number(found: Found) -> Iterator[NumberRef]:
    t = found.transmission
    if t.kind == "other" or (t.dialect == "ros1" and not typed_ros1(found)):
        return
    ros1 = t.dialect == "ros1"
    coupled = t.kind != "simple"
    reduction = "mechanicalReduction" if ros1 else "mechanical_reduction"
    seen = {"joint": 0, "actuator": 0}
    for ref in members(found):
        seen[ref.noun] += 1
        if not ros1 and seen[ref.noun] > (2 if coupled else 1):
            continue  # ros2_control reads only the first one or two
        tags: list[str] = []
        if ref.noun == "actuator" and (ros1 or coupled):
            tags.append(reduction)
        if ref.noun == "joint":
            tags += [reduction, "offset"] if (coupled or not ros1) else ["offset"]
        for tag in tags:
            element = _number_element(ref.element, tag, ros1)
            if element is not None:
                field = "offset" if tag == "offset" else "reduction"
                yield NumberRef(element, field, ref.noun, ref.member.name, loader_text(element))


def _number_element(member: etree._Element, tag: str, ros1: bool) -> etree._Element | None:
    found = children(member, tag)
    if not found:
        return None
    if not ros1:
        # ros2_control takes the first element whose GetText() is not null
        # (ros2_control hardware_interface/src/component_parser.cpp:134-161 @157446a).
        return next((e for e in found if loader_text(e) is not None), found[0])
    return found[0]


def label(found: Found) -> str:
    """``transmission 'name'`` for messages (or ``unnamed transmission``)."""
    name = found.transmission.name
    return f"transmission '{name}'" if name else "unnamed transmission"


def loader_group(found: Found) -> tuple[object, ...]:
    """Transmissions read by the same loader instance: ROS 1, or one ``<ros2_control>``."""
    if found.transmission.dialect == "ros1":
        return ("ros1",)
    component = enclosing_component(found.element)
    return ("ros2", component)


def robot_joints_of_transmissions(
    ctx: LintContext,
) -> list[tuple[Found, etree._Element, JointInfo]]:
    """(transmission, its ``<joint>`` element, the robot's joint) for standard transmissions;
    found once per document, several rules ask."""
    known = ctx.memo.get("robot_joints")
    if known is None:
        known = ctx.memo["robot_joints"] = list(_robot_joints(ctx))
    return known  # type: ignore[no-any-return]


def _robot_joints(ctx: LintContext) -> Iterator[tuple[Found, etree._Element, JointInfo]]:
    if not ctx.is_robot:
        return
    joints = ctx.joints
    for found in ctx.transmissions():
        if found.transmission.kind == "other":
            continue
        for joint in children(found.element, "joint"):
            info = joints.get(joint.get("name", ""))
            if info is not None:
                yield found, joint, info


def interface_texts(element: etree._Element) -> list[str]:
    """The non-empty ``<hardwareInterface>`` texts of a ROS 1 joint or actuator, stripped."""
    texts = ((h.text or "").strip() for h in children(element, "hardwareInterface"))
    return [text for text in texts if text]
