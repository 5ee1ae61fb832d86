"""One document as ros2_control's compiled parser and loaders read it, and as txtool does.

Both sides become the same plain structure (:func:`oracle_view`, :func:`txtool_view`), so a
difference is a line naming what differs. The parser's rules are those of ros-controls/
ros2_control hardware_interface/src/component_parser.cpp: ``parse_transmission_from_xml``
(:589, names and ``<plugin>`` required), ``parse_transmission_joint_from_xml`` (:553, a ``role``
attribute required, ``read_only`` through ``parse_bool``, numbers through
``get_parameter_value_or``, :160: the first child of that name whose ``GetText()`` is not null,
the default where it does not convert) and ``auto_fill_transmission_interfaces`` (:636, joints
declared in the component; an actuator component's transmission has one joint and gets
``actuator1`` appended).
"""

from __future__ import annotations

import math
from typing import Any

from tests.oracle.reference import hex_float
from txtool.dialects.read import read_source
from txtool.io.xmlio import InputError, Source, parse_bytes
from txtool.model.distro import Distro
from txtool.model.semantics import ros2_value
from txtool.views.effective import PARSER_REFUSES, bindings_of

View = dict[str, Any]


def _number(value: float) -> str:
    """Bit-exact text of a value (NaN has one spelling: the loaders never keep its payload)."""
    return "nan" if math.isnan(value) else float.hex(value)


def oracle_view(result: dict) -> View:
    """The parser oracle's result, as :func:`txtool_view` gives txtool's."""
    if not result["accepted"]:
        cause = "transmission" if result.get("accepted_without_transmissions") else "other"
        return {"accepted": False, "cause": cause, "error": result["error"]}
    transmissions = []
    for hardware in result["hardware"]:
        for t in hardware["transmissions"]:
            shown: View = {
                "name": t["name"], "type": t["type"],
                "joints": [_oracle_member(m) for m in t["joints"]],
                "actuators": [_oracle_member(m) for m in t["actuators"]],
            }
            if "loader" in t:
                shown.update(_oracle_loader(t["loader"]))
            transmissions.append(shown)
    return {"accepted": True, "transmissions": transmissions}


def _oracle_member(m: dict) -> tuple:
    return (m["name"], m["role"], _number(hex_float(m["mechanical_reduction"])),
            _number(hex_float(m["offset"])), m["read_only"])


def _oracle_loader(loader: dict) -> View:
    if not loader["loaded"]:
        return {"loaded": False}
    return {
        "loaded": loader["configured"] or loader["configure_error"],
        "joint_reduction": [_number(hex_float(v)) for v in loader["joint_reduction"]],
        "joint_offset": [_number(hex_float(v)) for v in loader["joint_offset"]],
        "actuator_reduction": [_number(hex_float(v)) for v in loader["actuator_reduction"]],
        "joint_order": loader["joint_order"],
        "actuator_order": loader["actuator_order"],
    }


def txtool_view(data: bytes, distro: Distro) -> View:
    """What txtool says ``distro``'s ros2_control makes of the document ``data``."""
    try:
        source = Source("variant.urdf", data, parse_bytes(data, "variant.urdf"))
    except InputError as exc:
        return {"accepted": False, "cause": "xml", "error": str(exc)}
    return source_view(source, distro)


def source_view(source: Source, distro: Distro) -> View:
    """:func:`txtool_view` of a loaded (or expanded) document."""
    found = [f for f in read_source(source, locate=False) if _read_by_parser(f.element, source)]
    bindings = bindings_of(found, distro)
    refusals = [b.reason for b in bindings if b.reason and b.reason.startswith(PARSER_REFUSES)]
    if refusals:
        return {"accepted": False, "cause": "transmission", "error": refusals[0]}
    transmissions = []
    for item, binding in zip(found, bindings, strict=True):
        t = item.transmission
        added = [("actuator1", "actuator1", _number(1.0), _number(0.0), False)
                 for _ in binding.added_actuators]
        shown: View = {
            "name": t.name, "type": t.type,
            "joints": [_txtool_member(m, distro) for m in t.joints],
            "actuators": [_txtool_member(m, distro) for m in t.actuators] + added,
        }
        if t.kind != "other":
            shown.update(_txtool_loader(binding, t.kind))
        transmissions.append(shown)
    return {"accepted": True, "transmissions": transmissions}


def _read_by_parser(element: Any, source: Source) -> bool:
    """A transmission the parser reads: a child of a ``<ros2_control>`` child of the root."""
    parent = element.getparent()
    return (parent is not None and parent.tag == "ros2_control"
            and parent.getparent() is source.root and source.root.tag == "robot")


def _txtool_member(m: Any, distro: Distro) -> tuple:
    return (m.name, m.role or "", _number(ros2_value(m.mechanical_reduction, 1.0, distro)),
            _number(ros2_value(m.offset, 0.0, distro)), m.read_only)


def _txtool_loader(binding: Any, kind: str) -> View:
    if not binding.loadable:
        return {"loaded": False}
    slots = binding.slots
    return {
        "loaded": True,
        "joint_reduction": [_number(s.joint_reduction) for s in slots],
        "joint_offset": [_number(s.joint_offset) for s in slots],
        "actuator_reduction": [] if kind == "simple" else [_number(s.actuator_reduction)
                                                            for s in slots],
        "joint_order": sorted({s.joint for s in slots}),
        "actuator_order": sorted({s.actuator for s in slots}),
    }


# What configure() says where a hardware plugin passes no actuator handle (ros2_control
# transmission_interface simple_transmission.hpp, SimpleTransmission::configure).
NO_ACTUATOR_HANDLES = "No actuator handles were passed in"


def differences(oracle: View, txtool: View) -> list[tuple[str, str]]:
    """What differs: (class, detail) pairs; a class is a documented judgement's key or one of
    ``verdict``, ``count``, ``name``, ``member``, ``loaded``, ``value``."""
    if not oracle["accepted"] and oracle["cause"] == "other":
        return []  # the parser refuses the file for something other than its transmissions
    if txtool.get("cause") == "xml":
        return [("xml-1.0", f"txtool refuses the XML ({txtool['error']}), tinyxml2 reads it")]
    if oracle["accepted"] != txtool["accepted"]:
        said = {True: "accepts", False: "refuses"}
        return [("verdict", f"parser {said[oracle['accepted']]} ({oracle.get('error', '')}), "
                            f"txtool {said[txtool['accepted']]} ({txtool.get('error', '')})")]
    if not oracle["accepted"]:
        return []  # both refuse
    ours, theirs = txtool["transmissions"], oracle["transmissions"]
    if len(ours) != len(theirs):
        return [("count", f"parser reads {len(theirs)} transmissions, txtool {len(ours)}")]
    found = []
    for a, b in zip(theirs, ours, strict=True):
        found += _transmission_differences(a, b)
    return found


def _transmission_differences(parser: View, ours: View) -> list[tuple[str, str]]:
    found = []
    for key in ("name", "type", "joints", "actuators"):
        if parser[key] != ours[key]:
            cls = "member" if key in ("joints", "actuators") else "name"
            found.append((cls, f"{parser['name']!r} {key}: parser {parser[key]!r}, "
                               f"txtool {ours[key]!r}"))
    if "loaded" not in parser:
        return found
    loaded = parser["loaded"]
    if loaded == NO_ACTUATOR_HANDLES and ours.get("loaded"):
        found.append(("configure-without-actuators", f"{parser['name']!r}: {loaded}"))
        loaded = True
    elif isinstance(loaded, str):
        loaded = False  # configure() refuses it
    if loaded != ours.get("loaded"):
        return [*found, ("loaded", f"{parser['name']!r}: parser loader "
                                   f"{parser['loaded']!r}, txtool {ours.get('loaded')!r}")]
    skipped = {"name", "type", "joints", "actuators", "loaded"}
    if parser["loaded"] == NO_ACTUATOR_HANDLES:
        skipped.add("actuator_order")  # no actuator handle: txtool shows a stand-in name
    for key in sorted(set(parser) - skipped):
        if loaded and parser.get(key) != ours.get(key):
            found.append(("value", f"{parser['name']!r} {key}: parser {parser.get(key)!r}, "
                                   f"txtool {ours.get(key)!r}"))
    return found
