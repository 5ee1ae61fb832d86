"""Transmissions that differ only in their names, converted once.

A large robot repeats a few transmissions thousands of times under other names. Reading,
translating and judging each one costs far more than the parse of its text, so a conversion
keys each ``<transmission>`` element by its serialization with every ``name="..."`` attribute
value replaced by the index of its first appearance (:class:`Renaming`), and converts the
first element of a key in full. A later element of the same key (a follower) takes that
conversion with its own names put in, when the first said nothing about it (no loss, note or
warning, and nothing carried as written): equal keys make equal conversions up to the names.

That holds because every step reads names only to tell them apart and to order them (the
same argument as :mod:`.shapes`): the key keeps which names are equal, the order of all of
them among each other and among :data:`.shapes.LITERAL_NAMES` (kept as written), and
everything else of the element as written. A step that reads outside the element would break
it, so an element inside a ``<ros2_control>`` (whose declarations the reader reads), with a
comment or processing instruction (a ``name="..."`` text there is not an attribute), or with
a name that the serialization escapes is not keyed, and is converted in full.
"""

from __future__ import annotations

import re
from collections.abc import Hashable
from dataclasses import dataclass, field
from typing import NamedTuple

from lxml import etree

from txtool.model.core import Member, Transmission, replace
from txtool.transform.shapes import LITERAL_NAMES

# A name attribute (the serializer puts one space before each): inside a tag, as what follows
# it up to the tag's end holds no "<" or ">" (escaped in values and text); a text that reads
# ' name="..."' is followed by "<" first. An attribute value holds no '"' (escaped).
NAME = re.compile(rb' name="([^"]*)"(?=[^<>]*>)')
_LITERALS = frozenset(name.encode("ascii") for name in LITERAL_NAMES)


class Renaming(NamedTuple):
    """An element's key (its serialization up to the names) and its names, by index."""

    key: Hashable
    names: tuple[str, ...]


def renaming_of(element: etree._Element) -> Renaming | None:
    """The :class:`Renaming` of a ``<transmission>`` element, or None when it is not keyed."""
    data = etree.tostring(element, with_tail=False)  # ASCII: other characters as references
    if b"<!" in data or b"<?" in data:
        return None
    parts = NAME.split(data)
    raws = parts[1::2]
    index = {raw: None for raw in raws if raw not in _LITERALS}  # in order of appearance
    for position, raw in enumerate(index):
        index[raw] = position
    if b"&" in b"".join(index):
        return None  # an escaped name: its order is not the order of its bytes
    # Equal names, and the order of all names among each other and the literal ones.
    names = tuple([index.get(raw, raw) for raw in raws])
    order = tuple([index.get(raw, raw) for raw in sorted(index.keys() | _LITERALS)])
    return Renaming((tuple(parts[0::2]), names, order),
                    tuple([raw.decode("ascii") for raw in index]))


class Renamer:
    """Puts other names into one transmission of a key: each of its names is the index of a
    name of the key, or kept (a literal name), worked out once."""

    def __init__(self, t: Transmission, names: tuple[str, ...]) -> None:
        index = {name: i for i, name in enumerate(names)}
        self.t = t
        self.name = index.get(t.name)
        self.joints = [(m, index.get(m.name)) for m in t.joints]
        self.actuators = [(m, index.get(m.name)) for m in t.actuators]
        self.parameters = [(n, index.get(n), value) for n, value in t.parameters]

    def __call__(self, names: tuple[str, ...]) -> Transmission:
        """The transmission with ``names`` (another element's of the key) put in."""
        def member(m: Member, i: int | None) -> Member:
            return m if i is None else replace(m, name=names[i])

        return replace(
            self.t, name=self.t.name if self.name is None else names[self.name],
            joints=tuple([member(m, i) for m, i in self.joints]),
            actuators=tuple([member(m, i) for m, i in self.actuators]),
            parameters=tuple([(n if i is None else names[i], value)
                              for n, i, value in self.parameters]),
        )


class Record:
    """The full conversion of the first element of a key."""

    def __init__(self, renaming: Renaming, original: Transmission, translated: Transmission
                 ) -> None:
        self.renaming = renaming
        self.original = original
        self.translated = translated
        self.verdict: Hashable | None = None  # the check's key for the first judged alone
        self._translated = Renamer(translated, renaming.names)
        self._original: Renamer | None = None

    def translation_for(self, names: tuple[str, ...]) -> Transmission:
        return self._translated(names)

    def original_for(self, names: tuple[str, ...]) -> Transmission:
        if self._original is None:
            self._original = Renamer(self.original, self.renaming.names)
        return self._original(names)


@dataclass(slots=True)
class Follower:
    """A transmission converted as its :class:`Record` up to the names."""

    record: Record
    names: tuple[str, ...]  # its own, by the index of the key's
    name: str = ""
    element: etree._Element | None = None  # the old element, until it is placed
    built: etree._Element | None = None  # then what the placer built for it

    def translated(self) -> Transmission:
        return self.record.translation_for(self.names)

    def transmission(self) -> Transmission:
        """The original transmission, as reading the element gives it."""
        return self.record.original_for(self.names)


@dataclass
class Memo:
    """Records by key; a key whose first conversion said something is marked spoken."""

    records: dict[Hashable, Record | None] = field(default_factory=dict)

    def follow(self, renaming: Renaming | None) -> Follower | None:
        if renaming is None:
            return None
        record = self.records.get(renaming.key)
        return None if record is None else Follower(record, renaming.names)

    def learn(self, renaming: Renaming | None, original: Transmission, translated: Transmission,
              clean: bool) -> Record | None:
        """Keep the first conversion of a key, when it said nothing."""
        if renaming is None or renaming.key in self.records:
            return None
        record = Record(renaming, original, translated) if clean else None
        self.records[renaming.key] = record
        return record
