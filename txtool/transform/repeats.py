"""``roundtrip`` of a robot that repeats transmissions under other names, cycled once per shape.

A large robot repeats a few transmissions thousands of times; converting the whole document
through every cycle costs seconds per thousand. A transmission that repeats an earlier one (its
*first*) up to the names (the same :class:`.memo.Renaming` key) and whose joints are alike
(the same type, limits and dynamics) comes back from every cycle as its first does, with its
names put in: every conversion reads names only to tell them apart and to order them
(:mod:`.memo`), and the equivalence check reads the joints only through their limits. So each
such *follower* is left out of the document that is cycled, and takes its first's rows. Where
those rows say nothing (every field kept, the behaviour equivalent, no detail) the follower's
are the same with its name; where they say something, the follower is cycled in full, as a
detail may name what it lost.

That needs each follower and its first to stand apart from everything else the conversions
read: none of their names is used by another transmission (both would then read the other's
members), the document has no ``<ros2_control>`` (a conversion reads its declarations) and no
carried original (:mod:`.reversible`, a comment beside a transmission), every transmission is
a child of the root (and none is inside a xacro macro), and the document is the file as
written, not a xacro expansion. The document cycled also leaves out the root's URDF ``<link>``
and ``<joint>`` children: conversions never read them, and the equivalence check reads the
joints of the whole document, found before.
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
from txtool.transform.memo import renaming_of

# What the cycled document leaves out besides the followers: URDF parts no conversion reads.
_URDF_PARTS = frozenset({"link", "joint"})
_CARRIED = b"txtool-original"


class Plan(NamedTuple):
    """The transmissions of a document, by position: which follow which first."""

    elements: list[etree._Element]  # every <transmission>, in document order
    first_of: dict[int, int]  # a follower's position -> its first's

    def without(self, firsts: set[int]) -> Plan:
        """The plan in which the followers of ``firsts`` are cycled in full."""
        return Plan(self.elements, {f: p for f, p in self.first_of.items() if p not in firsts})


def plan_repeats(source: Source, joints: JointsOnDemand) -> Plan | None:
    """The followers of ``source``, or None where none can be left out."""
    root = source.root
    if source.expanded or _CARRIED in source.data:
        return None
    if next(root.iter("{*}ros2_control"), None) is not None:
        return None
    elements = transmission_elements(root)
    if len(elements) < 2 or any(e.getparent() is not root for e in elements):
        return None
    keys: list[Hashable | None] = []
    uses: Counter[str] = Counter()
    known: dict[tuple, tuple | None] = {}
    names_of: list[set[str]] = []
    for element in elements:
        renaming = renaming_of(element)
        names = _names(element) if renaming is None else set(renaming.names)
        if renaming is not None and any(isinstance(n, bytes) for n in renaming.key[1]):
            renaming = None  # a literal name (actuator1, *) is not told apart by its key
        uses.update(names)
        names_of.append(names)
        keys.append(None if renaming is None else
                    (renaming.key, _joints_alike(element, joints, known)))
    firsts: dict[Hashable, int] = {}
    first_of: dict[int, int] = {}
    for position, (key, names) in enumerate(zip(keys, names_of, strict=True)):
        if key is None or any(uses[n] > 1 for n in names):
            continue
        first = firsts.setdefault(key, position)
        if first != position:
            first_of[position] = first
    return Plan(elements, first_of) if first_of else None


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
    """``source`` without the followers of ``plan`` and the root's URDF links and joints."""
    root = source.root
    followers = {id(plan.elements[f]) for f in plan.first_of}
    shell = etree.Element(root.tag, dict(root.attrib), nsmap=root.nsmap)
    shell.text = root.text
    for child in root:
        if id(child) in followers or child.tag in _URDF_PARTS:
            continue
        shell.append(copy.copy(child))
    data = etree.tostring(shell, encoding="utf-8", xml_declaration=True)
    return Source(source.path, data, parse_bytes(data, source.path, limit=None))
