"""The xacro elements a transmission stands in: conditionals it can be moved out of (copied
around it), and how to name any of them in a message."""

from __future__ import annotations

from itertools import takewhile

from lxml import etree

from txtool.io.xmlio import local
from txtool.transform.placement.layout import namespace_of

XACRO = ("http://www.ros.org/wiki/xacro", "http://ros.org/wiki/xacro")
_CONDITIONS = {"if", "unless"}


def is_condition(element: etree._Element) -> bool:
    """Whether ``element`` is a ``xacro:if`` or ``xacro:unless``."""
    return namespace_of(element) in XACRO and local(element) in _CONDITIONS


def between(old: etree._Element, component: etree._Element) -> list[etree._Element]:
    """The elements between ``old`` and its ancestor ``component``, innermost first."""
    return list(takewhile(lambda parent: parent is not component, old.iterancestors()))


def prefixed(element: etree._Element) -> str:
    """``element`` as a message names it: ``xacro:if value="..."``, ``xacro:macro
    name="..."``, or its local name."""
    tag = local(element)
    if namespace_of(element) in XACRO:
        return f"xacro:{tag}" + (f" value=\"{element.get('value')}\""
                                  if element.get("value") is not None else
                                  f" name=\"{element.get('name')}\""
                                  if element.get("name") is not None else "")
    return tag
