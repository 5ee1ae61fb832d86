"""Converted elements built once per key (:mod:`.renamings`) and then copied with other names.

A transmission whose old element was keyed is built as :func:`txtool.dialects.build` builds
it, once per key and layout; every other one of the key is a copy with its own names put in
(equal keys build equal elements up to the names). For the block generated for a whole
document the copies are written as text and parsed in one go: lxml builds thousands of
elements from text far faster than one by one. A template is written as text only when that
text parses back to the very element (an element built with an empty text would come back
without one), and it holds no name it does not key.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Hashable
from operator import itemgetter
from typing import Protocol

from lxml import etree

from txtool import dialects
from txtool.io.xmlio import safe_parser
from txtool.model.core import Dialect, Transmission
from txtool.transform.repeated.renamings import NAME, Renaming

_UNSAFE = re.compile(rb"[^\x20-\x7e\n\t]|&#")  # a reference, or what another encoding writes


def plain(text: bytes) -> bool:
    """Whether ``text`` (a serialization) reads the same written in any ASCII encoding."""
    return _UNSAFE.search(text) is None


class Converted(Protocol):
    @property
    def new(self) -> Transmission: ...


class Templates:
    def __init__(self) -> None:
        self._elements: dict[Hashable, tuple[etree._Element, tuple[int | None, ...]]] = {}
        self._texts: dict[Hashable, tuple[str, Callable, bool] | None] = {}
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

    def text(self, renaming: Renaming, dialect: Dialect, indent: str, step: str,
             conversion: Converted, plain_only: bool = False) -> bytes | None:
        """The text of :meth:`element` (no namespace) for ``conversion.new``, whose dialect
        is ``dialect`` (read only for the first of a key and layout), or None when it cannot
        be written so (``plain_only``: or is not :func:`.block_text.plain`)."""
        known = self.form(renaming, dialect, indent, step, conversion, plain_only)
        if known is None:
            return None
        form, pick, _ = known
        return (form % pick(renaming.names)).encode()

    def form(self, renaming: Renaming, dialect: Dialect, indent: str, step: str,
             conversion: Converted, plain_only: bool = False
             ) -> tuple[str, Callable, bool] | None:
        """What :meth:`text` fills in: a ``%`` form, what picks the names for its ``%s``
        out of a renaming's names, and whether the text is plain (see :func:`_split`)."""
        key = (renaming.key, dialect, indent, step)
        known = self._texts.get(key, False)
        if known is False:
            known = self._texts[key] = _split(
                self.element(renaming, conversion.new, indent, step, None), renaming)
        if known is None or plain_only and not known[2]:
            return None
        return known

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
           ) -> tuple[str, Callable, bool] | None:
    """``element``'s text as a ``%`` form with a ``%s`` for each name that ``renaming`` keys,
    what picks those names out of a renaming's, and whether the text is plain; or None when
    the text does not give the element back."""
    text = etree.tostring(element, with_tail=False)
    if etree.tostring(etree.fromstring(text, safe_parser())) != text:
        return None
    index = {name.encode("ascii"): i for i, name in enumerate(renaming.names)}
    parts = NAME.split(text)  # what NAME matches goes; the names stay, between the others
    form = parts[0].decode("ascii").replace("%", "%%")
    slots = []
    for raw, after in zip(parts[1::2], parts[2::2], strict=True):
        slot = index.get(raw)
        name = raw.decode("ascii").replace("%", "%%") if slot is None else "%s"
        form += ' name="' + name + '"' + after.decode("ascii").replace("%", "%%")
        if slot is not None:
            slots.append(slot)
    pick = (lambda names: ()) if not slots else itemgetter(*slots) if len(slots) > 1 else (
        lambda names, slot=slots[0]: (names[slot],))
    return form, pick, plain(text)


def parse_children(pieces: list[bytes]) -> list[etree._Element]:
    """The elements (with their tails) of the text ``pieces`` join to."""
    return list(etree.fromstring(b"<x>" + b"".join(pieces) + b"</x>", safe_parser()))
