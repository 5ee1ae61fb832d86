"""``roundtrip`` of a robot that repeats transmissions under other names, cycled once per shape.

A large robot repeats a few transmissions thousands of times; converting the whole document through
every cycle costs seconds per thousand. A transmission that repeats an earlier one (its *first*) up
to the names (the same :class:`.repeated.renamings.Renaming` key) and whose joints are alike (the
same type, limits and dynamics) comes back from every cycle as its first does, with its names put
in: every conversion reads names only to tell them apart and to order them
(:mod:`.repeated.renamings`), and the equivalence check reads the joints only through their limits.
So each such *follower* is left out of the document that is cycled, and takes its first's rows.
Where those rows say nothing (every field kept, the behaviour equivalent, no detail) the follower's
are the same with its name; where they say something, the follower is cycled in full, as a detail
may name what it lost.

That needs each follower and its first to stand apart from everything else the conversions
read: none of their names is used by another transmission (both would then read the other's
members) or names a ``<ros2_control>`` block; in a block, the declarations of their joints are
keyed with them and leave with them (see :class:`_Blocks` for when that changes nothing else);
outside the blocks, none declares their joints; a transmission inside another element is not
keyed. The document has no carried original (:mod:`.reversible`, a comment beside a
transmission), every block is a child of the root, and the document is the file as written,
not a xacro expansion. The document cycled also leaves out the root's URDF ``<link>`` and
``<joint>`` children: conversions never read them, and the equivalence check reads the joints
of the whole document, found before.
"""

from __future__ import annotations

import copy
from collections import Counter
from collections.abc import Hashable
from typing import NamedTuple

from lxml import etree

from txtool.dialects.read import transmission_elements
from txtool.io.xmlio import Source, parse_bytes
from txtool.model.robot import JointsOnDemand, child_index, children, joint_info
from txtool.transform.repeated.renamings import renaming_of

# What the cycled document leaves out besides the followers: URDF parts no conversion reads.
_URDF_PARTS = frozenset({"link", "joint"})
_CARRIED = b"txtool-original"


class Plan(NamedTuple):
    """The transmissions of a document, by position: which follow which first."""

    elements: list[etree._Element]  # every <transmission>, in document order
    first_of: dict[int, int]  # a follower's position -> its first's
    declarations: dict[int, list[etree._Element]]  # in a block: its joints' declarations

    def without(self, firsts: set[int]) -> Plan:
        """The plan in which the followers of ``firsts`` are cycled in full."""
        return self._replace(first_of={f: p for f, p in self.first_of.items()
                                       if p not in firsts})


def plan_repeats(source: Source, joints: JointsOnDemand) -> Plan | None:
    """The followers of ``source``, or None where none can be left out."""
    root = source.root
    if source.expanded or _CARRIED in source.data:
        return None
    elements = transmission_elements(root)
    blocks = _Blocks(root)
    if len(elements) < 2 or not blocks.apart:
        return None
    keys: list[Hashable | None] = []
    uses: Counter[str] = Counter()
    known: dict[tuple, tuple | None] = {}
    names_of: list[set[str]] = []
    for element in elements:
        renaming = renaming_of(element)
        names = _names(element) if renaming is None else set(renaming.names)
        if renaming is not None and any(isinstance(n, str) for n in renaming.key[1]):
            renaming = None  # a literal name (actuator1, *) is not told apart by its key
        uses.update(names)
        names_of.append(names)
        place = None if renaming is None else blocks.place(element)
        keys.append(None if place is None else
                    (renaming.key, place, _joints_alike(element, joints, known)))
    firsts: dict[Hashable, int] = {}
    first_of: dict[int, int] = {}
    for position, (key, names) in enumerate(zip(keys, names_of, strict=True)):
        if key is None or any(uses[n] > 1 for n in names) or blocks.named(names):
            continue
        first = firsts.setdefault(key, position)
        if first != position:
            first_of[position] = first
    if not first_of:
        return None
    return Plan(elements, first_of, {f: blocks.declarations(elements[f]) for f in first_of})


class _Blocks:
    """The ``<ros2_control>`` blocks of a document, and where a transmission stands among them.

    A transmission in a block reads the declarations of its joints there: one is keyed with
    them, and only where removing it with them from the block changes nothing else. That is
    so where every joint the block declares is declared once in the document, and the block
    declares exactly the joints of its transmissions, in the order they name them (as txtool
    generates a block: converting back recognises a generated block by building it again).
    A transmission outside the blocks is keyed only when none of them declares its joints
    (converting it to ROS 2 would move it into that block).
    """

    def __init__(self, root: etree._Element) -> None:
        self.root = root
        self.blocks = {block: index for index, block in enumerate(root.iter("{*}ros2_control"))}
        self.apart = all(block.getparent() is root for block in self.blocks)
        self.declared: Counter[str | None] = Counter(
            joint.get("name") for block in self.blocks for joint in children(block, "joint"))
        self._orderly: dict[etree._Element, dict[str, etree._Element] | None] = {}

    def place(self, element: etree._Element) -> Hashable | None:
        """What a transmission's conversions read besides it, or None where that is more
        than its block's declarations of its joints."""
        parent = element.getparent()
        names = [member.get("name", "") for member in children(element, "joint")]
        if parent is self.root:
            return None if any(self.declared[name] for name in names) else ()
        declared = self._declarations_of(parent) if parent in self.blocks else None
        if declared is None:
            return None
        shapes = [_declaration_shape(declared[name], name) for name in names]
        if None in shapes:
            return None
        return self.blocks[parent], tuple(shapes)

    def named(self, names: set[str]) -> bool:
        """Whether a block is named like one of ``names`` (converting back reads a block
        around one transmission that bears its name as generated)."""
        return any(block.get("name") in names for block in self.blocks)

    def declarations(self, element: etree._Element) -> list[etree._Element]:
        parent = element.getparent()
        if parent is self.root:
            return []
        declared = self._orderly[parent]
        assert declared is not None
        return [declared[member.get("name", "")] for member in children(element, "joint")]

    def _declarations_of(self, block: etree._Element) -> dict[str, etree._Element] | None:
        """The block's declarations by joint name, where it is orderly (above)."""
        if block not in self._orderly:
            declared = [(joint.get("name"), joint) for joint in children(block, "joint")]
            named = [member.get("name", "") for t in children(block, "transmission")
                     for member in children(t, "joint")]
            orderly = [name for name, _ in declared] == list(dict.fromkeys(named)) and all(
                self.declared[name] == 1 for name, _ in declared)
            self._orderly[block] = {name: joint for name, joint in declared  # type: ignore[misc]
                                    } if orderly else None
        return self._orderly[block]


def _declaration_shape(declaration: etree._Element, name: str) -> bytes | None:
    """A joint's declaration as written, but for its own name."""
    data = etree.tostring(declaration, with_tail=False)
    named = b' name="' + name.encode("ascii", "xmlcharrefreplace") + b'"'
    head = data[:data.find(b">")]
    if b"<!" in data or b"<?" in data or b"&" in named or head.count(named) != 1:
        return None
    return data.replace(named, b"", 1)


def _names(element: etree._Element) -> set[str]:
    """Every name="..." value in a transmission that is not keyed."""
    return {node.get("name") for node in element.iter()
            if isinstance(node.tag, str) and node.get("name") is not None}


def _joints_alike(element: etree._Element, joints: JointsOnDemand,
                  known: dict[tuple, tuple | None]) -> tuple:
    """What the cycles read of a transmission's URDF joints (in the order it names them):
    unlike any other where a joint is missing or mimics another (then it is no one's
    follower). ``known``: each reading by what it reads (joints written alike read alike)."""
    alike = []
    for member in children(element, "joint"):
        joint = joints.elements.get(member.get("name", ""))
        if joint is None:
            return (object(),)  # equal to nothing
        kids = child_index(joint)
        written = (joint.get("type"), _attributes(kids, "limit"), _attributes(kids, "dynamics"),
                   _attributes(kids, "mimic"))
        if written not in known:
            info = joint_info(joint)
            known[written] = None if info.mimic is not None else (
                info.type, repr(info.lower), repr(info.upper), repr(info.velocity),
                repr(info.effort), repr(info.damping), repr(info.friction))
        if known[written] is None:
            return (object(),)
        alike.append(known[written])
    return tuple(alike)


def _attributes(kids: dict[str, list[etree._Element]], name: str) -> tuple | None:
    """The attributes of the first child ``name`` (the one a joint is read from)."""
    found = kids.get(name)
    return tuple(found[0].items()) if found else None


def cycled_document(source: Source, plan: Plan) -> Source:
    """``source`` without the followers of ``plan`` (and their joints' declarations) and the
    root's URDF links and joints."""
    root = source.root
    left_out = {id(plan.elements[f]) for f in plan.first_of}
    left_out.update(id(d) for f in plan.first_of for d in plan.declarations[f])
    shell = _kept(root, left_out, parts=_URDF_PARTS)
    data = etree.tostring(shell, encoding="utf-8", xml_declaration=True)
    return Source(source.path, data, parse_bytes(data, source.path, limit=None))


def _kept(element: etree._Element, left_out: set[int], parts: frozenset[str] = frozenset()
          ) -> etree._Element:
    """A copy of ``element`` without the children in ``left_out`` or named in ``parts``;
    a ``<ros2_control>`` child copied the same way."""
    shell = etree.Element(element.tag, dict(element.attrib), nsmap=element.nsmap)
    shell.text = element.text
    shell.tail = element.tail
    for child in element:
        if id(child) in left_out or child.tag in parts:
            continue
        if isinstance(child.tag, str) and child.tag.rpartition("}")[2] == "ros2_control":
            shell.append(_kept(child, left_out))
        else:
            shell.append(copy.copy(child))
    return shell
