"""Export simple transmissions as Beam Bots (BB) DSL: a ``transmission`` inside an ``actuator``
inside the ``joint``, as BB's main branch defines it.

Facts from beam-bots/bb (Apache-2.0), PR #110 squash-merged as 23b6bde:

* The ``transmission`` entity is an option of ``actuator`` and ``sensor``, not of ``joint``
  (``lib/bb/dsl.ex:209-247`` and ``:274-282``; ``documentation/dsls/DSL-BB.md:36-44``, "joint >
  actuator > transmission"). Fields: ``reduction`` (float, default 1.0), ``offset`` (angle or
  length), ``reversed?`` (default false) (``lib/bb/dsl/transmission.ex:13-17``).
* ``motor = sign * reduction * (joint - offset)``, velocity ``sign * reduction * joint``, effort
  ``sign * joint / reduction``, ``sign = -1`` when ``reversed?`` (``lib/bb/transmission.ex:29-34``,
  ``:46-47``, ``:84-85``): ros2_control's SimpleTransmission with reduction ``sign * reduction``,
  so ``reversed? true`` and a negative reduction are the same motion.
* The offset must be an angle on revolute and continuous joints and a length on prismatic ones;
  other joint types are not checked (``lib/bb/dsl/validate_limit_units_transformer.ex:20-21``,
  ``:92-106``).
* BB's URDF exporter writes a ``<transmission>`` only for a reduction other than 1.0, and only the
  reduction: ``reversed?`` and ``offset`` are lost, and no ``<hardwareInterface>`` is written
  (``lib/bb/urdf/exporter.ex:35`` and ``build_transmission_elements/2``, read at @330b7c6,
  before the transmission moved into the actuator).

Units are CLDR names as BB's ``~u`` sigil takes them (``radian``, ``meter``), written in plain
decimal form like BB's importer writes them.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

from txtool.dialects.read import Found, first_child_text, read_source
from txtool.io.xmlio import Source
from txtool.model.robot import JointInfo, children, robot_joints
from txtool.model.semantics import NotLoadable, effective
from txtool.transform.bb.actuators import DRIVER, Attachment, Direction, render_joints
from txtool.transform.bb.names import RobotNames, atom_name, elixir_atom, robot_names, unique_name
from txtool.transform.bb.topology import render_topology

MOVING = ("revolute", "continuous", "prismatic")


@dataclass
class BBExport:
    """The DSL text, what could not be carried faithfully (losses) and what to know (notes)."""

    text: str
    losses: list[str] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)

    @property
    def lossless(self) -> bool:
        return not self.losses


def export_bb(
    source: Source, *, direction: Direction = "reversed", topology: bool = False
) -> BBExport:
    """BB actuators for every simple transmission of ``source``; with ``topology`` a whole
    ``topology do ... end`` of the robot's links and joints holding them."""
    found = read_source(source, locate=False)
    if not found:
        return BBExport("# no transmission to export\n")
    names = robot_names(source.root)
    export = BBExport("")
    attachments = _Collector(robot_joints(source.root), names, export.losses).collect(found)
    export.notes.extend(_notes(attachments, direction))
    if topology:
        export.text = render_topology(source, names, attachments, direction, export.losses)
    else:
        export.text = render_joints(attachments, direction)
    return export


class _Collector:
    """Turns transmissions into attachments, reporting what BB cannot carry as losses."""

    def __init__(self, joints: dict[str, JointInfo], names: RobotNames, losses: list[str]):
        self.joints = joints
        self.names = names
        self.losses = losses
        self.taken = names.taken()
        self.actuators: dict[str, str] = {}  # BB actuator name -> its transmission

    def collect(self, found: Sequence[Found]) -> list[Attachment]:
        result = []
        for item in found:
            attachment = self._attachment(item)
            if attachment is not None:
                result.append(attachment)
        return result

    def _attachment(self, found: Found) -> Attachment | None:
        t = found.transmission
        if t.kind != "simple":
            what = "custom type" if t.kind == "other" else f"{t.kind.replace('_', '-')} type"
            self._lose(t.name, f"{what} '{t.type}' is not representable in BB (BB has simple "
                               "transmissions only)")
            return None
        if not self._members_fit(found):
            return None
        self.losses.extend(ignored_values(found))
        try:
            eff = effective(t)
        except NotLoadable as exc:
            self._lose(t.name, f"not loadable: {exc}")
            return None
        joint = eff.joints[0]
        info = self._joint(t.name, joint)
        actuator = t.actuators[0].name if t.actuators else None
        return Attachment(
            transmission=t.name,
            joint=joint,
            actuator=actuator or "",
            joint_atom=self.names.joints.get(joint, atom_name(joint)),
            actuator_atom=self._actuator_atom(t.name, joint, actuator),
            reduction=eff.actuator_reduction[0] * eff.joint_reduction[0],
            offset=eff.joint_offset[0],
            linear=info is not None and info.is_linear,
        )

    def _members_fit(self, found: Found) -> bool:
        """One joint and one actuator, as a simple transmission and a BB actuator need."""
        t = found.transmission
        if t.dialect == "ros1" and _legacy_type(found):
            self._lose(t.name, f"ros_control skips it: its type '{t.type}' is a type= attribute "
                               "and it has no <type> element (TX302 fixes that)")
        if not t.joints:
            self._lose(t.name, "a simple transmission without a joint has nothing to drive")
            return False
        if any(not m.name.strip() for m in (*t.joints, *t.actuators)):
            self._lose(t.name, "a joint or actuator without a name (ros_control's parser "
                               "refuses it)")
            return False
        if len(t.joints) > 1 or len(t.actuators) > 1:
            self._lose(t.name, f"a simple transmission joins one joint and one actuator, this "
                               f"has {len(t.joints)} and {len(t.actuators)}"
                               + (" (ros_control refuses it)" if t.dialect == "ros1" else
                                  "; its first joint and actuator are exported"))
            return t.dialect != "ros1"
        return True

    def _joint(self, transmission: str, joint: str) -> JointInfo | None:
        info = self.joints.get(joint)
        if info is None:
            self._lose(transmission, f"joint '{joint}' is not in this robot: its type, and so "
                                     "the offset's unit, is unknown (written as an angle)")
        elif joint in self.names.dropped:
            self._lose(transmission, f"joint '{joint}' is dropped by BB's URDF importer (its "
                                     f"parent link '{self.names.dropped[joint]}' is not "
                                     "defined)")
        elif info.type not in MOVING:
            self._lose(transmission, f"joint '{joint}' is {info.type or 'untyped'}: an actuator "
                                     "on it has nothing to move")
        return info

    def _actuator_atom(self, transmission: str, joint: str, actuator: str | None) -> str:
        if actuator is None:
            wanted = atom_name(joint) + "_motor"
            self._lose(transmission, f"no actuator: named it {elixir_atom(wanted)} (BB "
                                     "needs a name; "
                                     "ros2_control calls it 'actuator1')")
        else:
            wanted = atom_name(actuator)
        name = unique_name(wanted, self.taken)
        if name != wanted:
            owner = self.actuators.get(wanted)
            holder = (f"the actuator of transmission '{owner}'" if owner is not None
                      else "a link or joint")
            self._lose(transmission, f"actuator {elixir_atom(wanted)} is already the name of "
                                     f"{holder} (BB needs link, joint and actuator names "
                                     f"unique); named it {elixir_atom(name)}")
        self.taken.add(name)
        self.actuators[name] = transmission
        return name

    def _lose(self, transmission: str, reason: str) -> None:
        self.losses.append(f"transmission '{transmission}': {reason}")


def _legacy_type(found: Found) -> bool:
    """ros_control reads only a ``<type>`` element; a ``type=`` attribute alone is skipped."""
    text = first_child_text(found.element, "type")
    return not (text or "").strip() and bool(found.element.get("type"))


def ignored_values(found: Found) -> list[str]:
    """Values written in a simple transmission that its loader never reads (see TX400)."""
    t = found.transmission
    lost = []
    if t.dialect == "ros1":
        if children(found.element, "mechanicalReduction"):
            lost.append(f"transmission '{t.name}': ros_control never reads a "
                        "<mechanicalReduction> directly under <transmission>; exported as the "
                        "actuator's")
        for joint in t.joints:
            if joint.mechanical_reduction is not None:
                lost.append(f"joint '{joint.name}': <mechanicalReduction> "
                            f"{joint.mechanical_reduction.text} is ignored by ros_control for "
                            "simple transmissions (it reads the actuator's); not exported")
        for actuator in t.actuators:
            if actuator.offset is not None:
                lost.append(f"actuator '{actuator.name}': <offset> {actuator.offset.text} is "
                            "ignored by ros_control (offsets belong to joints); not exported")
        return lost
    for actuator in t.actuators:
        for tag, number in (("mechanical_reduction", actuator.mechanical_reduction),
                            ("offset", actuator.offset)):
            if number is not None:
                lost.append(f"actuator '{actuator.name}': <{tag}> {number.text} is ignored by "
                            "ros2_control for simple transmissions (it reads the joint's); "
                            "not exported")
    return lost


def _notes(attachments: Sequence[Attachment], direction: Direction) -> list[str]:
    if not attachments:
        return []
    notes = [f"'{DRIVER}' stands for your actuator module (BB's URDF importer cannot choose "
             "one either)"]
    reversed_joints = [a.joint for a in attachments if a.reduction < 0]
    if reversed_joints:
        listed = ", ".join(reversed_joints)
        if direction == "reversed":
            notes.append(f"direction: {listed} run reversed, written as 'reversed? true'; BB's "
                         "URDF exporter drops it (--bb-direction negative-reduction writes a "
                         "negative reduction, which it keeps)")
        else:
            notes.append(f"direction: {listed} run reversed, written as a negative reduction "
                         "(BB's URDF exporter keeps it; 'reversed?' it would drop)")
    return notes
