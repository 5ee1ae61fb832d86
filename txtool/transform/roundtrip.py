"""Prove that conversions keep reduction, offset, direction, roles and interfaces.

For every transmission and every cycle that starts from its dialect (``ros1 -> ros2-p2 ->
ros1``, ``ros1 -> ros2-p1 -> ros2-p2 -> ros1``, ...), the whole document is converted through
the cycle, read back, and compared field by field with the original (floats bit for bit).
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
from txtool.transform.convert import convert_source
from txtool.views.tables import FIELDS, differences, surviving


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
    originals = [f.transmission for f in read_source(source)]
    joints = robot_joints(source.root)
    for start in DIALECTS:
        group = [t for t in originals if t.dialect == start and t.kind != "other"]
        if group:
            report.rows.extend(_cycles(source, start, group, joints))
    report.skipped = [f"{t.name}: custom type '{t.type}'" for t in originals if t.kind == "other"]
    return report


def _by_name(source: Source) -> dict[str, Transmission]:
    return {f.transmission.name: f.transmission for f in read_source(source)}


def _cycles(source: Source, start: Dialect, group: list[Transmission], joints) -> list[CycleRow]:
    from txtool.mechanics.equivalence import compare_pair

    rows = []
    for cycle in cycles_from(start):
        current = source
        first_leg: dict[str, Transmission] = {}
        for step in cycle[1:]:
            current = _reconvert(current, step)
            if not first_leg:
                first_leg = _by_name(current)
        final = _by_name(current)
        for t in group:
            back = final.get(t.name)
            if back is None:
                rows.append(CycleRow(t.name, cycle, dict.fromkeys(FIELDS, False), "n/a: lost",
                                     ("the transmission is missing after the cycle",)))
                continue
            converted = first_leg.get(t.name)
            equivalence = compare_pair(t, converted, joints) if converted else None
            rows.append(CycleRow(
                t.name, cycle, surviving(t, back), _verdict(equivalence),
                tuple(differences(t, back)),
            ))
    return rows


def _verdict(row) -> str:
    if row is None:
        return "n/a: not converted"
    if row.status == "equivalent":
        return "yes"
    if row.status == "not loadable":
        return f"n/a: {row.reason}"
    return f"no: {row.reason}"
