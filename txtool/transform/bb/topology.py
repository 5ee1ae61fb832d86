"""A whole BB ``topology do ... end`` for a URDF: its links and joints, with the actuators.

Each joint is written as BB's URDF importer writes it (beam-bots/bb ``lib/bb/urdf/importer.ex``
@64ab268, ``render_joint/3`` :351-364): ``type``, then ``origin`` (nonzero parts; metres and
radians, :444-462), ``axis`` (cardinal axes as fixed angles, others as roll and pitch in degrees,
:385-404, :464-478), ``limit`` (units by joint type; a continuous joint has no position limits,
:406-430), then the child link. The actuators go before the child link. Visuals, collisions,
inertia, dynamics and mimic sensors are left to ``mix bb.from_urdf``.
"""

from __future__ import annotations

import math
import re
from collections.abc import Sequence

from lxml import etree

from txtool.io.xmlio import Source
from txtool.transform.bb.actuators import Attachment, Direction, actuator_lines, decimal_text
from txtool.transform.bb.names import RobotNames, UrdfJoint, elixir_atom

# importer.ex @cardinal_axes (:25-32): unit axes as fixed rotations of +Z, in degrees
CARDINAL_AXES: dict[tuple[float, float, float], tuple[tuple[str, float], ...]] = {
    (1.0, 0.0, 0.0): (("pitch", 90.0),),
    (-1.0, 0.0, 0.0): (("pitch", -90.0),),
    (0.0, 1.0, 0.0): (("roll", -90.0),),
    (0.0, -1.0, 0.0): (("roll", 90.0),),
    (0.0, 0.0, 1.0): (),
    (0.0, 0.0, -1.0): (("pitch", 180.0),),
}
_NUMBER = re.compile(r"\s*[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?")
INDENT = "  "


def render_topology(
    source: Source,
    names: RobotNames,
    attachments: Sequence[Attachment],
    direction: Direction,
    losses: list[str],
) -> str:
    if not names.links:
        losses.append(f"{source.path}: no <robot> with <link> elements, so no topology; "
                      "give the robot's URDF")
        return ""
    children_of: dict[str, list[UrdfJoint]] = {}
    for joint in names.urdf_joints:
        children_of.setdefault(joint.parent or "", []).append(joint)
    child_links = {j.child for j in names.urdf_joints}
    roots = [link for link in names.links if link not in child_links]
    if len(roots) != 1:
        losses.append(f"{source.path}: BB's topology has one root link, this robot has "
                      f"{len(roots)} ({', '.join(roots) or 'a cycle'})")
        if not roots:
            return ""
    by_joint: dict[str, list[Attachment]] = {}
    for a in attachments:
        by_joint.setdefault(a.joint, []).append(a)
    writer = _Writer(names, children_of, by_joint, direction)
    lines = ["topology do", *writer.link(roots[0], 1), "end"]
    header = ("# BB topology: links, joints and actuators (visuals, collisions, inertia, "
              "dynamics and mimic sensors: mix bb.from_urdf)\n")
    return header + "\n".join(lines) + "\n"


class _Writer:
    def __init__(self, names: RobotNames, children_of: dict[str, list[UrdfJoint]],
                 by_joint: dict[str, list[Attachment]], direction: Direction):
        self.names = names
        self.children_of = children_of
        self.by_joint = by_joint
        self.direction = direction
        self.visited: set[str] = set()

    def link(self, name: str, depth: int) -> list[str]:
        pad = INDENT * depth
        head = f"{pad}link {elixir_atom(self.names.links[name])}"
        if name in self.visited:  # a cycle: BB's importer refuses it; write the link alone
            return [head]
        self.visited.add(name)
        body = [line for j in self.children_of.get(name, []) for line in self.joint(j, depth + 1)]
        return [head + " do", *body, pad + "end"] if body else [head]

    def joint(self, joint: UrdfJoint, depth: int) -> list[str]:
        pad = INDENT * depth
        inner = INDENT * (depth + 1)
        body = [f"{inner}type :{joint.type}"]
        body += _block("origin", _origin(joint.element), inner)
        body += _axis(joint, inner)
        body += _block("limit", _limit(joint), inner)
        for a in self.by_joint.get(joint.name, []):
            body += [inner + line for line in actuator_lines(a, self.direction)]
        if joint.child in self.names.links:
            body += self.link(joint.child, depth + 1)
        return [f"{pad}joint {elixir_atom(joint.bb_name)} do", *body, pad + "end"]


def _block(name: str, entries: list[str], pad: str) -> list[str]:
    if not entries:
        return []
    return [f"{pad}{name} do", *(pad + INDENT + e for e in entries), pad + "end"]


def _number(text: str | None, default: float) -> float:
    """As BB's parser reads a number: ``Float.parse`` of a prefix, 0.0 where there is none."""
    if text is None:
        return default
    match = _NUMBER.match(text)
    return float(match.group(0)) if match else 0.0


def _triple(text: str | None, default: str) -> tuple[float, float, float]:
    parts = (text if text is not None else default).split()
    values = [_number(p, 0.0) for p in parts[:3]] + [0.0] * (3 - len(parts[:3]))
    return values[0], values[1], values[2]


def _unit(value: float, unit: str) -> str:
    return f"~u({decimal_text(value)} {unit})"


def _origin(element: etree._Element) -> list[str]:
    origin = next(element.iterchildren("{*}origin"), None)
    if origin is None:
        return []
    xyz = _triple(origin.get("xyz"), "0 0 0")
    rpy = _triple(origin.get("rpy"), "0 0 0")
    fields = [("x", xyz[0], "meter"), ("y", xyz[1], "meter"), ("z", xyz[2], "meter"),
              ("roll", rpy[0], "radian"), ("pitch", rpy[1], "radian"), ("yaw", rpy[2], "radian")]
    return [f"{key} {_unit(value, unit)}" for key, value, unit in fields if value != 0.0]


def _axis(joint: UrdfJoint, pad: str) -> list[str]:
    axis = next(joint.element.iterchildren("{*}axis"), None)
    if joint.type == "fixed" or axis is None:
        return []
    x, y, z = _triple(axis.get("xyz"), "1 0 0")
    angles = CARDINAL_AXES.get((_round_axis(x), _round_axis(y), _round_axis(z)))
    if angles is None:
        pitch = math.degrees(math.atan2(x, z))
        roll = math.degrees(math.atan2(-y, math.sqrt(x * x + z * z)))
        angles = (("roll", roll), ("pitch", pitch))
    entries = [f"{key} {_unit(value, 'degree')}" for key, value in angles]
    return _block("axis", entries, pad) or [f"{pad}axis do", f"{pad}end"]


def _round_axis(v: float) -> float:
    for target in (1.0, -1.0, 0.0):
        if abs(v - target) < 0.001:
            return target
    return v


def _limit(joint: UrdfJoint) -> list[str]:
    limit = next(joint.element.iterchildren("{*}limit"), None)
    if joint.type == "fixed" or limit is None:
        return []
    if joint.type == "prismatic":
        units = {"lower": "meter", "upper": "meter", "effort": "newton",
                 "velocity": "meter_per_second"}
    else:
        units = {"lower": "radian", "upper": "radian", "effort": "newton_meter",
                 "velocity": "radian_per_second"}
    if joint.type == "continuous":
        units = {k: v for k, v in units.items() if k in ("effort", "velocity")}
    return [f"{key} {_unit(_number(limit.get(key), 0.0), unit)}"
            for key, unit in units.items() if limit.get(key) is not None]
