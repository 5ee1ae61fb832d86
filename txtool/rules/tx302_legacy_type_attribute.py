"""The transmission type given as a ``type="..."`` attribute.

What it does: reports a ROS 1 ``<transmission type="...">``, in either form published robots
use: legacy (pre-Hydro, pr2_mechanism_model era), where the attribute is the only type, often
with ``<mechanicalReduction>`` directly under ``<transmission>``; and hybrid, the attribute
*and* a ``<type>`` element (husky, urdf_sim_tutorial).

Why it matters: ros_control reads the type only from the ``<type>`` child element. A legacy
transmission is skipped with "No type element found in transmission 'T'", and a reduction
standing directly under ``<transmission>`` is never read (the SimpleTransmission loader wants
the actuator's): a warning. In the hybrid form the attribute is read by nothing: harmless but
misleading, an ``info``.

Loader: ros_control (ros-controls/ros_control transmission_interface/src/transmission_parser.cpp
``TransmissionParser::parse`` takes the ``<type>`` child).

Failing example::

    <robot name="r">
      <transmission name="wheel_trans" type="SimpleTransmission">
        <joint name="wheel">
          <hardwareInterface>hardware_interface/VelocityJointInterface</hardwareInterface>
        </joint>
        <actuator name="wheel_motor"/>
        <mechanicalReduction>1</mechanicalReduction>
      </transmission>
    </robot>

Expected finding: ``2:3 warning TX302 transmission 'wheel_trans' gives its type as the legacy
type="SimpleTransmission" attribute: ros_control reads only a <type> element and skips it ('No
type element found')``

Passing example::

    <robot name="r">
      <transmission name="wheel_trans">
        <type>transmission_interface/SimpleTransmission</type>
        <joint name="wheel">
          <hardwareInterface>hardware_interface/VelocityJointInterface</hardwareInterface>
        </joint>
        <actuator name="wheel_motor">
          <mechanicalReduction>1</mechanicalReduction>
        </actuator>
      </transmission>
    </robot>

Fix: ``txtool migrate --write`` writes the passing example: in the hybrid form it removes the
attribute; for a legacy ``SimpleTransmission`` or ``transmission_interface/SimpleTransmission``
it adds ``<type>transmission_interface/SimpleTransmission</type>`` as the first child and
removes the attribute; and when the type is SimpleTransmission, a ``<mechanicalReduction>``
directly under ``<transmission>`` moves into the single ``<actuator>`` (unless that actuator
already has one), keeping its text, so xacro expressions survive. Custom attribute types
(``pr2_mechanism_model/*``) have loaders of their own and no standard equivalent; they are
reported, not fixed. New and moved elements take the indentation of the surrounding XML.
"""

from __future__ import annotations

from collections.abc import Iterator

from lxml import etree

from txtool.dialects.read import Found, detect_dialect, first_child_text, transmission_elements
from txtool.lint.context import LintContext
from txtool.lint.problem import Problem
from txtool.lint.rule_helpers import children, label, per_transmission

CODE = "TX302"
NAME = "legacy-type-attribute"
SEVERITY = "warning"
FIXABLE = True

SIMPLE = "transmission_interface/SimpleTransmission"
_SIMPLE_ATTRIBUTES = ("SimpleTransmission", SIMPLE)


def _type_element_text(transmission: etree._Element) -> str:
    return (first_child_text(transmission, "type") or "").strip()


@per_transmission
def check(ctx: LintContext) -> Iterator[Problem]:
    for tx in ctx.facts:
        attribute = tx.element.get("type")
        if attribute is None or not tx.ros1:
            continue
        found = tx.found
        fixable = None if _fixed_by_us(found.element, attribute) else False
        hybrid = bool(_type_element_text(found.element))
        yield ctx.problem(CODE, found.element, _message(found, attribute), fixable=fixable,
                          loader_severity="info" if hybrid else None)


def _fixed_by_us(transmission: etree._Element, attribute: str) -> bool:
    """The fix drops a redundant attribute and rewrites simple types; custom ones are left."""
    return bool(_type_element_text(transmission)) or attribute.strip() in _SIMPLE_ATTRIBUTES


def _message(found: Found, attribute: str) -> str:
    if _type_element_text(found.element):
        return (
            f"{label(found)} has a type=\"{attribute}\" attribute beside its <type> element: "
            "ros_control ignores the attribute (nothing reads it)"
        )
    message = (
        f"{label(found)} gives its type as the legacy type=\"{attribute}\" attribute: "
        "ros_control reads only a <type> element and skips it ('No type element found')"
    )
    if attribute.strip() not in _SIMPLE_ATTRIBUTES:
        message += "; a custom type, port it by hand"
    return message


def fix(root: etree._Element) -> int:
    fixed = 0
    for transmission in transmission_elements(root):
        attribute = transmission.get("type")
        if attribute is None or detect_dialect(transmission) != "ros1":
            continue
        if not _fixed_by_us(transmission, attribute):
            continue
        written = _type_element_text(transmission)
        if not written:
            type_element = etree.Element(_same_namespace(transmission, "type"))
            type_element.text = SIMPLE
            insert_child(transmission, type_element, 0)
        del transmission.attrib["type"]
        if (written or SIMPLE) in _SIMPLE_ATTRIBUTES:  # SimpleTransmission, old or new name
            _move_reduction_to_actuator(transmission)
        fixed += 1
    return fixed


def _move_reduction_to_actuator(transmission: etree._Element) -> None:
    reductions = children(transmission, "mechanicalReduction")
    actuators = children(transmission, "actuator")
    if len(reductions) != 1 or len(actuators) != 1:
        return
    if children(actuators[0], "mechanicalReduction"):
        return
    remove_child(reductions[0])
    insert_child(actuators[0], reductions[0], len(actuators[0]))


def _same_namespace(parent: etree._Element, name: str) -> str:
    namespace = etree.QName(parent).namespace
    return f"{{{namespace}}}{name}" if namespace else name


# Whitespace-preserving edits, shared with the other fixes.


def _text_before(element: etree._Element) -> str | None:
    previous = element.getprevious()
    if previous is not None:
        return previous.tail
    parent = element.getparent()
    return parent.text if parent is not None else None


def line_indent(element: etree._Element) -> str | None:
    """The whitespace that starts ``element``'s line; None when something precedes it."""
    before = _text_before(element)
    if before is None or "\n" not in before:
        return None
    last = before.rsplit("\n", 1)[1]
    return None if last.strip() else last


def indent_step(element: etree._Element) -> str:
    """One level of indentation as used inside or around ``element`` (two spaces if unknown)."""
    for scope in (element, element.getparent()):
        outer = line_indent(scope) if scope is not None else None
        if scope is None or outer is None:
            continue
        for child in scope:
            inner = line_indent(child)
            if inner is not None and inner.startswith(outer) and len(inner) > len(outer):
                return inner[len(outer) :]
    return "\t" if "\t" in (line_indent(element) or "") else "  "


def _children_gap(parent: etree._Element) -> str | None:
    """Newline plus indentation that separates ``parent``'s children, if they are laid out."""
    for child in parent:
        indent = line_indent(child)
        if indent is not None:
            return "\n" + indent
    return None


def insert_child(parent: etree._Element, child: etree._Element, index: int) -> None:
    """Insert ``child`` at ``index`` among ``parent``'s children, laid out like its siblings."""
    kids = list(parent)
    if not kids:
        own = line_indent(parent)
        child.tail = None
        if own is not None and not (parent.text or "").strip():
            parent.text = "\n" + own + indent_step(parent)
            child.tail = "\n" + own
        parent.append(child)
        return
    gap = _children_gap(parent)
    if index < len(kids):
        child.tail = gap
        kids[index].addprevious(child)
        return
    last = kids[-1]
    child.tail = last.tail
    last.tail = gap
    last.addnext(child)


def remove_child(element: etree._Element) -> None:
    """Remove ``element`` and the whitespace that led up to it (its tail stays)."""
    parent = element.getparent()
    if parent is None:
        return
    previous = element.getprevious()
    before = previous.tail if previous is not None else parent.text
    joined = element.tail if before is None or not before.strip() else before + (element.tail or "")
    if previous is not None:
        previous.tail = joined
    else:
        parent.text = joined
    element.tail = None
    parent.remove(element)
