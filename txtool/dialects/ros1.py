"""Writer for ROS 1 (ros_control) transmissions: ``<type>``, ``<hardwareInterface>``,
``<mechanicalReduction>``, ``<offset>`` and ``<role>`` elements."""

from __future__ import annotations

from lxml import etree

from txtool.model.core import Member, Number, Transmission


def write(t: Transmission, dialect: str = "ros1") -> etree._Element:
    element = etree.Element("transmission", name=t.name)
    etree.SubElement(element, "type").text = t.type
    for joint in t.joints:
        _member(element, "joint", joint, joint=True)
    for actuator in t.actuators:
        _member(element, "actuator", actuator, joint=False)
    return element


def _member(parent: etree._Element, tag: str, member: Member, *, joint: bool) -> None:
    element = etree.SubElement(parent, tag, name=member.name)
    if member.role is not None:
        etree.SubElement(element, "role").text = member.role
    if joint:
        _number(element, "offset", member.offset)
    _number(element, "mechanicalReduction", member.mechanical_reduction)
    for interface in member.interfaces:
        etree.SubElement(element, "hardwareInterface").text = interface


def _number(parent: etree._Element, tag: str, number: Number | None) -> None:
    if number is not None and number.text is not None:
        etree.SubElement(parent, tag).text = number.text
