"""One writer module per XML dialect; each builds a ``<transmission>`` element from the model."""

from __future__ import annotations

from lxml import etree

from txtool.dialects import ros1, ros2
from txtool.model.core import Dialect, Transmission


def build(
    t: Transmission, dialect: Dialect, *, indent: str = "  ", step: str = "  ",
    namespace: str | None = None,
) -> etree._Element:
    """A ``<transmission>`` element for ``t`` formatted to sit at ``indent``.

    ``namespace`` is the default namespace of the place it goes to (some URDFs declare one).
    """
    writer = ros1.write if dialect == "ros1" else ros2.write
    element = writer(t, dialect)
    if namespace:
        for node in element.iter():
            node.tag = f"{{{namespace}}}{node.tag}"
    pretty(element, indent, step)
    return element


def pretty(element: etree._Element, indent: str, step: str) -> None:
    """Indent ``element``'s descendants; leaf text is left alone."""
    children = element[:]
    if not children:
        return
    inner = "\n" + indent + step
    element.text = inner
    for child in children:
        if len(child):  # a leaf keeps its text
            pretty(child, indent + step, step)
        child.tail = inner
    children[-1].tail = "\n" + indent
