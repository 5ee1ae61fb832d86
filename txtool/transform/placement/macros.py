"""Transmissions converted inside a xacro macro: one ``<ros2_control>`` per macro, or none.

ros2_control makes one hardware component of each ``<ros2_control>`` element of the expanded
robot (hardware_interface/src/component_parser.cpp, ``parse_control_resources_from_urdf``: one
``HardwareInfo`` per element; resource_manager.cpp loads one plugin instance for each). A
``<ros2_control>`` written inside a macro is there once per call of the macro. So the
transmissions that stand together in one macro go into one block, in place (nothing crosses
the macro's boundary); and where the robot holds that macro more than once (called more than
once, or inside a macro called more than once), the conversion is refused with the macro's
name and its calls: each call would be a hardware
component of its own, one per joint for a macro called once per joint, each running the
hardware plugin alone (where the robot has one driver, one component must declare every
joint). Calls the document does not show (a macro library included elsewhere) are counted
in the files migrated with it (:func:`calls_in_files`); where none of them shows a call, the
block is written, and a note says that each call makes one component.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from typing import NamedTuple

from lxml import etree

from txtool.io.xmlio import InputError, local, parse_bytes
from txtool.transform.placement.layout import namespace_of
from txtool.transform.placement.scope import XACRO


def is_xacro(element: etree._Element) -> bool:
    """Whether ``element`` is one of xacro's: in its namespace, or with its prefix (xacro
    reads the prefix: files also bind it to ``http://wiki.ros.org/xacro``)."""
    return namespace_of(element) in XACRO or element.prefix == "xacro"


def enclosing_macro(element: etree._Element) -> etree._Element | None:
    """The nearest ``xacro:macro`` around ``element``, or None."""
    return next((parent for parent in element.iterancestors()
                 if local(parent) == "macro" and is_xacro(parent)), None)


class Call(NamedTuple):
    """One call of a macro: where (a line of the document, or ``FILE:LINE``), and the name of
    the macro it stands in (None at the top of a file)."""

    where: str
    within: str | None


MacroCalls = Mapping[str, tuple[Call, ...]]  # by the called macro's name

# xacro's own elements, which are not calls of a macro (xacro/__init__.py, eval_all).
_BUILTIN = frozenset({"macro", "property", "include", "if", "unless", "arg", "insert_block",
                      "element", "attribute", "call", "eval-comments"})


def calls_in(root: etree._Element, file: str | None = None) -> dict[str, list[Call]]:
    """The macro calls (``<xacro:NAME .../>``) of one tree, by name: ``file`` names the file
    in their places (else the line alone)."""
    found: dict[str, list[Call]] = {}
    for element in root.iter(etree.Element):
        if not is_xacro(element) or local(element) in _BUILTIN:
            continue
        line = element.sourceline or 0
        where = f"{file}:{line}" if file is not None else f"line {line}"
        macro = enclosing_macro(element)
        within = (macro.get("name") or "").strip() if macro is not None else None
        found.setdefault(local(element), []).append(Call(where, within))
    return found


def calls_in_files(files: Iterable[tuple[str, bytes]]) -> dict[str, tuple[Call, ...]]:
    """:func:`calls_in` for each of ``files`` (path and bytes; one that does not parse has
    none), together."""
    found: dict[str, list[Call]] = {}
    for path, data in files:
        if b"xacro" not in data:
            continue
        try:
            root = parse_bytes(data, path).getroot()
        except InputError:
            continue
        for name, calls in calls_in(root, path).items():
            found.setdefault(name, []).extend(calls)
    return {name: tuple(calls) for name, calls in found.items()}


def times(name: str, calls: MacroCalls, seen: frozenset[str] = frozenset()) -> int:
    """How many times the expanded robot holds the body of macro ``name``: each call inside
    another macro counts once for each time that one is expanded (a macro no call is seen of
    counts once)."""
    total = 0
    for call in calls.get(name, ()):
        inner = call.within
        if inner is None or inner in seen or inner == name or not calls.get(inner):
            total += 1
        else:
            total += times(inner, calls, seen | {name})
    return total


def refusal(transmissions: list[str], macro: etree._Element, count: int,
            where: list[Call], scope: str = "this file expands") -> str:
    """The one line that says why transmissions inside ``macro`` are not converted (``count``:
    how many times ``scope`` expands it; ``where``: its calls)."""
    name = (macro.get("name") or "").strip()
    shown = ", ".join(call.where + (f" in <xacro:macro name=\"{call.within}\">"
                                    if call.within else "") for call in where[:4]) + (
        ", ..." if len(where) > 4 else "")
    which = (f"transmission '{transmissions[0]}'" if len(transmissions) == 1 else
             f"{len(transmissions)} transmissions ('{transmissions[0]}', ...)")
    return (f"{which}: inside <xacro:macro name=\"{name}\"> (line {macro.sourceline}), which "
            f"{scope} {count} times (called at {shown}): converted there, each "
            "call would be a <ros2_control> hardware component of its own; write the "
            "transmissions where the robot's one <ros2_control> is (outside the macro), or "
            "convert the expanded robot")


def per_call(block: str, macro: etree._Element) -> str:
    """The note for a block written inside a macro whose calls the document does not show."""
    return (f"<ros2_control name=\"{block}\"> is written inside <xacro:macro "
            f"name=\"{(macro.get('name') or '').strip()}\">: each call of the macro makes one "
            "ros2_control hardware component")
