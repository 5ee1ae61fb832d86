"""Writer for ROS 2 (ros2_control) transmissions.

Proposal 2 (``ros2-p2``) is the form ros2_control parses: ``role`` attributes,
``<mechanical_reduction>``/``<offset>`` children, ``read_only``, ``<param name>``.
Proposal 1 (``ros2-p1``) writes roles as ``<role>`` elements instead.
"""

from __future__ import annotations

from lxml import etree

from txtool.model.core import Member, Number, Transmission


def write(t: Transmission, dialect: str = "ros2-p2") -> etree._Element:
    element = etree.Element("transmission", name=t.name)
    etree.SubElement(element, "plugin").text = t.type
    role_attribute = dialect == "ros2-p2"
    for actuator in t.actuators:
        _member(element, "actuator", actuator, role_attribute)
    for joint in t.joints:
        _member(element, "joint", joint, role_attribute)
    for name, value in t.parameters:
        etree.SubElement(element, "param", name=name).text = value
    return element


def _member(parent: etree._Element, tag: str, member: Member, role_attribute: bool) -> None:
    element = etree.SubElement(parent, tag, name=member.name)
    if member.role is not None and role_attribute:
        element.set("role", member.role)
    if member.read_only:
        element.set("read_only", "true")
    if member.role is not None and not role_attribute:
        etree.SubElement(element, "role").text = member.role
    _number(element, "mechanical_reduction", member.mechanical_reduction)
    _number(element, "offset", member.offset)


def _number(parent: etree._Element, tag: str, number: Number | None) -> None:
    if number is not None and number.text is not None:
        etree.SubElement(parent, tag).text = number.text
