"""Map elements to 1-based ``line:column`` in the file the user wrote.

lxml keeps ``sourceline`` but no column; the column is found in the line's text. For xacro
inputs the transmissions are read from the expansion, so an element is traced back to the
source by its transmission's name: literally, or through the ``${...}`` pattern of a macro body
(then the position is marked as "after xacro expansion").
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from functools import cached_property, lru_cache

from lxml import etree

from txtool.robot import local
from txtool.xmlio import Source


@dataclass(frozen=True)
class Position:
    line: int
    column: int
    expanded: bool = False  # True when only traced through a xacro macro


class Locator:
    def __init__(self, source: Source) -> None:
        self.source = source

    @property
    def lines(self) -> list[str]:
        return text_lines(self.source.data)

    def column(self, line: int, tag: str, name: str | None = None) -> int:
        """Column of ``<tag`` (preferably with ``name="..."``) on ``line``; 1 if not found."""
        lines = self.lines
        if not 1 <= line <= len(lines):
            return 1
        text = lines[line - 1]
        starts = [match.start() for match in _tag_pattern(tag).finditer(text)]
        if name is not None:
            for start in starts:
                end = text.find(">", start)
                attribute = _NAME_ATTRIBUTE.search(text, start, end if end >= 0 else len(text))
                if attribute is not None and attribute.group(2) == name:
                    return start + 1
        return starts[0] + 1 if starts else _first_text_column(text)

    def position(self, element: etree._Element) -> Position:
        """Where ``element`` (of :attr:`Source.tree`) is written."""
        if not self.source.expanded:
            line = element.sourceline or 1
            return Position(line, self.column(line, local(element), element.get("name")))
        return self._traced(element)

    def _traced(self, element: etree._Element) -> Position:
        twin, exact = self._twin(element)
        if twin is None:
            return Position(1, 1, expanded=True)
        line = twin.sourceline or 1
        return Position(line, self.column(line, local(twin), twin.get("name")), not exact)

    def _twin(self, element: etree._Element) -> tuple[etree._Element | None, bool]:
        """The source element that produced ``element``, and whether the match was literal."""
        chain = _chain_to_transmission(element)
        if not chain:
            return None, False
        transmission = chain[0]
        candidates = self._source_transmissions()
        best, exact = _match_named(candidates, transmission.get("name"))
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

    @cached_property
    def _all_source(self) -> list[etree._Element]:
        tree = self.source.source_tree
        return list(tree.getroot().iter()) if tree is not None else []

    def _source_transmissions(self) -> list[etree._Element]:
        return [e for e in self._all_source if local(e) == "transmission"]


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


@lru_cache(maxsize=2)
def text_lines(data: bytes) -> list[str]:
    """The lines of a document (shared by everything that places findings in it)."""
    return data.decode("utf-8", errors="replace").splitlines()


_NAME_ATTRIBUTE = re.compile(r"\bname\s*=\s*([\"'])(.*?)\1")


@lru_cache(maxsize=64)
def _tag_pattern(tag: str) -> re.Pattern[str]:
    return re.compile(rf"<(?:[\w.-]+:)?{re.escape(tag)}(?![\w.:-])")


def _first_text_column(text: str) -> int:
    stripped = len(text) - len(text.lstrip())
    return stripped + 1
