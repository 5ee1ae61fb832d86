"""Prove that conversions keep reduction, offset, direction, roles and interfaces.

For every transmission and every cycle that starts from its dialect (``ros1 -> ros2-p2 ->
ros1``, ``ros1 -> ros2-p1 -> ros2-p2 -> ros1``, ...), the whole document is converted through
the cycle, each leg converting the tree the one before converted, and the transmissions it
ends with are compared field by field with the original (floats bit for bit), on what the
original defines (:func:`txtool.transform.check.judge`).
Each first leg is also checked numerically: the converted config must drive the actuators
exactly like the original (:mod:`txtool.mechanics.equivalence`).
"""

from __future__ import annotations

import hashlib
import itertools
from collections.abc import Mapping
from dataclasses import dataclass, field
from functools import cache
from types import MappingProxyType

from lxml import etree

from txtool.dialects.read import Found, read_each, read_source
from txtool.io.xmlio import Source, parse_bytes, serialize
from txtool.model.core import DIALECTS, Dialect, Transmission
from txtool.model.robot import JointInfo, joint_elements, joint_info
from txtool.model.semantics import listed_against_roles
from txtool.transform.check import judge, paired
from txtool.transform.convert import convert_source
from txtool.transform.reversible import carries_originals
from txtool.views.tables import FIELDS


@dataclass(frozen=True, slots=True)
class CycleRow:
    transmission: str
    cycle: tuple[Dialect, ...]
    fields: Mapping[str, bool]  # shared by the rows that keep the same fields
    equivalent: str  # "yes", "no: reason", or "n/a: reason"
    details: tuple[str, ...] = ()

    @property
    def ok(self) -> bool:
        return all(self.fields.values()) and not self.equivalent.startswith("no")


@dataclass
class RoundTripReport:
    path: str
    rows: list[CycleRow] = field(default_factory=list)
    skipped: list[str] = field(default_factory=list)  # custom types, passed through untouched
    expanded: bool = False  # read from a xacro expansion

    @property
    def ok(self) -> bool:
        return all(row.ok for row in self.rows)

    @property
    def summary(self) -> str:
        """The report's last line: what the cycles kept, or that there was nothing to cycle
        (a file of xacro macros expands to no transmission; a custom type is passed
        through), which is no proof that anything survives."""
        if not self.rows:
            where = (" as xacro expands it (transmissions inside macros are cycled as written "
                     "with --no-xacro)" if self.expanded else "")
            return f"nothing cycled: no transmission of a standard type in the document{where}"
        return ("all cycles keep every field" if self.ok
                else "some cycles lose data or change behaviour")

    def to_json(self) -> dict:
        """The JSON document (schemas/roundtrip.schema.json; its --against keys empty)."""
        return {
            "path": self.path,
            "against": None,
            "ok": self.ok,
            "cycles": [
                {"transmission": r.transmission, "cycle": list(r.cycle), **r.fields,
                 "equivalent": r.equivalent, "details": list(r.details)}
                for r in self.rows
            ],
            "skipped": self.skipped,
            "transmissions": [],
            "bb_exporter_dropped": [],
        }


def cycles_from(start: Dialect) -> list[tuple[Dialect, ...]]:
    others = [d for d in DIALECTS if d != start]
    two = [(start, x, start) for x in others]
    three = [(start, *pair, start) for pair in itertools.permutations(others)]
    return two + three


@dataclass(slots=True)
class _Leg:
    """A conversion's text; its tree, when kept to be converted next (in place), and the
    transmissions read from that tree, once read."""

    data: bytes
    tree: etree._ElementTree | None = None
    found: list[Found] | None = None

    def taken(self) -> _Leg:
        """This leg, its tree given up to the one returned (converted in place there)."""
        leg = _Leg(self.data, self.tree, self.found)
        self.tree = self.found = None
        return leg

    def parsed(self, path: str) -> etree._ElementTree:
        """Its tree: the one kept, or a parse of its text (kept from then on)."""
        if self.tree is None:
            self.tree = parse_bytes(self.data, path, limit=None)
        return self.tree


def _reconvert(source: Source, target: Dialect, *, whole: bool,
               found: list[Found] | None = None) -> _Leg:
    """``source`` converted to ``target``, its tree converted in place (an empty document is
    left in its place; ``found``: its transmissions, when read): the text and, ``whole``,
    the tree converted. The conversion's own read-back check is left out: the cycle's
    result is judged here, against the original.

    ``whole``: the converted tree is written whole rather than said as edits of
    ``source.data``. Only its transmissions are read (from the tree itself), and the edits
    write that same tree (``convert`` checks it), but for originals a document carries
    (:func:`.reversible.carries_originals`): going back to ROS 1 writes them as their bytes,
    which only a parse of the edited text reads."""
    tree = source.tree
    converting = Source(source.path, source.data, tree, expanded=source.expanded or whole)
    data = convert_source(converting, target, consume=True, check=False, found=found).data
    source.tree = converting.tree
    return _Leg(data, tree if whole else None)


def roundtrip(source: Source, *, consume: bool = False) -> RoundTripReport:
    """The rows of every cycle of every transmission of ``source``. With ``consume`` the
    caller gives up ``source.tree``: the first conversion of it converts it in place."""
    report = RoundTripReport(source.path, expanded=source.expanded)
    found: list[Found] | None = read_source(source, locate=False)
    originals = [f.transmission for f in found]
    groups = _groups(originals)
    joints = _joints(source.root, originals)
    starts = [start for start in DIALECTS if groups[start]]
    firsts = list(dict.fromkeys(cycle[1] for start in starts for cycle in cycles_from(start)))
    whole = not carries_originals(source.root)
    ends = {start: _Ends(source.path, groups[start], whole) for start in starts}
    # Each first leg converts the document as read, once for every group that starts with
    # it: the first leg its tree (given up with ``consume``), the others a parse of its text;
    # the last leg's tree is where its cycles, run first, go on converting (the others parse
    # the text the leg wrote): one tree alive at a time.
    text = serialize(source.tree) if source.expanded else source.data
    legs = {}
    for first in firsts:
        document, read = (source, found) if consume and first == firsts[0] else (Source(
            source.path, source.data, parse_bytes(text, source.path, limit=None),
            expanded=source.expanded), None)
        found = None  # (what was read of the tree its conversion converts)
        leg = _reconvert(document, first, whole=whole, found=read)
        if first != firsts[-1]:
            leg.tree = None  # parsed again when its cycles come
        legs[first] = leg
        del document, read
    del text
    rows: dict[tuple[Dialect, ...], list[CycleRow]] = {}
    for first in reversed(firsts):
        leg = legs.pop(first)
        for start in starts:
            rows.update(_cycles(start, first, leg, ends[start], joints))
    report.rows = [row for start in starts for cycle in cycles_from(start)
                   for row in rows[cycle]]
    report.skipped = [f"{t.name}: custom type '{t.type}'" for t in originals if t.kind == "other"]
    return report


def _joints(root: etree._Element, originals: list[Transmission]) -> dict[str, JointInfo]:
    """The joints the transmissions name, read before the document is converted: the
    equivalence checks sample them, and holding their elements would hold the whole tree."""
    elements = joint_elements(root)
    named = dict.fromkeys(j.name for t in originals for j in t.joints)
    return {name: joint_info(elements[name]) for name in named if name in elements}


def _groups(originals: list[Transmission]) -> dict[Dialect, list[Transmission]]:
    """The transmissions cycled from each dialect (custom types are passed through)."""
    return {start: [t for t in originals if t.dialect == start and t.kind != "other"]
            for start in DIALECTS}


def _cycles(start: Dialect, first: Dialect, leg: _Leg, ends: _Ends,
            joints: Mapping[str, JointInfo]) -> dict[tuple[Dialect, ...], list[CycleRow]]:
    """The rows of the cycles from ``start`` that begin with the leg to ``first``. The
    first conversion of the leg takes its tree, each later one a fresh parse; the
    transmissions read from it for the verdicts are the ones that conversion converts."""
    cycles = [c for c in cycles_from(start) if c[1] == first]
    if not cycles:
        return {}
    if leg.found is None:
        leg.found = read_source(Source(ends.path, leg.data, leg.parsed(ends.path)),
                                locate=False)
    verdicts = _verdicts(ends.group, [f.transmission for f in leg.found], joints)
    return {cycle: _rows(cycle, ends.group, ends.judged(leg, cycle[2:]), verdicts)
            for cycle in cycles}


_Judged = list[dict[str, str] | None]  # per transmission: what it lost, or None: missing


class _Ends:
    """What each cycle brings back, judged against the original. A cycle's last leg that
    converts a text already converted to the same dialect (converting ``ros1 -> ros2-p1 ->
    ros2-p2`` often writes what ``ros1 -> ros2-p2`` wrote) brings back what it brought back
    then: a conversion depends on nothing but the text and the dialect."""

    def __init__(self, path: str, group: list[Transmission], whole: bool) -> None:
        self.path = path
        self.group = group
        self.whole = whole  # (see _reconvert)
        self.known: dict[tuple[bytes, Dialect], _Judged] = {}

    def judged(self, leg: _Leg, steps: tuple[Dialect, ...]) -> _Judged:
        """The judgement of the group after converting ``leg`` through ``steps`` (a cycle
        whose end is known converts nothing: ``leg`` keeps its tree for the next)."""
        *between, last = steps
        current = leg
        for step in between:
            current = self._convert(current, step)
        key = (_digest(current.data), last)
        if key not in self.known:
            final = self._convert(current, last)
            self.known[key] = _judge(self.group, final.parsed(self.path).getroot())
        return self.known[key]

    def _convert(self, leg: _Leg, target: Dialect) -> _Leg:
        """``leg`` converted to ``target``: its tree, which the conversion takes, or a parse
        of its text."""
        taken = leg.taken()
        return _reconvert(Source(self.path, taken.data, taken.parsed(self.path)), target,
                          whole=self.whole, found=taken.found)


def _digest(data: bytes) -> bytes:
    """What texts are told apart by (holding 32 bytes, not the text)."""
    return hashlib.sha256(data).digest()


def _verdicts(group: list[Transmission], first_leg: list[Transmission],
              joints: Mapping[str, JointInfo]) -> list[str]:
    """Whether each transmission's first conversion (``first_leg``: the transmissions of the
    document it wrote) drives the actuators like the original."""
    from txtool.mechanics.equivalence import compare_pair

    verdicts = ["n/a: not converted"] * len(group)
    for i, converted in paired(group, first_leg):
        verdicts[i] = _verdict(compare_pair(group[i], converted, joints))
    return verdicts


def _judge(group: list[Transmission], final: etree._Element) -> _Judged:
    """What each transmission of ``group`` lost in the document of root ``final`` (None: it
    is missing there)."""
    judged: _Judged = [None] * len(group)
    for i, back in paired(group, read_each(final)):
        judged[i] = judge(group[i], back)
    return judged


def _rows(cycle: tuple[Dialect, ...], group: list[Transmission], judged: _Judged,
          verdicts: list[str]) -> list[CycleRow]:
    rows = []
    for index, (t, lost) in enumerate(zip(group, judged, strict=True)):
        if lost is None:
            rows.append(CycleRow(t.name, cycle, _fields(frozenset(FIELDS)), "n/a: lost",
                                 ("the transmission is missing after the cycle",)))
            continue
        details = [f"{key}: {change}" for key, change in lost.items()]
        if verdicts[index].startswith("no") and t.dialect == "ros1" and listed_against_roles(t):
            details.append("the original lists its members against their roles (TX404): "
                           "ros_control binds their data in XML order, ros2_control by name")
        rows.append(CycleRow(t.name, cycle, _fields(frozenset(lost)), verdicts[index],
                             tuple(details)))
    return rows


@cache
def _fields(lost: frozenset[str]) -> Mapping[str, bool]:
    """Whether each field is kept, given those ``lost``: one read-only mapping for each
    combination, which the rows share (and the reports write once)."""
    return MappingProxyType({key: key not in lost for key in FIELDS})


def _verdict(row) -> str:
    if row.status == "equivalent":
        return "yes"
    if row.status == "not loadable":
        return f"n/a: {row.reason}"
    return f"no: {row.reason}"
