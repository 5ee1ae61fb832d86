"""Faults injected into a known-good config: each a precise edit of its XML.

:func:`inject` takes the robot's own config (bytes), the transmissions a run of it simulates
and a fault name, and returns the faulty config with the cause kinds
(:data:`txtool.simulation.result.KINDS`) the diagnosis must name, or None where the fault does
not apply to this robot (no coupled transmission, no declared interface, ...). The edits touch
one transmission (the first simulated one of the kind the fault needs, or the one of a given
joint), in the dialect the simulation reads: the ``<ros2_control>`` block when the file has
one, else the ROS 1 ``<transmission>`` elements.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

from lxml import etree

from txtool.dialects.translate import interface_kind
from txtool.io.xmlio import parse_bytes

FAULTS = (
    "reduction x2", "reduction x0.5", "reduction x1.1", "sign reversed", "offset +0.3",
    "offset +0.01", "joints swapped", "actuator roles swapped", "effort convention",
    "joint removed", "interface changed",
)
# The fault in its own words: the cause kinds of which one must be named.
NAMED = {
    "reduction x2": {"reduction"}, "reduction x0.5": {"reduction"},
    "reduction x1.1": {"reduction"},
    "sign reversed": {"direction"},
    "offset +0.3": {"offset"}, "offset +0.01": {"offset"},
    "joints swapped": {"joints_swapped"},
    "actuator roles swapped": {"roles_swapped"},  # ROS 2: see COUPLED_ROS2
    "effort convention": {"effort_convention"},
    "joint removed": {"missing_transmission"},
    "interface changed": {"interface"},
}
# A coupled transmission's first actuator reversed also reads as its joints swapped (when the
# joint reductions are equal, diagnose.py); ros2_control reads no roles, its mistake is the XML
# order of the actuators.
COUPLED = {"sign reversed": {"direction", "joints_swapped"}}
COUPLED_ROS2 = {"actuator roles swapped": {"xml_order"}}
# What else the same edit may honestly show: swapped joints carry their offsets and their
# interfaces along; ros2_control's XML order shows as the reductions (and signs) it moves; a
# transmission the robot leaves out because another took its actuator comes in when that one
# is removed (open_manipulator's omy_f3m names actuator1 twice).
ALSO = {
    "joints swapped": {"offset", "interface"},
    "actuator roles swapped": {"reduction", "direction"},
    "joint removed": {"transmission_kind"},
}


@dataclass(frozen=True)
class Fault:
    name: str
    config: bytes
    named: frozenset[str]  # one of these kinds must be named
    allowed: frozenset[str]  # every cause named is of one of these kinds
    transmission: str  # the transmission edited


class Config:
    """The config's transmissions as the simulation reads them, for editing."""

    def __init__(self, text: bytes, simulated: Sequence[str]) -> None:
        self.tree = parse_bytes(text, "config")
        root = self.tree.getroot()
        self.ros2 = bool(root.findall("ros2_control/transmission"))
        found = root.findall("ros2_control/transmission" if self.ros2 else "transmission")
        self.transmissions = [t for t in found if t.get("name") in simulated]

    def bytes(self) -> bytes:
        return etree.tostring(self.tree, xml_declaration=True, encoding="utf-8")

    def kind(self, t: etree._Element) -> str:
        text = (t.findtext("plugin" if self.ros2 else "type") or t.get("type") or "")
        for written, kind in (("Simple", "simple"), ("Differential", "differential"),
                              ("FourBar", "four_bar")):
            if written in text:
                return kind
        return "other"

    def first(self, kinds: tuple[str, ...], joint: str | None = None) -> etree._Element | None:
        for t in self.transmissions:
            joints = [j.get("name") for j in t.findall("joint")]
            if self.kind(t) in kinds and (joint is None or joint in joints):
                return t
        return None

    def reduction(self, t: etree._Element) -> etree._Element:
        """The element of the reduction that scales the transmission's (first) joint."""
        if self.ros2 and self.kind(t) == "simple":
            member, tag = t.find("joint"), "mechanical_reduction"
        else:
            member = t.find("actuator")
            tag = "mechanical_reduction" if self.ros2 else "mechanicalReduction"
        assert member is not None
        found = member.find(tag)
        if found is None:
            found = etree.SubElement(member, tag)
            found.text = "1"
        return found

    def offset(self, t: etree._Element) -> etree._Element:
        joint = t.find("joint")
        assert joint is not None
        found = joint.find("offset")
        if found is None:
            found = etree.SubElement(joint, "offset")
            found.text = "0"
        return found

    def interfaces(self, t: etree._Element) -> list[etree._Element]:
        """The elements naming how the transmission's first joint is commanded."""
        joint = t.find("joint")
        assert joint is not None
        if not self.ros2:
            return [e for e in joint.findall("hardwareInterface")
                    if interface_kind(e.text or "") in ("position", "velocity", "effort")]
        block = t.getparent()
        assert block is not None
        return [e for j in block.findall("joint") if j.get("name") == joint.get("name")
                for e in j.findall("command_interface")
                if e.get("name") in ("position", "velocity", "effort")]


def _scale(value: etree._Element, factor: float) -> None:
    value.text = f"{float(value.text or '0') * factor:.12g}"


def _shift(value: etree._Element, delta: float) -> None:
    value.text = f"{float(value.text or '0') + delta:.12g}"


def _reduction(factor: float) -> Callable[[Config, str | None], str | None]:
    def edit(config: Config, joint: str | None) -> str | None:
        t = config.first(("simple", "differential", "four_bar"), joint)
        if t is None:
            return None
        _scale(config.reduction(t), factor)
        return t.get("name")
    return edit


def _offset(delta: float) -> Callable[[Config, str | None], str | None]:
    def edit(config: Config, joint: str | None) -> str | None:
        t = config.first(("simple", "differential", "four_bar"), joint)
        if t is None:
            return None
        _shift(config.offset(t), delta)
        return t.get("name")
    return edit


def _swap_joints(config: Config, joint: str | None) -> str | None:
    """Two simple transmissions exchange their joints."""
    first = config.first(("simple",), joint)
    others = [t for t in config.transmissions
              if config.kind(t) == "simple" and t is not first]
    if first is None or not others:
        return None
    a, b = first.find("joint"), others[0].find("joint")
    assert a is not None and b is not None
    names = a.get("name"), b.get("name")
    a.set("name", names[1] or "")
    b.set("name", names[0] or "")
    return first.get("name")


def _swap_actuator_roles(config: Config, joint: str | None) -> str | None:
    """ROS 1: the two actuators' ``<role>`` exchanged in place. ros2_control reads no roles
    (ros2_control#3382): there the same mistake is the actuators listed in the other order,
    which moves their parameters."""
    t = config.first(("differential", "four_bar"), joint)
    if t is None:
        return None
    actuators = t.findall("actuator")
    if config.ros2:
        first = actuators[0]
        t.remove(first)
        actuators[1].addnext(first)
        return t.get("name")
    roles = [a.find("role") for a in actuators]
    assert roles[0] is not None and roles[1] is not None
    roles[0].text, roles[1].text = roles[1].text, roles[0].text
    return t.get("name")


def _remove(config: Config, joint: str | None) -> str | None:
    t = config.first(("simple", "differential", "four_bar"), joint)
    if t is None:
        return None
    parent = t.getparent()
    assert parent is not None
    parent.remove(t)
    return t.get("name")


def _interface(config: Config, joint: str | None) -> str | None:
    """Effort becomes position; any other command interface becomes effort."""
    for t in config.transmissions:
        names = [j.get("name") for j in t.findall("joint")]
        found = config.interfaces(t)
        if not found or (joint is not None and joint not in names):
            continue
        for element in found:
            if config.ros2:
                element.set("name", "position" if element.get("name") == "effort" else "effort")
            else:
                effort = interface_kind(element.text or "") == "effort"
                element.text = ("hardware_interface/PositionJointInterface" if effort
                                else "hardware_interface/EffortJointInterface")
        return t.get("name")
    return None


EDITS: dict[str, Callable[[Config, str | None], str | None]] = {
    "reduction x2": _reduction(2.0), "reduction x0.5": _reduction(0.5),
    "reduction x1.1": _reduction(1.1), "sign reversed": _reduction(-1.0),
    "offset +0.3": _offset(0.3), "offset +0.01": _offset(0.01),
    "joints swapped": _swap_joints, "actuator roles swapped": _swap_actuator_roles,
    "joint removed": _remove, "interface changed": _interface,
}


def inject(text: bytes, simulated: Sequence[str], fault: str, joint: str | None = None,
           ros1_twin: bytes | None = None) -> Fault | None:
    """``text`` with ``fault``, on the transmission of ``joint`` if given; None if it does not
    apply. "effort convention" is the same transmissions read by the other loader: the ROS 1
    twin of a ROS 2 config with a four-bar (ros_control's effort map is not ros2_control's)."""
    named = frozenset(NAMED[fault])
    allowed = named | ALSO.get(fault, set())
    if fault == "effort convention":
        config = Config(text, simulated)
        four_bar = config.first(("four_bar",), joint)
        if ros1_twin is None or not config.ros2 or four_bar is None:
            return None
        return Fault(fault, ros1_twin, named, allowed, four_bar.get("name") or "")
    config = Config(text, simulated)
    edited = EDITS[fault](config, joint)
    if edited is None:
        return None
    target = next(t for t in config.transmissions if t.get("name") == edited)
    if config.kind(target) != "simple":
        named = frozenset((COUPLED_ROS2 if config.ros2 else {}).get(fault)
                          or COUPLED.get(fault) or named)
    return Fault(fault, config.bytes(), named, named | ALSO.get(fault, set()), edited)


def with_reduction_factor(text: bytes, simulated: Sequence[str], factor: float,
                          joint: str | None = None) -> tuple[bytes, str] | None:
    """``text`` with one transmission's reduction times ``factor`` (the one "reduction xK"
    edits), and that transmission's name."""
    return _edited(text, simulated, _reduction(factor), joint)


def with_offset(text: bytes, simulated: Sequence[str], delta: float,
                joint: str | None = None) -> tuple[bytes, str] | None:
    """``text`` with one transmission's joint offset moved by ``delta``."""
    return _edited(text, simulated, _offset(delta), joint)


def _edited(text: bytes, simulated: Sequence[str],
            edit: Callable[[Config, str | None], str | None], joint: str | None
            ) -> tuple[bytes, str] | None:
    config = Config(text, simulated)
    name = edit(config, joint)
    return None if name is None else (config.bytes(), name)
