"""Prove that conversions keep reduction, offset, direction, roles and interfaces.

For every transmission and every cycle that starts from its dialect (``ros1 -> ros2-p2 ->
ros1``, ``ros1 -> ros2-p1 -> ros2-p2 -> ros1``, ...), the whole document is converted through
the cycle, read back, and compared field by field with the original (floats bit for bit), on
what the original defines (:func:`txtool.transform.convert.judge`).
Each first leg is also checked numerically: the converted config must drive the actuators
exactly like the original (:mod:`txtool.mechanics.equivalence`).
"""

from __future__ import annotations

import hashlib
import itertools
from collections import Counter
from collections.abc import Hashable, Mapping
from dataclasses import dataclass, field

from lxml import etree

from txtool.dialects.read import read_source
from txtool.io.xmlio import Source, parse_bytes
from txtool.model.core import DIALECTS, Dialect, Transmission, builder
from txtool.model.robot import JointInfo, JointsOnDemand, joint_elements
from txtool.model.semantics import listed_against_roles
from txtool.transform.convert import convert_source, judge
from txtool.transform.repeated.nameless_shapes import ordered_shape, shape
from txtool.transform.repeats import Plan, cycled_document, plan_repeats
from txtool.views.tables import FIELDS


@dataclass(frozen=True, slots=True)
class CycleRow:
    transmission: str
    cycle: tuple[Dialect, ...]
    fields: dict[str, bool]
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

    @property
    def ok(self) -> bool:
        # The rows of repeated transmissions share their fields (see .repeats): each fields
        # and verdict they share is looked at once.
        shared = {(id(row.fields), row.equivalent): row for row in self.rows}
        return all(row.ok for row in shared.values())

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


def _reconvert(source: Source, target: Dialect, *, consume: bool) -> bytes:
    """``source`` converted to ``target``. The conversion's own read-back check is left out:
    the cycle's result is judged here, against the original."""
    return convert_source(source, target, consume=consume, check=False).data


def roundtrip(source: Source, *, consume: bool = False) -> RoundTripReport:
    """The rows of every cycle of every transmission of ``source``. With ``consume`` the
    caller gives up ``source.tree``: the last conversion of it converts it in place."""
    joints = JointsOnDemand(joint_elements(source.root))
    plan = plan_repeats(source, joints)
    while plan is not None:
        # A transmission that repeats another is cycled once, with it (see .repeats).
        report, originals = _report(cycled_document(source, plan), joints, consume=True)
        spoken = spoken_firsts(report, originals, plan)
        if not spoken:
            report.rows = with_followers(report, originals, plan)
            return report
        plan = plan.without(spoken)
        if not plan.first_of:
            plan = None
    return _report(source, joints, consume=consume)[0]


def _report(source: Source, joints: Mapping[str, JointInfo], *, consume: bool
            ) -> tuple[RoundTripReport, list[Transmission]]:
    """:func:`roundtrip`'s report on ``source`` cycled in full, and its transmissions."""
    report = RoundTripReport(source.path)
    originals = [f.transmission for f in read_source(source, locate=False)]
    groups = _groups(originals)
    starts = [start for start in DIALECTS if groups[start]]
    firsts = list(dict.fromkeys(cycle[1] for start in starts for cycle in cycles_from(start)))
    # Each first leg converts the document as read, once for every group that starts with it.
    legs = {first: _reconvert(source, first, consume=consume and first == firsts[-1])
            for first in firsts}
    for start in starts:
        report.rows.extend(_cycles(source.path, start, groups[start], joints, legs))
    report.skipped = [f"{t.name}: custom type '{t.type}'" for t in originals if t.kind == "other"]
    return report, originals


def _groups(originals: list[Transmission]) -> dict[Dialect, list[Transmission]]:
    """The transmissions cycled from each dialect (custom types are passed through)."""
    return {start: [t for t in originals if t.dialect == start and t.kind != "other"]
            for start in DIALECTS}


_new_row = builder(CycleRow)
_ByPosition = dict[int, CycleRow]  # a cycle's rows by their transmission's position


def _by_cycle(report: RoundTripReport, originals: list[Transmission]
              ) -> list[tuple[tuple[Dialect, ...], _ByPosition]]:
    """The rows of ``report`` cycle by cycle, by the position of each one's transmission
    among ``originals`` (the report's rows, in :func:`_report`'s order)."""
    rows = iter(report.rows)
    found = []
    for start in DIALECTS:
        members = [j for j, t in enumerate(originals) if t.dialect == start and t.kind != "other"]
        found.extend((cycle, {j: next(rows) for j in members}) for cycle in cycles_from(start)
                     if members)
    return found


def _silent(row: CycleRow) -> bool:
    return row.equivalent == "yes" and not row.details and all(row.fields.values())


def _kept(plan: Plan) -> dict[int, int]:
    """Each transmission cycled: its position in the document -> in the document cycled."""
    kept = (p for p in range(len(plan.elements)) if p not in plan.first_of)
    return {p: j for j, p in enumerate(kept)}


def spoken_firsts(report: RoundTripReport, originals: list[Transmission], plan: Plan
                  ) -> set[int]:
    """The firsts of ``plan`` whose rows in ``report`` (of the document cycled) say something
    or are missing: their followers are cycled in full."""
    firsts = set(plan.first_of.values())
    at = _kept(plan)
    if len(at) != len(originals):
        return firsts  # not the transmissions planned: cycle everything
    covered: Counter[int] = Counter()
    spoken = set()
    by_cycle = _by_cycle(report, originals)
    for first in firsts:
        for _, rows in by_cycle:
            row = rows.get(at[first])
            if row is not None:
                covered[first] += 1
                if not _silent(row):
                    spoken.add(first)
    return spoken | {f for f in firsts if not covered[f]}


def with_followers(report: RoundTripReport, originals: list[Transmission], plan: Plan
                   ) -> list[CycleRow]:
    """The rows of the whole document: ``report``'s, and each follower's after its first's
    (the same, with its name), in document order."""
    at = _kept(plan)
    rows = []
    for cycle, by_position in _by_cycle(report, originals):
        for position, element in enumerate(plan.elements):
            first = plan.first_of.get(position)
            row = by_position.get(at[position if first is None else first])
            if row is None:
                continue
            rows.append(row if first is None else _new_row(
                transmission=element.get("name", ""), cycle=cycle, fields=row.fields,
                equivalent=row.equivalent))
    return rows


_Key = tuple[str, bool]


def _by_name(source: Source) -> dict[_Key, list[Transmission]]:
    """Standard and custom transmissions by name; same-named ones in document order (the
    order conversions keep among them)."""
    found: dict[_Key, list[Transmission]] = {}
    for f in read_source(source, locate=False):
        found.setdefault((f.transmission.name, f.transmission.kind == "other"), []).append(
            f.transmission)
    return found


def _take(found: dict[_Key, list[Transmission]], name: str) -> Transmission | None:
    same = found.get((name, False))
    return same.pop(0) if same else None


def _cycles(path: str, start: Dialect, group: list[Transmission], joints,
            legs: dict[Dialect, bytes]) -> list[CycleRow]:
    """The rows of every cycle from ``start``. Cycles that begin with the same conversion
    share it (and its equivalence check); each later leg converts a fresh parse (the first
    cycle takes the parse the shared leg was read from): one tree of each leg alive at once."""
    rows: dict[tuple[Dialect, ...], list[CycleRow]] = {}
    cycles = cycles_from(start)
    ends = _Ends(path, group)
    for first in dict.fromkeys(cycle[1] for cycle in cycles):
        data = legs[first]
        tree = parse_bytes(data, path, limit=None)
        verdicts = _Verdicts(group, _by_name(Source(path, data, tree)), joints)
        parsed = [tree]
        del tree
        for cycle in (c for c in cycles if c[1] == first):
            rows[cycle] = _rows(cycle, group, ends.judged(data, cycle[2:], parsed), verdicts)
        parsed.clear()
    return [row for cycle in cycles for row in rows[cycle]]


_Judged = list[dict[str, str] | None]  # per transmission: what it lost, or None: missing


class _Ends:
    """What each cycle brings back, judged against the original. A cycle's last leg that
    converts a text already converted to the same dialect (converting ``ros1 -> ros2-p1 ->
    ros2-p2`` often writes what ``ros1 -> ros2-p2`` wrote) brings back what it brought back
    then: a conversion depends on nothing but the text and the dialect."""

    def __init__(self, path: str, group: list[Transmission]) -> None:
        self.path = path
        self.group = group
        self.known: dict[tuple[bytes, Dialect], _Judged] = {}

    def judged(self, data: bytes, steps: tuple[Dialect, ...],
               parsed: list[etree._ElementTree]) -> _Judged:
        """The judgement of the group after converting ``data`` through ``steps``;
        ``parsed`` holds a parse of ``data`` or nothing; the first conversion takes it."""
        *between, last = steps
        for step in between:
            data = self._convert(data, step, parsed)
        key = (_digest(data), last)
        if key not in self.known:
            final = self._convert(data, last, parsed)
            self.known[key] = _judge(self.group, _by_name(self._parse(final)))
        return self.known[key]

    def _convert(self, data: bytes, target: Dialect, parsed: list[etree._ElementTree]) -> bytes:
        tree = parsed.pop() if parsed else parse_bytes(data, self.path, limit=None)
        return _reconvert(Source(self.path, data, tree), target, consume=True)

    def _parse(self, data: bytes) -> Source:
        return Source(self.path, data, parse_bytes(data, self.path, limit=None))


def _digest(data: bytes) -> bytes:
    """What texts are told apart by (holding 32 bytes, not the text)."""
    return hashlib.sha256(data).digest()


class _Verdicts:
    """Whether each transmission's first conversion drives the actuators like the original,
    computed when a cycle first asks (once per first leg). A pair whose ordered shape
    (:func:`.repeated.nameless_shapes.ordered_shape`: the same up to names that compare alike) and
    joint limits were already found equivalent is equivalent: the comparison reads names only
    to order and match them."""

    def __init__(self, group: list[Transmission], first_leg: dict[_Key, list[Transmission]],
                 joints) -> None:
        self.converted = [_take(first_leg, t.name) for t in group]
        self.group = group
        self.joints = joints
        self.known: dict[int, str] = {}
        self.equivalent: set[Hashable] = set()

    def __getitem__(self, index: int) -> str:
        from txtool.mechanics.equivalence import compare_pair

        if index not in self.known:
            t, converted = self.group[index], self.converted[index]
            if converted is None:
                self.known[index] = _verdict(None)
                return self.known[index]
            key = (ordered_shape(t, converted),
                   tuple(_limits(self.joints.get(j.name)) for j in t.joints))
            if key in self.equivalent:
                self.known[index] = "yes"
                return "yes"
            self.known[index] = _verdict(compare_pair(t, converted, self.joints))
            if self.known[index] == "yes":
                self.equivalent.add(key)
        return self.known[index]


def _limits(info: JointInfo | None) -> tuple[str, ...] | None:
    """What the equivalence samples of a joint (its floats as text: -0.0 is not 0.0)."""
    if info is None:
        return None
    return (repr(info.position_range()), repr(info.velocity), repr(info.effort))


def _judge(group: list[Transmission], final: dict[_Key, list[Transmission]]) -> _Judged:
    """What each transmission of ``group`` lost in ``final`` (None: it is missing there)."""
    judged: _Judged = []
    # shapes (:func:`.repeated.nameless_shapes.shape`) that came back whole
    kept: set[Hashable] = set()
    for t in group:
        back = _take(final, t.name)
        if back is None:
            judged.append(None)
            continue
        key = shape(t, back)
        lost = {} if key in kept else judge(t, back)
        if not lost:
            kept.add(key)
        judged.append(lost)
    return judged


def _rows(cycle: tuple[Dialect, ...], group: list[Transmission], judged: _Judged,
          verdicts: _Verdicts) -> list[CycleRow]:
    rows = []
    for index, (t, lost) in enumerate(zip(group, judged, strict=True)):
        if lost is None:
            rows.append(CycleRow(t.name, cycle, dict.fromkeys(FIELDS, False), "n/a: lost",
                                 ("the transmission is missing after the cycle",)))
            continue
        details = [f"{key}: {change}" for key, change in lost.items()]
        if verdicts[index].startswith("no") and t.dialect == "ros1" and listed_against_roles(t):
            details.append("the original lists its members against their roles (TX404): "
                           "ros_control binds their data in XML order, ros2_control by name")
        rows.append(CycleRow(t.name, cycle, {key: key not in lost for key in FIELDS},
                             verdicts[index], tuple(details)))
    return rows


def _verdict(row) -> str:
    if row is None:
        return "n/a: not converted"
    if row.status == "equivalent":
        return "yes"
    if row.status == "not loadable":
        return f"n/a: {row.reason}"
    return f"no: {row.reason}"
