"""Transmissions that differ only in their names, converted once.

A large robot repeats a few transmissions thousands of times under other names. Reading,
translating and judging each one costs far more than the parse of its text, so a conversion
keys each ``<transmission>`` element by its serialization (:func:`serialization`) with every
``name="..."`` attribute value replaced by the index of its first appearance
(:class:`Renaming`), and converts the first element of a key in full. A later element of the
same key (a follower) takes that conversion with its own names put in, when the first said
nothing about it (no loss, note or warning, and nothing carried as written): equal keys make
equal conversions up to the names.

That holds because every step reads names only to tell them apart and to order them (the
same argument as :mod:`.nameless_shapes`): the key keeps which names are equal, the order of all of
them among each other and among :data:`.nameless_shapes.LITERAL_NAMES` (kept as written), and
everything else of the element as written. A step that reads outside the element would break
it, so an element inside a ``<ros2_control>`` (whose declarations the reader reads), with a
comment or processing instruction (a ``name="..."`` text there is not an attribute), or with
a name that the serialization escapes or that is not ASCII is not keyed, and is converted in
full.
"""

from __future__ import annotations

import re
from collections.abc import Hashable
from dataclasses import dataclass, field
from operator import itemgetter, lt
from typing import NamedTuple, Protocol

from lxml import etree

from txtool.model.core import Member, Transmission, replace
from txtool.transform.repeated.nameless_shapes import LITERAL_NAMES


class WrittenText(Protocol):
    """A transmission written as text, not built as an element
    (:class:`txtool.transform.repeated.block_text.Written`, which imports this module)."""

    def source(self) -> bytes: ...

# A name attribute (the serializer puts one space before each): inside a tag, as what follows
# it up to the tag's end holds no "<" or ">" (escaped in values and text); a text that reads
# ' name="..."' is followed by "<" first. An attribute value holds no '"' (escaped). NAME
# reads bytes (templates); the keys are made from text, which lxml writes faster.
NAME = re.compile(rb' name="([^"]*)"(?=[^<>]*>)')
_NAME = re.compile(NAME.pattern.decode("ascii"))
_KEPT = {name: name for name in LITERAL_NAMES}
_LITERAL_LIST = sorted(LITERAL_NAMES)


class Renaming(NamedTuple):
    """An element's key (its serialization up to the names) and its names, by index."""

    key: Hashable
    names: tuple[str, ...]


def renaming_of(element: etree._Element) -> Renaming | None:
    """The :class:`Renaming` of a ``<transmission>`` element, or None when it is not keyed."""
    parts = _parts(element)
    return None if parts is None else _renaming(parts)


def serialization(element: etree._Element) -> str:
    """What an element is keyed by: lxml's serialization of it, without its tail."""
    return etree.tostring(element, with_tail=False, encoding="unicode")


def _parts(element: etree._Element) -> list[str] | None:
    """The serialization of ``element`` cut at its names (the names are at the odd
    indices), or None when it holds a comment or processing instruction."""
    data = serialization(element)
    return None if _unkeyed(data) else _NAME.split(data)


def _unkeyed(data: str) -> bool:
    """Whether a serialization holds a comment, CDATA section or processing instruction
    (the one-character searches are the faster)."""
    return "!" in data and "<!" in data or "?" in data and "<?" in data


def _unordered(names: str) -> bool:
    """Whether names (joined) may sort otherwise than as written: escaped (``&amp;``), or
    not ASCII (left out as when the keys were ASCII bytes, with references for the rest)."""
    return "&" in names or not names.isascii()


def _renaming(parts: list[str]) -> Renaming | None:
    raws = parts[1::2]
    distinct = dict.fromkeys(raws)  # the names that are not literal, in order of appearance
    if not LITERAL_NAMES.isdisjoint(distinct):
        for literal in LITERAL_NAMES:
            distinct.pop(literal, None)
    if _unordered("".join(distinct)):
        return None
    # Equal names, and the order of all names among each other and the literal ones (kept).
    index = dict(zip(distinct, range(len(distinct)), strict=True))
    index.update(_KEPT)
    names = tuple(map(index.__getitem__, raws))
    everything = [*distinct, *LITERAL_NAMES]
    everything.sort()
    order = tuple(map(index.__getitem__, everything))
    return Renaming((tuple(parts[0::2]), names, order), tuple(distinct))


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
        # What placing a follower reads of its conversion, without building it.
        self.dialect = translated.dialect
        self._name = self._translated.name
        # Each joint of the conversion: the index of its name (None: kept), the name, and
        # its command and state interfaces.
        self.joint_plan = [(i, m.name, (m.interfaces, m.state_interfaces))
                           for m, i in self._translated.joints]
        self.skeleton, pattern, _ = renaming.key  # type: ignore[misc]
        self.distinct = pattern == tuple(range(len(pattern)))  # no name twice, none literal
        # The names and the literal ones in the order they sort: indices into the names
        # followed by the literal names.
        every = [*renaming.names, *_LITERAL_LIST]
        self._order = itemgetter(*sorted(range(len(every)), key=every.__getitem__))

    def match(self, raws: list[str], data: str) -> tuple[str, ...] | None:
        """The names of an element whose :func:`renaming_of` has this record's key, from its
        names as written (``raws``), its key's skeleton being this record's; or None when its
        key differs (or it has none). Only for a :attr:`distinct` record: then the key says
        that the names are distinct and not literal, the order they sort in, and where each
        literal name sorts among them. ``data``: the element's serialization."""
        # In the record's order, the names and the literal ones strictly increase: so they
        # are distinct, none is literal, and they sort as the record's.
        ordered = self._order(raws + _LITERAL_LIST)
        if not all(map(lt, ordered, ordered[1:])) or (
                "&" in data or not data.isascii()) and _unordered("".join(raws)):
            return None
        return tuple(raws)

    def name_for(self, names: tuple[str, ...]) -> str:
        """The name of ``translation_for(names)``."""
        return self.translated.name if self._name is None else names[self._name]

    def joints_for(self, names: tuple[str, ...]
                   ) -> list[tuple[str, tuple[str, ...], tuple[str, ...]]]:
        """The name, command and state interfaces of each joint of ``translation_for(names)``.
        """
        return [(name if i is None else names[i], *interfaces)
                for i, name, interfaces in self.joint_plan]

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
    built: etree._Element | WrittenText | None = None  # then what the placer built (or wrote)

    def translated(self) -> Transmission:
        return self.record.translation_for(self.names)

    def renaming(self) -> Renaming:
        return Renaming(self.record.renaming.key, self.names)

    def transmission(self) -> Transmission:
        """The original transmission, as reading the element gives it."""
        return self.record.original_for(self.names)


@dataclass
class Memo:
    """Records by key; a key whose first conversion said something is marked spoken."""

    records: dict[Hashable, Record | None] = field(default_factory=dict)
    _distinct: dict[tuple[str, ...], list[Record]] = field(default_factory=dict)

    def keyed(self, element: etree._Element) -> Follower | Renaming | None:
        """``element`` as a follower of the record of its key (:func:`renaming_of`) when
        there is one (its first said nothing), else its renaming (None: it has no key). A
        record whose names are distinct is matched without the key being made."""
        data = serialization(element)
        parts = _NAME.split(data)
        # A record's skeleton holds no "<!" or "<?", nor then does an element of the same
        # skeleton: its names, attribute values, hold no "<" (escaped).
        for record in self._distinct.get(tuple(parts[0::2]), ()):
            names = record.match(parts[1::2], data)
            if names is not None:
                return Follower(record, names, record.name_for(names), element)
        if _unkeyed(data):
            return None
        renaming = _renaming(parts)
        if renaming is None:
            return None
        record = self.records.get(renaming.key)
        return renaming if record is None else Follower(
            record, renaming.names, record.name_for(renaming.names), element)

    def learn(self, renaming: Renaming | None, original: Transmission, translated: Transmission,
              clean: bool) -> Record | None:
        """Keep the first conversion of a key, when it said nothing."""
        if renaming is None or renaming.key in self.records:
            return None
        record = Record(renaming, original, translated) if clean else None
        self.records[renaming.key] = record
        if record is not None and record.distinct:
            self._distinct.setdefault(record.skeleton, []).append(record)
        return record
