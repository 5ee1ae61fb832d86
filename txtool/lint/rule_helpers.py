"""Helpers shared by rules: members with their elements, xacro-aware scoping, type families."""

from __future__ import annotations

import sys
from collections.abc import Callable, Iterable, Iterator
from functools import lru_cache

from lxml import etree

from txtool.dialects.read import Found
from txtool.io.xmlio import is_xacro_element, local
from txtool.lint.context import LintContext
from txtool.lint.facts import OWN_LOADER_FAMILIES, Facts, MemberRef, facts_of
from txtool.lint.problem import Problem
from txtool.model.core import TYPE_PREFIX, Member
from txtool.model.distro import Distro, NumberReading
from txtool.model.distro import numbers_of as numbers_of_distro
from txtool.model.numbers import C_SPACE, parse_ros2
from txtool.model.robot import children

KNOWN_FAMILIES: tuple[str, ...] = (*OWN_LOADER_FAMILIES, "franka_hw/")

PREFIX = "hardware_interface/"
# The interface names ros_control registers with pluginlib (see TX204).
ROS1_INTERFACES: tuple[str, ...] = tuple(
    PREFIX + name
    for name in (
        "JointStateInterface",
        "PositionJointInterface",
        "VelocityJointInterface",
        "EffortJointInterface",
        "BiDirectionalPositionJointInterface",
        "BiDirectionalVelocityJointInterface",
        "BiDirectionalEffortJointInterface",
    )
)
REGISTERED = frozenset(ROS1_INTERFACES)  # for set tests of many names at once
# ros2_control's spellings of ROS 1 tags (see TX303).
ROS2_SPELLINGS = frozenset({"mechanical_reduction", "hardware_interface"})


def members(found: Found) -> list[MemberRef]:
    """Joints then actuators, paired with their elements (same order as the model)."""
    return facts_of(found).members


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


class NumberRef:
    """A number element a loader reads: ``field`` is "reduction" or "offset".

    ``text`` is what the loader parses (see :func:`loader_text`), read once: several rules ask;
    ``written`` is the element's ``text`` (its text before any child or comment).
    """

    __slots__ = ("element", "field", "noun", "member", "text", "unknown", "unknown_written",
                 "single", "strict")

    def __init__(self, element: etree._Element, field: str, noun: str, member: str,
                 text: str | None, single: bool, written: str | None) -> None:
        self.element = element
        self.field = field
        self.noun = noun
        self.member = member
        self.text = text
        # Only xacro can tell the value (see LintContext.unknown): the element's text as
        # written, or the text the loader reads.
        unknown = self.unknown_written = written is not None and (
            "${" in written or "$(" in written)
        self.unknown = unknown or (text is not None and ("${" in text or "$(" in text))
        # The element's one text node is its text (see Facts.plain): what the loader reads is
        # all the element holds.
        self.single = single
        # ``parse_ros2`` of the text: ros2_control's reading, a plain finite number or None
        # (every number rule asks).
        self.strict: float | None = parse_ros2(text)

    def describe(self) -> str:
        return f"{self.field} of {self.noun} '{self.member}'"

    def all_text(self) -> str:
        """Every text node of the element (see :func:`all_text`)."""
        if self.single:
            return self.element.text or ""
        return all_text(self.element)


_NODES = etree.XPath("node()")
_TEXTS = etree.XPath("text()")


def all_text(element: etree._Element) -> str:
    """Every text node of the element itself (CDATA included, comments and children not)."""
    return "".join(str(node) for node in _TEXTS(element))


def loader_text(element: etree._Element, plain: bool = False,
                ros2: bool = False) -> str | None:
    """The text TinyXML's ``GetText()`` gives the loaders: the element's first child node when
    it is text (CDATA counts as text), else None.

    A number split by a comment or CDATA section (``5<!-- x -->0``) is read up to the split only,
    and an element that starts with a comment has no text at all. Whitespace alone is not a
    node for TinyXML (tinyxml2 ``XMLDocument::Identify`` skips it before the next node or end
    tag; TinyXML 1 drops blank text), so it does not count.

    ``plain``: the document holds no CDATA section (see :attr:`Facts.plain`), so an element
    without children (comments count) has at most one text node, its ``text``. ``ros2``:
    read as ros2_control's tinyxml2 (9.0 and later) reads it, whose ``GetText()`` passes over
    leading comments (``<offset><!-- rad -->0.5</offset>`` is 0.5; see
    :func:`txtool.dialects.read.get_text`).
    """
    if plain and not len(element):
        text = element.text
        return text if text is not None and text.strip(C_SPACE) else None
    for node in _NODES(element):
        if not isinstance(node, str):
            if ros2 and isinstance(node, etree._Comment):
                continue
            return None
        if node.strip(C_SPACE):
            return str(node)
    return None


def numbers_of(facts: Facts) -> list[NumberRef]:
    """The reduction and offset elements the transmission's loader reads (standard types), found
    once per transmission."""
    known: list[NumberRef] | None = facts.numbers  # type: ignore[assignment]
    if known is None:
        known = facts.numbers = _read_numbers(facts)
    return known


def _read_numbers(facts: Facts) -> list[NumberRef]:
    found: list[NumberRef] = []
    if facts.kind == "other" or (facts.ros1 and not facts.typed_ros1):
        return found
    ros1 = facts.ros1
    plain = facts.plain
    coupled = facts.kind != "simple"
    reduction = "mechanicalReduction" if ros1 else "mechanical_reduction"
    if ros1:  # ros_control reads every member
        joint_tags = (reduction, "offset") if coupled else ("offset",)
        actuator_tags: tuple[str, ...] = (reduction,)
        joints, actuators = facts.joints, facts.actuators
    else:  # ros2_control reads only the first one or two
        joint_tags = (reduction, "offset")
        actuator_tags = (reduction,) if coupled else ()
        first = 2 if coupled else 1
        joints, actuators = facts.joints[:first], facts.actuators[:first]
    for refs, tags in ((joints, joint_tags), (actuators, actuator_tags)):
        for ref in refs:
            for tag in tags:
                elements = ref.tagged(tag)
                if not elements:
                    continue
                element = elements[0] if ros1 else _number_element(elements, plain)
                field = "offset" if tag == "offset" else "reduction"
                found.append(NumberRef(element, field, ref.noun, ref.name,
                                       loader_text(element, plain, not ros1),
                                       plain and not len(element), element.text))
    return found


def ros2_readings_of(ctx: LintContext) -> tuple[NumberReading, ...]:
    """How the ROS 2 distributions that read this file read numbers (every ROS 2 build's when
    nothing says which: ``--ros-distro``, ``ros-distro`` in the configuration)."""
    readings = tuple(dict.fromkeys(numbers_of_distro(d) for d in ctx.readers.distros if d.ros2))
    return readings or (NumberReading.ISTRINGSTREAM, NumberReading.FROM_CHARS)


def _number_element(found: list[etree._Element], plain: bool) -> etree._Element:
    """The element ros2_control reads: the first whose GetText() is not null
    (ros2_control hardware_interface/src/component_parser.cpp:134-161 @157446a); ros_control
    reads the first."""
    return next((e for e in found if loader_text(e, plain, True) is not None), found[0])


def coupled_groups(
    tx: Facts,
) -> tuple[tuple[str, tuple[Member, ...], list[etree._Element], tuple[str, str]], ...]:
    """``(noun, members, their elements, the roles the loader expects)`` for the joints, then
    the actuators, of a transmission (the role rules of coupled transmissions read these)."""
    from txtool.model.semantics import ROLES_ACTUATOR, ROLES_JOINT  # coupled types only

    t, element = tx.found.transmission, tx.found.element
    return (("joint", t.joints, children(element, "joint"), ROLES_JOINT),
            ("actuator", t.actuators, children(element, "actuator"), ROLES_ACTUATOR))


def member_names(ctx: LintContext) -> tuple[list[str], list[str]]:
    """The joint names, then the actuator names, of every transmission in document order
    (found once per document: several rules ask)."""
    known = ctx.memo.get("member names")
    if known is None:
        joints: list[str] = []
        actuators: list[str] = []
        for tx in ctx.facts:
            for ref in tx.joints:
                joints.append(ref.name)
            for ref in tx.actuators:
                actuators.append(ref.name)
        known = ctx.memo["member names"] = (joints, actuators)
    return known  # type: ignore[no-any-return]


def in_actuator_component(tx: Facts) -> bool:
    """Whether ros2_control's parser reads ``tx`` as a transmission of an actuator component: a
    ROS 2 transmission right inside a ``<ros2_control type="actuator">`` (the type stripped, as
    the parser strips it from Jazzy on; get_attribute_value, component_parser.cpp:133)."""
    component = tx.component
    if tx.ros1 or component is None or tx.element.getparent() is not component:
        return False
    return (component.get("type") or "").strip(C_SPACE) == "actuator"


def read_blocks(ctx: LintContext) -> tuple[list[etree._Element], Callable[[str], str]]:
    """The ``<ros2_control>`` blocks ros2_control's parser reads (children of ``<robot>``,
    parse_control_resources_from_urdf) in document order, when two or more stand there and a
    ROS 2 program reads the document (xacro expanded); else none. With them, how the parser
    reads a name: stripped from Jazzy on, as written on Humble (component_parser.cpp
    get_attribute_value:133 @53b9999; the humble branch returns the attribute as it is)."""
    if not ctx.hints.components or ctx.literal or local(ctx.source.root) != "robot":
        return [], str
    blocks = list(ctx.source.root.iterchildren("{*}ros2_control"))
    if len(blocks) < 2:
        return [], str
    distros = [d for d in ctx.readers.distros if d.ros2]
    if not distros:
        return [], str  # only ROS 1 programs read the document: nothing reads the blocks
    if all(d is Distro.HUMBLE for d in distros):
        return blocks, str
    return blocks, _stripped


def _stripped(text: str) -> str:
    return text.strip(C_SPACE)


def label(found: Found) -> str:
    """``transmission 'name'`` for messages (or ``unnamed transmission``)."""
    return facts_of(found).label


def robot_joints_of_transmissions(
    ctx: LintContext,
) -> list[tuple[Found, etree._Element, etree._Element]]:
    """(transmission, its ``<joint>`` element, the robot's ``<joint>`` element) for standard
    transmissions; found once per document, several rules ask (read a joint through
    ``ctx.joints`` when it matters: most need none read)."""
    known = ctx.memo.get("robot_joints")
    if known is None:
        known = ctx.memo["robot_joints"] = list(_robot_joints(ctx))
    return known  # type: ignore[no-any-return]


def _robot_joints(ctx: LintContext) -> Iterator[tuple[Found, etree._Element, etree._Element]]:
    if not ctx.is_robot:
        return
    robot = ctx.joint_elements
    for tx in ctx.facts:
        if tx.kind == "other":
            continue
        for ref in tx.joints:
            element = robot.get(ref.name)  # the model's name is the element's
            if element is not None:
                yield tx.found, ref.element, element


_SIMPLE = TYPE_PREFIX + "SimpleTransmission"
_SMALLEST_NORMAL = sys.float_info.min


Check = Callable[[LintContext], Iterable[Problem]]


def whole_robot(check: Check) -> Check:
    """Mark a rule that also speaks about a document without transmissions: what makes the
    loader refuse the whole robot (the linter runs only these on such a document)."""
    check.whole_robot = True  # type: ignore[attr-defined]
    return check


def per_transmission(check: Check) -> Check:
    """Mark the check of a rule that looks at one transmission at a time: a document whose
    transmissions are all :func:`canonical` gives it nothing to say, so the linter does not
    call it for such a document (the check itself, called directly, looks at every
    transmission)."""
    check.per_transmission = True  # type: ignore[attr-defined]
    return check


def all_canonical(ctx: LintContext) -> bool:
    """Whether every transmission of the document is :func:`canonical` (found once per
    document): the rules about one transmission at a time then have nothing to say."""
    known: bool | None = ctx.memo.get("canonical")
    if known is None:
        known = True
        for tx in ctx.facts:  # noqa: SIM110 (a loop costs less than a generator, per document)
            if not canonical(tx):
                known = False
                break
        ctx.memo["canonical"] = known
    return known


def canonical(tx: Facts) -> bool:
    """A ROS 1 ``SimpleTransmission`` written as ros_control reads it, in a document without
    CDATA: a name, a ``<type>`` element of that exact text and no ``type=`` attribute; one
    named joint whose ``<hardwareInterface>`` texts are registered names (TX110, TX204,
    TX205, TX300, TX301 silent); one named actuator with a ``<mechanicalReduction>``; each
    number the loader reads (that reduction, the joint's ``<offset>``) a single text that
    parses as a normal, finite, plain number (TX104-TX106, TX111); no reduction or offset where
    ros_control never reads it (TX400) and no ros2_control spelling (TX303). The other rules
    about one transmission skip ROS 1 simple ones (``tests/lint/test_canonical.py`` runs
    every rule with and without this answer)."""
    if not tx.plain or tx.type_text != _SIMPLE or not tx.ros1:
        return False
    joints, actuators = tx.joints, tx.actuators
    if len(joints) != 1 or len(actuators) != 1:
        return False
    joint, actuator = joints[0], actuators[0]
    interfaces = joint.interfaces
    if not interfaces or not REGISTERED.issuperset(interfaces):
        return False
    if not (tx.name.strip() and joint.name.strip() and actuator.name.strip()):
        return False
    kids, own, driven = tx.kids, joint.kids, actuator.kids
    if "mechanicalReduction" in kids or "mechanicalReduction" in own or "offset" in driven:
        return False
    for spelling in ROS2_SPELLINGS:  # two lookups a dictionary cost less than a set operation
        if spelling in kids or spelling in own or spelling in driven:
            return False
    if tx.element.get("type") is not None:
        return False
    reductions = driven.get("mechanicalReduction")
    if reductions is None or not _normal_number(reductions[0]):
        return False
    offsets = own.get("offset")
    return offsets is None or _normal_number(offsets[0])


def _normal_number(element: etree._Element) -> bool:
    """An element without children (so, without CDATA, one text node) whose text parses as a
    plain, finite number of at least the smallest normal magnitude."""
    return not len(element) and _normal_text(element.text)


@lru_cache(maxsize=1024)  # the few number texts documents repeat
def _normal_text(text: str | None) -> bool:
    value = parse_ros2(text)
    return value is not None and abs(value) >= _SMALLEST_NORMAL
