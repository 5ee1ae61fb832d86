"""Where a finding in a xacro expansion belongs: the macro call in the file the user edits.

The rules read the expansion; :class:`~txtool.io.locate.Locator` finds, by aligning the
expansion with the file as written, the macro call (or include) that produced an element.
This module then finds the element's twin in the macro's body (in this file or in a file it
includes, read as xacro resolves includes: see :mod:`txtool.lint.fragments`) and decides:

* the twin's value comes from the call's arguments (``${reduction}``): the finding is at the
  call, at the argument when one alone is used, with the body's element as a related place,
  "in expansion of macro 'M' defined at FILE:LINE";
* the twin's value is written in the body, and the body is in this file: the finding is at
  the body's element, with the call as a related place, "expanded from the call of macro 'M'
  at FILE:LINE";
* the body is in another file: the finding is at the call (or include), the body's element
  related. That file, checked in the same run, reports such a mistake itself: see
  :func:`without_repeats`.
"""

from __future__ import annotations

import os
import re
from collections.abc import Iterator, Sequence
from functools import lru_cache

from lxml import etree

from txtool.io.locate import Locator, Position
from txtool.io.xmlio import (
    MAX_BYTES,
    SAFE_OPTIONS,
    InputError,
    XacroOptions,
    is_xacro_element,
    local,
    read_regular,
)
from txtool.lint.problem import Note, Problem

_EXPRESSION = re.compile(r"\$\{([^}]*)\}")
_IDENTIFIER = re.compile(r"[A-Za-z_]\w*")
_NOT_CALLS = frozenset({"include", "if", "unless", "call", "insert_block", "element",
                        "attribute"})
MAX_INCLUDED = 64  # files read to find macros: a robot's own tree, not a workspace


class Tracer:
    """Positions of a xacro expansion's elements with their call chain."""

    def __init__(self, locator: Locator, path: str, options: XacroOptions | None = None) -> None:
        self.locator = locator
        self.path = path
        self._options = options or XacroOptions()
        self._files: dict[str, tuple[etree._Element, Sequence[str]] | None] = {}
        self._definitions = self._find_definitions()
        self._pools: Pools = {}
        locator.add_macros({name: body for name, (_, body) in self._definitions.items()})

    def position(self, element: etree._Element) -> tuple[Position, tuple[Note, ...]] | None:
        """Where a finding at ``element`` goes and its related places; None: no call found
        (the locator's own position holds)."""
        producer, made = self.locator.producer(element)
        if producer is None or made is None or not is_xacro_element(producer):
            return None
        name = local(producer)
        if name in _NOT_CALLS:
            return None
        call = self._at(self.path, producer)
        found = self._definitions.get(name)
        if found is None:
            return call, ()
        where, body = found
        twin, nested = _twin(body, made, element, self._definitions, self._pools)
        if twin is None:
            note_at = self._at(where, body)
            return call, (Note(where, note_at.line, note_at.column,
                               self._defined(name, where, body)),)
        # The macros the twin stands in, innermost first, each noted where its expansion
        # holds the next: the twin, then each nested call.
        chain = [(name, where, body), *nested]
        places = [twin, *(self._call_in(outer, inner) for outer, inner in
                          zip(chain[-1:0:-1], chain[:0:-1], strict=True))]
        notes = []
        for (macro, file, definition), place in zip(chain[::-1], places, strict=True):
            at = self._at(file, place)
            notes.append(Note(file, at.line, at.column, self._defined(macro, file, definition)))
        used = _arguments(twin) & set(producer.attrib) if not nested else set()
        at_twin = self._at(nested[-1][1] if nested else where, twin)
        if not used and not nested and where == self.path:
            return at_twin, (Note(where, call.line, call.column,
                                  f"expanded from the call of macro '{name}' at "
                                  f"{_shown(where)}:{call.line}"),)
        if len(used) == 1:
            call = self._argument(producer, used.pop(), call)
        return call, tuple(notes)

    @staticmethod
    def _call_in(outer: tuple[str, str, etree._Element],
                 inner: tuple[str, str, etree._Element]) -> etree._Element:
        """The call of macro ``inner`` in the body of ``outer`` (else the body itself)."""
        name = inner[0]
        for child in outer[2].iter():
            if isinstance(child.tag, str) and is_xacro_element(child) and local(child) == name:
                return child
        return outer[2]

    def _defined(self, name: str, where: str, body: etree._Element) -> str:
        return f"in expansion of macro '{name}' defined at {_shown(where)}:{body.sourceline}"

    def _at(self, where: str, element: etree._Element) -> Position:
        line = element.sourceline or 1
        lines = self._lines(where)
        text = lines[line - 1] if 0 < line <= len(lines) else ""
        match = re.search(rf"<(?:[\w.-]+:)?{re.escape(local(element))}(?![\w.:-])", text)
        return Position(line, match.start() + 1 if match else 1)

    def _argument(self, call: etree._Element, name: str, at: Position) -> Position:
        """The position of the call's ``name="..."`` attribute (its start tag may span lines)."""
        lines = self._lines(self.path)
        pattern = re.compile(rf"(?<![\w.:-]){re.escape(name)}\s*=")
        for line in range(at.line, min(at.line + 20, len(lines)) + 1):
            text = lines[line - 1]
            start = at.column - 1 if line == at.line else 0
            match = pattern.search(text, start)
            if match:
                return Position(line, match.start() + 1)
            if ">" in text[start:]:
                break
        return at

    def _lines(self, where: str) -> Sequence[str]:
        if where == self.path:
            return self.locator.lines
        known = self._files.get(os.path.realpath(where))
        return known[1] if known else []

    def _find_definitions(self) -> dict[str, tuple[str, etree._Element]]:
        """Each macro's body by name, and the file it is written in: this file's first, then
        those of the files it includes (breadth first, as far as names can be resolved)."""
        found: dict[str, tuple[str, etree._Element]] = {}
        tree = self.locator.source.source_tree
        if tree is None:
            return found
        _macros_of(tree.getroot(), self.path, found)
        if self.path == "-" or not os.path.isfile(self.path):
            return found
        from txtool.lint.fragments import included_files

        for name in included_files(self.path, self._options, MAX_INCLUDED):
            root = self._read(os.path.realpath(name))
            if root is not None:
                _macros_of(root, _shown_path(name), found)
        return found

    def _read(self, key: str) -> etree._Element | None:
        if key not in self._files:
            try:
                data = read_regular(key, MAX_BYTES)
                root = etree.fromstring(data, etree.XMLParser(**SAFE_OPTIONS))
                from txtool.io.encodings import text_lines

                self._files[key] = (root, text_lines(data))
            except (InputError, etree.XMLSyntaxError, ValueError):
                self._files[key] = None
        known = self._files[key]
        return known[0] if known else None


def _macros_of(root: etree._Element, where: str,
               found: dict[str, tuple[str, etree._Element]]) -> None:
    for element in root.iter():
        if (isinstance(element.tag, str) and local(element) == "macro"
                and is_xacro_element(element)):
            found.setdefault(element.get("name", ""), (where, element))


Chain = list[tuple[str, str, etree._Element]]  # (macro, file, body) of nested calls
Entry = tuple[etree._Element, Chain]
# What an element makes where it stands, by tag, for each element and macro chain asked about:
# each body is walked once however many findings its expansions hold.
Pools = dict[tuple[etree._Element, tuple[str, ...]], dict[str, list[Entry]]]
MAX_PATTERNS = 64  # names matched as patterns per step: a bounded cost per finding


def _twin(body: etree._Element, made: etree._Element, element: etree._Element,
          macros: dict[str, tuple[str, etree._Element]],
          pools: Pools) -> tuple[etree._Element | None, Chain]:
    """The element of ``body`` (a macro) written for ``element``, which the call made as (or
    within) ``made``: ``made``'s twin among the body's children (or those of the macros the
    body calls), then down by tag and name; and the nested macros it was found in."""
    steps = [element, *element.iterancestors()]
    chain = steps[: steps.index(made) + 1][::-1] if made in steps else [element]
    parent: etree._Element = body
    best: etree._Element | None = None
    nested: Chain = []
    for step in chain:
        found = _named(_pool(parent, nested, macros, pools).get(local(step), []), step)
        if found is None:
            break
        best, nested = found
        parent = best
    return best, nested


def _pool(parent: etree._Element, nested: Chain,
          macros: dict[str, tuple[str, etree._Element]], pools: Pools) -> dict[str, list[Entry]]:
    key = (parent, tuple(name for name, _, _ in nested))
    known = pools.get(key)
    if known is None:
        known = pools[key] = {}
        for entry in _in_place(parent, macros, nested):
            known.setdefault(local(entry[0]), []).append(entry)
    return known


def _in_place(parent: etree._Element, macros: dict[str, tuple[str, etree._Element]],
              nested: Chain, depth: int = 0) -> Iterator[Entry]:
    """The elements ``parent`` makes where it stands: conditionals' children, and the bodies
    of the known macros it calls (to a depth of 8), each with the macros it is written in."""
    for child in parent:
        if not isinstance(child.tag, str):
            continue
        if not is_xacro_element(child):
            yield child, nested
        elif local(child) in ("if", "unless"):
            yield from _in_place(child, macros, nested, depth)
        elif local(child) in macros and depth < 8:
            file, body = macros[local(child)]
            yield from _in_place(body, macros, [*nested, (local(child), file, body)], depth + 1)


def _named(alike: Sequence[Entry], step: etree._Element) -> Entry | None:
    """The entry whose element is ``step`` written: its name, or a ``${...}`` pattern of it."""
    name = step.get("name")
    if name is None or len(alike) < 2:
        return alike[0] if alike else None
    patterns = 0
    for entry in alike:
        written = entry[0].get("name") or ""
        if written == name:
            return entry
        if "$" in written and patterns < MAX_PATTERNS:
            patterns += 1
            if _pattern(written).fullmatch(name):
                return entry
    return alike[0]


@lru_cache(maxsize=256)
def _pattern(text: str) -> re.Pattern[str]:
    parts = re.split(r"\$\{[^}]*\}|\$\([^)]*\)", text)
    return re.compile(".*".join(re.escape(p) for p in parts), re.DOTALL)


def _arguments(twin: etree._Element) -> set[str]:
    """The names the ``${...}`` expressions of the values a finding at ``twin`` is about
    use, the first of these that uses any: its text; its other attributes than ``name``;
    below a member (``<joint>``, ``<actuator>``), its children's texts and attributes (an
    interface, a reduction). A transmission's findings are about the element itself (its
    type, its members): its texts and attributes only. Names are left out: a macro names
    what it makes after its arguments, whatever the finding is about."""
    own_text = _names_in([twin.text or ""])
    if own_text:
        return own_text
    attributes = _names_in([value for key, value in twin.attrib.items() if key != "name"])
    if attributes or local(twin) == "transmission":
        return attributes
    return _names_in([text for node in twin.iterdescendants() if isinstance(node.tag, str)
                      for text in [node.text or "", *(value for key, value in node.attrib.items()
                                                      if key != "name")]])


def _names_in(texts: list[str]) -> set[str]:
    used: set[str] = set()
    for text in texts:
        for expression in _EXPRESSION.findall(text):
            used.update(_IDENTIFIER.findall(expression))
    return used


def _shown(path: str) -> str:
    return os.path.basename(path) if os.path.isabs(path) else path


def _shown_path(path: str) -> str:
    """An included file as paths are shown: relative to the working folder when below it."""
    relative = os.path.relpath(path)
    return path if relative.startswith("..") else relative


def without_repeats(problems: list[Problem]) -> list[Problem]:
    """One mistake, one finding: a finding whose related place is where another finding of
    the same rule stands (the included file, checked as well, reports its own mistake) is
    left out."""
    if not any(p.related for p in problems):
        return problems
    at = {(os.path.realpath(p.path), p.line, p.code) for p in problems}
    return [p for p in problems
            if not any((os.path.realpath(n.path), n.line, p.code) in at for n in p.related)]
