"""Map elements to 1-based ``line:column`` in the file the user wrote.

lxml keeps ``sourceline`` but no column; the column is found in the line's text. For xacro
inputs the transmissions are read from the expansion, so an element is traced back to the
source by its transmission's name: literally, or through the ``${...}`` pattern of a macro body
(then the position is marked as "after xacro expansion").
"""

from __future__ import annotations

import re
from collections.abc import Iterator
from dataclasses import dataclass
from functools import cached_property, lru_cache

from lxml import etree

from txtool.io.encodings import Lines, text_lines
from txtool.io.xmlio import Source, is_xacro_element, local

_RECENT = 1024


@dataclass(frozen=True, slots=True)
class Position:
    line: int
    column: int
    expanded: bool = False  # True when only traced through a xacro macro


class Locator:
    def __init__(self, source: Source) -> None:
        self.source = source
        # What the last lines and elements asked about hold and where they are: rules report
        # in document order, and several at the same element or on the same line, so a few
        # recent ones answer nearly every question (a document written on one line asks about
        # one line). Kept for the last _RECENT only, not for every finding of a large document;
        # the keys keep the lxml proxies (and so their identities) alive.
        self._tag_index: dict[tuple[int, str], tuple[list[int], dict[str, int]]] = {}
        self._positions: dict[etree._Element, Position] = {}

    @cached_property
    def lines(self) -> Lines:
        return text_lines(self.source.data)

    def column(self, line: int, tag: str, name: str | None = None) -> int:
        """Column of ``<tag`` (preferably with ``name="..."``) on ``line``; 1 if not found."""
        lines = self.lines
        if not 1 <= line <= len(lines):
            return 1
        starts, by_name = self._tags_on(line, tag)
        if name is not None and name in by_name:
            return by_name[name] + 1
        return starts[0] + 1 if starts else _first_text_column(lines[line - 1])

    def _tags_on(self, line: int, tag: str) -> tuple[list[int], dict[str, int]]:
        """Where ``<tag`` starts on ``line``, and the first start per ``name`` attribute: each
        line is scanned once per tag, so even a document written on one line costs linear time."""
        key = (line, tag)
        found = self._tag_index.get(key)
        if found is None:
            text = self.lines[line - 1]
            starts = [match.start() for match in _tag_pattern(tag).finditer(text)]
            by_name: dict[str, int] = {}
            for start in starts:
                end = text.find(">", start)
                attribute = _NAME_ATTRIBUTE.search(text, start, end if end >= 0 else len(text))
                if attribute is not None:
                    by_name.setdefault(attribute.group(2), start)
            if len(self._tag_index) >= _RECENT:
                self._tag_index.clear()
            found = self._tag_index[key] = (starts, by_name)
        return found

    def position(self, element: etree._Element) -> Position:
        """Where ``element`` (of :attr:`Source.tree`) is written."""
        known = self._positions.get(element)
        if known is None:
            if len(self._positions) >= _RECENT:
                self._positions.clear()
            known = self._positions[element] = self._position(element)
        return known

    def _position(self, element: etree._Element) -> Position:
        if not self.source.expanded:
            line = element.sourceline or 1
            return Position(line, self.column(line, local(element), element.get("name")))
        return self._traced(element)

    def _traced(self, element: etree._Element) -> Position:
        twin, exact = self._twin(element)
        if twin is None:
            twin = self._producer(element)
            if twin is None:
                return Position(1, 1, expanded=True)
            exact = False
        line = twin.sourceline or 1
        return Position(line, self.column(line, local(twin), twin.get("name")), not exact)

    def _twin(self, element: etree._Element) -> tuple[etree._Element | None, bool]:
        """The source element that produced ``element``, and whether the match was literal."""
        chain = _chain_to_transmission(element)
        if not chain:
            return None, False
        transmission = chain[0]
        name = transmission.get("name")
        literal = self._transmissions_by_name.get(name) if name is not None else None
        if literal is not None:
            best, exact = literal, True
        else:
            best, exact = _match_named(self._source_transmissions, name)
        if best is None:
            return None, False
        for step in chain[1:]:
            pool = [child for child in best.iter() if local(child) == local(step)]
            if step.get("name") is not None:
                found, literal = _match_named(pool, step.get("name"))
                exact = exact and literal
            else:
                found = pool[0] if pool else None
            if found is None:
                break
            best = found
        return best, exact

    def _producer(self, element: etree._Element) -> etree._Element | None:
        """The source element that produced ``element``: a macro call or include (or a literal
        element whose name xacro computed), by aligning each level of the
        expansion with the file as written."""
        return self.producer(element)[0]

    def producer(
        self, element: etree._Element
    ) -> tuple[etree._Element | None, etree._Element | None]:
        """The source element that produced ``element`` (see :meth:`_producer`), and when that
        is a xacro element (a macro call, an include), the element of the expansion it made
        that holds ``element`` (``element`` itself, or an ancestor)."""
        tree = self.source.source_tree
        if tree is None:
            return None, None
        chain = [element, *element.iterancestors()][::-1]
        written = tree.getroot()
        for step in chain[1:]:
            made = self._alignment(written, step.getparent()).get(step)
            if made is None or is_xacro_element(made):
                return made, step if made is not None else None
            written = made
        return written, None

    def add_macros(self, macros: dict[str, etree._Element]) -> None:
        """Macros defined in other files (included ones), so that the calls between two
        literal elements share what they produced by what each macro's body holds."""
        for name, body in macros.items():
            self._macros.setdefault(name, body)

    def _alignment(
        self, written: etree._Element, produced: etree._Element
    ) -> dict[etree._Element, etree._Element]:
        key = (written, produced)  # the elements themselves keep their proxies alive
        if key not in self._alignments:
            self._alignments[key] = _align(written, produced, self._macros)
        return self._alignments[key]

    @cached_property
    def _alignments(self) -> dict[tuple[etree._Element, etree._Element], dict]:
        return {}

    @cached_property
    def _macros(self) -> dict[str, etree._Element]:
        return {
            e.get("name", ""): e
            for e in self._all_source
            if local(e) == "macro" and is_xacro_element(e)
        }

    @cached_property
    def _all_source(self) -> list[etree._Element]:
        tree = self.source.source_tree
        return list(tree.getroot().iter()) if tree is not None else []

    @cached_property
    def _source_transmissions(self) -> list[etree._Element]:
        return [e for e in self._all_source if local(e) == "transmission"]

    @cached_property
    def _transmissions_by_name(self) -> dict[str, etree._Element]:
        by_name: dict[str, etree._Element] = {}
        for element in self._source_transmissions:
            by_name.setdefault(element.get("name", ""), element)
        return by_name


# xacro elements that produce no element where they stand.
_SILENT = frozenset({"property", "arg", "macro"})


def _align(
    written: etree._Element, produced: etree._Element, macros: dict[str, etree._Element]
) -> dict[etree._Element, etree._Element]:
    """Map each child of ``produced`` (expansion) to the child of ``written`` (source) that
    made it: its literal twin, else the macro call or include before that twin."""
    made = [c for c in produced if isinstance(c.tag, str)]
    result: dict[etree._Element, etree._Element] = {}
    start = 0
    pending: list[etree._Element] = []
    for child in _in_place(written):
        if is_xacro_element(child):
            if local(child) not in _SILENT:
                pending.append(child)
            continue
        twin = _next_twin(made, start, child)
        if twin is None:
            continue
        _attribute(made[start:twin], pending, macros, result)
        result[made[twin]] = child
        start, pending = twin + 1, []
    _attribute(made[start:], pending, macros, result)
    return result


def _in_place(written: etree._Element) -> Iterator[etree._Element]:
    """The element children, with those of conditionals in their place (which is where xacro
    puts them when the condition holds)."""
    for child in written:
        if not isinstance(child.tag, str):
            continue
        if is_xacro_element(child) and local(child) in ("if", "unless"):
            yield from _in_place(child)
        else:
            yield child


def _next_twin(made: list[etree._Element], start: int, child: etree._Element) -> int | None:
    name = child.get("name")
    for index in range(start, len(made)):
        candidate = made[index]
        if local(candidate) != local(child) or not _same_attributes(child, candidate):
            continue
        if name is None or _match_named([child], candidate.get("name"))[0] is not None:
            return index
    return None


def _same_attributes(written: etree._Element, produced: etree._Element) -> bool:
    """Whether ``produced`` may be ``written`` expanded: the same attributes, those written
    without an expression with the same value. A literal ``<gazebo>`` is not the ``<gazebo
    reference="...">`` a macro call made before it."""
    if set(written.attrib) != set(produced.attrib):
        return False
    return all("$" in value or produced.get(key) == value for key, value in written.items())


def _attribute(
    elements: list[etree._Element],
    producers: list[etree._Element],
    macros: dict[str, etree._Element],
    result: dict[etree._Element, etree._Element],
) -> None:
    """Share produced elements among the xacro calls that stand between two literal twins, in
    order: a call whose macro is known produces at most what its body holds."""
    if not producers:
        return
    expected = [_expected(p, macros) for p in producers]
    used: list[dict[str, int]] = [{} for _ in producers]
    cursor = 0
    for element in elements:
        tag = local(element)
        choice = next(
            (k for k in range(cursor, len(producers))
             if expected[k] is not None and used[k].get(tag, 0) < expected[k].get(tag, 0)),
            None,
        )
        if choice is None:
            unknown = [k for k in range(cursor, len(producers)) if expected[k] is None]
            named = sorted((k for k in unknown if _mentions(producers[k], element)),
                           key=lambda k: -_mentions(producers[k], element))
            calls = [k for k in unknown if local(producers[k]) != "include"]
            choice = (named or calls or unknown or [len(producers) - 1])[0]
        used[choice][tag] = used[choice].get(tag, 0) + 1
        cursor = choice
        result[element] = producers[choice]


def _mentions(call: etree._Element, element: etree._Element) -> int:
    """Length of the longest argument of ``call`` found in ``element``'s name (0: none): macros
    usually build names from their arguments (``prefix="left_"`` makes ``left_wheel_trans``)."""
    name = element.get("name") or ""
    # (``@*``: lxml's ``attrib.values()`` is quadratic in the number of attributes)
    return max((len(value) for value in call.xpath("@*") if value and value in name),
               default=0)


def _expected(producer: etree._Element, macros: dict[str, etree._Element],
              depth: int = 0) -> dict[str, int] | None:
    """How many elements of each tag a call produces, when the file tells: its macro's body,
    nested calls of known macros counted in (to a depth of 8)."""
    name = local(producer)
    body = macros.get(name) if name not in ("include", "call", "insert_block") else None
    if body is None or depth > 8:
        return None
    counts: dict[str, int] = {}
    for child in body:
        if not isinstance(child.tag, str):
            continue
        if is_xacro_element(child):
            if local(child) in _SILENT:
                continue
            nested = _expected(child, macros, depth + 1)
            if nested is None:
                return None  # conditionals, blocks, unknown macros: unknown
            for tag, count in nested.items():
                counts[tag] = counts.get(tag, 0) + count
            continue
        counts[local(child)] = counts.get(local(child), 0) + 1
    return counts


def _chain_to_transmission(element: etree._Element) -> list[etree._Element]:
    chain = [element]
    while local(chain[0]) != "transmission":
        parent = chain[0].getparent()
        if parent is None:
            return []
        chain.insert(0, parent)
    return chain


def _match_named(
    candidates: list[etree._Element], name: str | None
) -> tuple[etree._Element | None, bool]:
    if name is None:
        return (candidates[0], False) if candidates else (None, False)
    for candidate in candidates:
        if candidate.get("name") == name:
            return candidate, True
    for candidate in candidates:
        pattern = candidate.get("name")
        if pattern and "$" in pattern and _pattern(pattern).fullmatch(name):
            return candidate, False
    return None, False


def _pattern(text: str) -> re.Pattern[str]:
    parts = re.split(r"\$\{[^}]*\}|\$\([^)]*\)", text)
    return re.compile(".*".join(re.escape(p) for p in parts), re.DOTALL)


_NAME_ATTRIBUTE = re.compile(r"\bname\s*=\s*([\"'])(.*?)\1")


@lru_cache(maxsize=64)
def _tag_pattern(tag: str) -> re.Pattern[str]:
    return re.compile(rf"<(?:[\w.-]+:)?{re.escape(tag)}(?![\w.:-])")


def _first_text_column(text: str) -> int:
    stripped = len(text) - len(text.lstrip())
    return stripped + 1
