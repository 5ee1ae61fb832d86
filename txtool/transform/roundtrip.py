"""Prove that conversions keep reduction, offset, direction, roles and interfaces.

For every transmission and every cycle that starts from its dialect (``ros1 -> ros2-p2 ->
ros1``, ``ros1 -> ros2-p1 -> ros2-p2 -> ros1``, ...), the whole document is converted through
the cycle, read back, and compared field by field with the original (floats bit for bit), on
what the original defines (:func:`txtool.transform.convert.judge`).
Each first leg is also checked numerically: the converted config must drive the actuators
exactly like the original (:mod:`txtool.mechanics.equivalence`).
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass, field

from txtool.dialects.read import read_source
from txtool.io.xmlio import Source, parse_bytes
from txtool.model.core import DIALECTS, Dialect, Transmission
from txtool.model.robot import robot_joints
from txtool.transform.convert import convert_source, judge, listed_against_roles
from txtool.views.tables import FIELDS


@dataclass(frozen=True)
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
        return all(row.ok for row in self.rows)

    def to_json(self) -> dict:
        return {
            "path": self.path,
            "ok": self.ok,
            "cycles": [
                {"transmission": r.transmission, "cycle": list(r.cycle), **r.fields,
                 "equivalent": r.equivalent, "details": list(r.details)}
                for r in self.rows
            ],
            "skipped": self.skipped,
        }


def cycles_from(start: Dialect) -> list[tuple[Dialect, ...]]:
    others = [d for d in DIALECTS if d != start]
    two = [(start, x, start) for x in others]
    three = [(start, *pair, start) for pair in itertools.permutations(others)]
    return two + three


def _reconvert(source: Source, target: Dialect) -> Source:
    data = convert_source(source, target).data
    return Source(source.path, data, parse_bytes(data, source.path))


def roundtrip(source: Source) -> RoundTripReport:
    report = RoundTripReport(source.path)
    originals = [f.transmission for f in read_source(source, locate=False)]
    joints = robot_joints(source.root)
    for start in DIALECTS:
        group = [t for t in originals if t.dialect == start and t.kind != "other"]
        if group:
            report.rows.extend(_cycles(source, start, group, joints))
    report.skipped = [f"{t.name}: custom type '{t.type}'" for t in originals if t.kind == "other"]
    return report


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


def _cycles(source: Source, start: Dialect, group: list[Transmission], joints) -> list[CycleRow]:
    from txtool.mechanics.equivalence import compare_pair

    rows = []
    legs = _Legs(source)
    for cycle in cycles_from(start):
        first_leg = legs.read(cycle[:2])
        final = legs.read(cycle)
        for t in group:
            back = _take(final, t.name)
            converted = _take(first_leg, t.name)
            if back is None:
                rows.append(CycleRow(t.name, cycle, dict.fromkeys(FIELDS, False), "n/a: lost",
                                     ("the transmission is missing after the cycle",)))
                continue
            equivalence = compare_pair(t, converted, joints) if converted else None
            lost = judge(t, back)
            details = [f"{key}: {change}" for key, change in lost.items()]
            if equivalence is not None and equivalence.status == "differs" \
                    and t.dialect == "ros1" and listed_against_roles(t):
                details.append("the original lists its members against their roles (TX404): "
                               "ros_control binds their data in XML order, ros2_control by name")
            rows.append(CycleRow(t.name, cycle, {key: key not in lost for key in FIELDS},
                                 _verdict(equivalence), tuple(details)))
    return rows


class _Legs:
    """The document converted along each path of dialects, each conversion done once: the
    cycles from one dialect share their first legs (``ros1 -> ros2-p1`` starts two)."""

    def __init__(self, source: Source) -> None:
        self._documents: dict[tuple[Dialect, ...], Source] = {}
        self._read: dict[tuple[Dialect, ...], dict[_Key, list[Transmission]]] = {}
        self._source = source

    def document(self, path: tuple[Dialect, ...]) -> Source:
        if len(path) == 1:
            return self._source
        if path not in self._documents:
            self._documents[path] = _reconvert(self.document(path[:-1]), path[-1])
        return self._documents[path]

    def read(self, path: tuple[Dialect, ...]) -> dict[_Key, list[Transmission]]:
        """The transmissions at the end of ``path`` by name, a fresh dict to take from."""
        if path not in self._read:
            self._read[path] = _by_name(self.document(path))
        return {key: list(same) for key, same in self._read[path].items()}


def _verdict(row) -> str:
    if row is None:
        return "n/a: not converted"
    if row.status == "equivalent":
        return "yes"
    if row.status == "not loadable":
        return f"n/a: {row.reason}"
    return f"no: {row.reason}"
