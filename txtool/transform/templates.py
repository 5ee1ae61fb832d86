"""Converted elements built once per key (:mod:`.memo`) and then copied with other names.

A transmission whose old element was keyed is built as :func:`txtool.dialects.build` builds
it, once per key and layout; every other one of the key is a copy with its own names put in
(equal keys build equal elements up to the names). For the block generated for a whole
document the copies are written as text and parsed in one go: lxml builds thousands of
elements from text far faster than one by one. A template is written as text only when that
text parses back to the very element (an element built with an empty text would come back
without one), and it holds no name it does not key.
"""

from __future__ import annotations

from collections.abc import Hashable

from lxml import etree

from txtool import dialects
from txtool.io.xmlio import safe_parser
from txtool.model.core import Transmission
from txtool.transform.memo import NAME, Renaming


class Templates:
    def __init__(self) -> None:
        self._elements: dict[Hashable, tuple[etree._Element, tuple[int | None, ...]]] = {}
        self._texts: dict[Hashable, tuple[list[bytes], tuple[int | None, ...]] | None] = {}
        self._declarations: dict[Hashable, tuple[bytes, bytes]] = {}

    def element(self, renaming: Renaming, t: Transmission, indent: str, step: str,
                namespace: str | None) -> etree._Element:
        """What ``dialects.build(t, ...)`` gives, ``t`` the conversion of an element of
        ``renaming``: built for the first of its key, copied and renamed for the others."""
        key = (renaming.key, t.dialect, indent, step, namespace)
        known = self._elements.get(key)
        if known is None:
            new = dialects.build(t, t.dialect, indent=indent, step=step, namespace=namespace)
            index = {name: i for i, name in enumerate(renaming.names)}
            plan = tuple([index.get(node.get("name")) for node in new.iter()])  # type: ignore[arg-type]
            self._elements[key] = (new.__deepcopy__(None), plan)
            return new
        template, plan = known
        new = template.__deepcopy__(None)  # copy.deepcopy's own bookkeeping costs as much
        for node, i in zip(new.iter(), plan, strict=True):
            if i is not None:
                node.set("name", renaming.names[i])
        return new

    def text(self, renaming: Renaming, t: Transmission, indent: str, step: str
             ) -> list[bytes] | None:
        """The text of :meth:`element` (no namespace), or None when it cannot be written so."""
        key = (renaming.key, t.dialect, indent, step)
        if key not in self._texts:
            self._texts[key] = _split(self.element(renaming, t, indent, step, None), renaming)
        known = self._texts[key]
        if known is None:
            return None
        parts, slots = known
        pieces = [parts[0]]
        for position, slot in enumerate(slots):
            name = parts[2 * position + 1] if slot is None else renaming.names[slot].encode()
            pieces += (name, parts[2 * position + 2])
        return pieces

    def declaration(self, interfaces: tuple[tuple[str, ...], ...], indent: str, step: str
                    ) -> tuple[bytes, bytes]:
        """A joint declaration at ``indent`` (no namespace) as text, before and after its
        name."""
        key = (interfaces, indent, step)
        known = self._declarations.get(key)
        if known is None:
            element = etree.Element("joint", name="")
            for name in interfaces[0]:
                etree.SubElement(element, "command_interface", name=name)
            for name in interfaces[1]:
                etree.SubElement(element, "state_interface", name=name)
            dialects.pretty(element, indent, step)
            head, _, tail = etree.tostring(element).partition(b' name=""')
            known = self._declarations[key] = (head + b' name="', b'"' + tail)
        return known


def _split(element: etree._Element, renaming: Renaming
           ) -> tuple[list[bytes], tuple[int | None, ...]] | None:
    """``element``'s text cut at its name attributes, and which name goes in each cut (None:
    the name as written), or None when the text does not give the element back."""
    text = etree.tostring(element, with_tail=False)
    if etree.tostring(etree.fromstring(text, safe_parser())) != text:
        return None
    index = {name.encode("ascii"): i for i, name in enumerate(renaming.names)}
    parts = NAME.split(text)  # what NAME matches goes; the names stay, between the others
    for position in range(0, len(parts) - 1, 2):
        parts[position] += b' name="'
        parts[position + 2] = b'"' + parts[position + 2]
    return parts, tuple([index.get(raw) for raw in parts[1::2]])


def parse_children(pieces: list[bytes]) -> list[etree._Element]:
    """The elements (with their tails) of the text ``pieces`` join to."""
    return list(etree.fromstring(b"<x>" + b"".join(pieces) + b"</x>", safe_parser()))
