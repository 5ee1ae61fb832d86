"""Map elements to 1-based ``line:column`` in the file the user wrote.

lxml keeps ``sourceline`` but no column; the column is found in the line's text. For xacro
inputs the transmissions are read from the expansion, so an element is traced back to the
source by its transmission's name: literally, or through the ``${...}`` pattern of a macro body
(then the position is marked as "after xacro expansion").
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from functools import cached_property

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

    @cached_property
    def lines(self) -> list[str]:
        return self.source.data.decode("utf-8", errors="replace").splitlines()

    def column(self, line: int, tag: str, name: str | None = None) -> int:
        """Column of ``<tag`` (preferably with ``name="..."``) on ``line``; 1 if not found."""
        if not 1 <= line <= len(self.lines):
            return 1
        text = self.lines[line - 1]
        if name is not None:
            match = re.search(rf"<(?:\w+:)?{re.escape(tag)}\b[^>]*name\s*=\s*[\"']"
                              rf"{re.escape(name)}[\"']", text)
            if match:
                return match.start() + 1
        match = re.search(rf"<(?:\w+:)?{re.escape(tag)}\b", text)
        return match.start() + 1 if match else _first_text_column(text)

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


def _first_text_column(text: str) -> int:
    stripped = len(text) - len(text.lstrip())
    return stripped + 1
