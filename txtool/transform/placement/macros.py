"""Transmissions converted inside a xacro macro: one ``<ros2_control>`` per macro, or none.

ros2_control makes one hardware component of each ``<ros2_control>`` element of the expanded
robot (hardware_interface/src/component_parser.cpp, ``parse_control_resources_from_urdf``: one
``HardwareInfo`` per element; resource_manager.cpp loads one plugin instance for each). A
``<ros2_control>`` written inside a macro is there once per call of the macro. So the
transmissions that stand together in one macro go into one block, in place (nothing crosses
the macro's boundary); and where the document calls that macro more than once, the
conversion is refused with the macro's name and its calls: each call would be a hardware
component of its own, one per joint for a macro called once per joint, each running the
hardware plugin alone (where the robot has one driver, one component must declare every
joint). Calls the document does not show (a macro library included elsewhere) are counted
in the files migrated with it (:func:`calls_in_files`); where none of them shows a call, the
block is written, and a note says that each call makes one component.
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Mapping

from lxml import etree

from txtool.io.xmlio import local
from txtool.transform.placement.layout import namespace_of
from txtool.transform.placement.scope import XACRO


def enclosing_macro(element: etree._Element) -> etree._Element | None:
    """The nearest ``xacro:macro`` around ``element``, or None."""
    parent = element.getparent()
    while parent is not None:
        if namespace_of(parent) in XACRO and local(parent) == "macro":
            return parent
        parent = parent.getparent()
    return None


def calls(root: etree._Element, macro: etree._Element) -> list[int]:
    """The lines of the document's calls of ``macro`` (``<xacro:NAME .../>``)."""
    name = (macro.get("name") or "").strip()
    if not name:
        return []
    return [element.sourceline or 0 for namespace in XACRO
            for element in root.iter(f"{{{namespace}}}{name}")]


# xacro's own elements, which are not calls of a macro (xacro/__init__.py, eval_all).
_BUILTIN = frozenset({b"macro", b"property", b"include", b"if", b"unless", b"arg",
                      b"insert_block", b"element", b"attribute", b"call", b"eval-comments"})
_CALL = re.compile(rb"<xacro:([A-Za-z_][\w.\-]*)")

MacroCalls = Mapping[str, tuple[str, ...]]  # a macro's name -> where it is called (FILE:LINE)


def calls_in_files(files: Iterable[tuple[str, bytes]]) -> dict[str, tuple[str, ...]]:
    """Where each macro is called in ``files`` (path and bytes), as ``FILE:LINE``, found in the
    bytes (``<xacro:NAME``, the prefix xacro files use)."""
    found: dict[str, list[str]] = {}
    for path, data in files:
        line, at = 1, 0
        for match in _CALL.finditer(data):
            if match.group(1) in _BUILTIN:
                continue
            line += data.count(b"\n", at, match.start())
            at = match.start()
            found.setdefault(match.group(1).decode(), []).append(f"{path}:{line}")
    return {name: tuple(where) for name, where in found.items()}


def refusal(transmissions: list[str], macro: etree._Element, where: list[str]) -> str:
    """The one line that says why transmissions inside ``macro`` are not converted
    (``where``: its calls, as lines of the document or ``FILE:LINE``)."""
    name = (macro.get("name") or "").strip()
    shown = ", ".join(where[:4]) + (", ..." if len(where) > 4 else "")
    which = (f"transmission '{transmissions[0]}'" if len(transmissions) == 1 else
             f"{len(transmissions)} transmissions ('{transmissions[0]}', ...)")
    return (f"{which}: inside <xacro:macro name=\"{name}\"> (line {macro.sourceline}), which "
            f"is called {len(where)} times ({shown}): converted there, each "
            "call would be a <ros2_control> hardware component of its own; write the "
            "transmissions where the robot's one <ros2_control> is (outside the macro), or "
            "convert the expanded robot")


def per_call(block: str, macro: etree._Element) -> str:
    """The note for a block written inside a macro whose calls the document does not show."""
    return (f"<ros2_control name=\"{block}\"> is written inside <xacro:macro "
            f"name=\"{(macro.get('name') or '').strip()}\">: each call of the macro makes one "
            "ros2_control hardware component")
