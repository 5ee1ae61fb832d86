"""Read every ``<transmission>`` of a document into the canonical model.

The dialect is detected per transmission, so one file may mix them:

* ``ros1``: outside ``<ros2_control>`` with ``<type>`` (or the legacy ``type=`` attribute),
  ``<hardwareInterface>``, ``<mechanicalReduction>``, ``<role>`` elements.
* ``ros2-p1``: inside ``<ros2_control>`` (or carrying ``<plugin>``), roles as ``<role>`` elements.
* ``ros2-p2``: inside ``<ros2_control>``, roles as ``role=`` attributes (what ros2_control parses).

Numbers are parsed the way the detected loader parses them (see :mod:`txtool.model.numbers`).
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator
from dataclasses import dataclass, field
from functools import lru_cache
from typing import TYPE_CHECKING, Any

from lxml import etree

from txtool.io.xmlio import Source
from txtool.model.core import (
    Dialect,
    Location,
    Member,
    Number,
    Transmission,
    builder,
    kind_of,
    replace,
)
from txtool.model.numbers import C_SPACE, parse_ros1, parse_ros2
from txtool.model.robot import ancestor, child_index, children

if TYPE_CHECKING:
    from txtool.io.locate import Locator


# The model's constructors, without a frozen dataclass's per-field __setattr__ (see builder).
_new_transmission = builder(Transmission)
_new_member = builder(Member)
_new_number = builder(Number)


_Interfaces = tuple[tuple[str, ...], tuple[str, ...]]  # command and state interface names
_UNDECLARED: _Interfaces = ((), ())


class Declarations:
    """What the reader asks of a ``<ros2_control>``: its name and the interfaces a joint is
    declared with (the first of a repeated name, as :func:`~txtool.model.robot.component_of`
    keeps it), each joint read when it is asked for: a block generated for thousands of
    transmissions is read back one member at a time."""

    def __init__(self, element: etree._Element) -> None:
        self.name = element.get("name", "")
        self._element = element
        self._index: dict[str, etree._Element] | None = None
        self._read: dict[str, _Interfaces] = {}

    def interfaces(self, name: str) -> _Interfaces:
        """The command and state interfaces of joint ``name``; none where it is undeclared."""
        read = self._read.get(name)
        if read is not None:
            return read
        if self._index is None:
            self._index = {}
            for declared in children(self._element, "joint"):
                # the parser strips names (component_parser.cpp get_attribute_value)
                self._index.setdefault(declared.get("name", "").strip(C_SPACE), declared)
        element = self._index.get(name)
        self._read[name] = read = _UNDECLARED if element is None else _declared(element)
        return read


def _declared(element: etree._Element) -> _Interfaces:
    commands, states = [], []
    for child in element[:]:  # one pass: a declaration has a few interfaces and nothing else
        tag = child.tag
        if tag.__class__ is str:  # not a comment or processing instruction
            tag = tag.rpartition("}")[2]
            if tag == "command_interface":
                commands.append(child.get("name", "").strip(C_SPACE))
            elif tag == "state_interface":
                states.append(child.get("name", "").strip(C_SPACE))
    return tuple(commands), tuple(states)


@dataclass(frozen=True)
class Found:
    """A transmission and the element it was read from (in ``Source.tree``).

    ``memo`` keeps answers that lint rules share (see :mod:`txtool.lint.rule_helpers`).
    """

    transmission: Transmission
    element: etree._Element
    memo: dict[str, Any] = field(default_factory=dict, compare=False, repr=False)


def read_source(
    source: Source,
    *,
    locate: bool = True,
    candidates: Iterable[etree._Element] | None = None,
) -> list[Found]:
    """All transmissions of ``source`` in document order.

    With ``locate=False`` the model carries no locations (the linter places its findings from
    the elements, and finding columns for every member would cost more than the rules).
    ``candidates`` are the tree's ``<transmission>`` elements in document order when the
    caller has walked the tree already.
    """
    locator = None
    if locate:
        from txtool.io.locate import Locator

        locator = Locator(source)
    components: dict[etree._Element, Declarations] = {}  # each read once, however many members
    return [
        Found(read_transmission(element, locator, components), element)
        for element in transmission_elements(source.root, candidates)
    ]


def read_each(root: etree._Element) -> Iterator[Transmission]:
    """The transmissions of ``root`` in document order, each read as it comes (the document
    is not held read whole: a ``<ros2_control>``'s declarations are let go when its
    transmissions, which come one after another, are read)."""
    components: dict[etree._Element, Declarations] = {}
    for element in transmission_elements(root):
        component = enclosing_component(element)
        if component not in components:
            components.clear()
        yield read_transmission(element, None, components)


def transmission_elements(
    root: etree._Element, candidates: Iterable[etree._Element] | None = None
) -> list[etree._Element]:
    """``<transmission>`` elements that are transmissions (not nested in another one), of
    ``root`` or among its already collected ``candidates``."""
    return _found(root, candidates)[0]


def _found(root: etree._Element, candidates: Iterable[etree._Element] | None
           ) -> tuple[list[etree._Element], bool]:
    """:func:`transmission_elements`, and whether they are all the root's own
    ``<transmission>`` children: told by identity in one comparison, with no parent looked
    up for each (the common case)."""
    found = []
    # A child of the document's root element (the most common place) has only it above.
    top = root if root.getparent() is None else None
    tag = root.tag
    in_root = tag == "transmission" or tag.endswith("}transmission")
    if candidates is None and top is not None and not in_root:
        candidates = list(root.iter("{*}transmission"))
        if candidates == root.findall("{*}transmission"):
            return candidates, True
    nested: dict[etree._Element, bool] = {}  # by parent: transmissions share a few parents
    for element in root.iter("{*}transmission") if candidates is None else candidates:
        parent = element.getparent()
        if parent is top:
            if not in_root:
                found.append(element)
            continue
        inside = nested.get(parent)
        if inside is None:
            inside = nested[parent] = _is_or_inside_transmission(parent)
        if not inside:
            found.append(element)
    return found, False


def _is_or_inside_transmission(element: etree._Element | None) -> bool:
    if element is None:
        return False
    tag = element.tag
    return (tag == "transmission" or tag.endswith("}transmission")
            or ancestor(element, "transmission") is not None)


def enclosing_component(element: etree._Element) -> etree._Element | None:
    """The nearest ``<ros2_control>`` ancestor, in any namespace."""
    return ancestor(element, "ros2_control")


def detect_dialect(element: etree._Element,
                   kids: dict[str, list[etree._Element]] | None = None) -> Dialect:
    """The dialect of a ``<transmission>``; ``kids``: its :func:`child_index`, when known."""
    if kids is None:
        kids = child_index(element)
    members = (*kids.get("joint", ()), *kids.get("actuator", ()))
    for member in members:
        if member.get("role") is not None:
            return "ros2-p2"
    if "plugin" not in kids and enclosing_component(element) is None:
        return "ros1"
    for member in members:
        if children(member, "role"):
            return "ros2-p1"
    return "ros2-p2"


def read_transmission(
    element: etree._Element,
    locator: Locator | None,
    components: dict[etree._Element, Declarations] | None = None,
) -> Transmission:
    kids = child_index(element)  # one index for detecting and reading
    dialect = detect_dialect(element, kids)
    if dialect == "ros1":
        return _read_ros1(element, locator, kids)
    return _read_ros2(element, locator, dialect, {} if components is None else components, kids)


def text_of(element: etree._Element | None) -> str | None:
    if element is None:
        return None
    return element.text if element.text is not None else ""


_XML_SPACE = " \t\n\r"


def get_text(element: etree._Element) -> str | None:
    """tinyxml2's ``XMLElement::GetText()`` (9.0 and later, as ros2_control's parser calls it):
    the first text node after any leading comments, None where there is none.

    tinyxml2 keeps no text node that is only whitespace, so ``<a> <!--c--> 5 </a>`` gives
    ``" 5 "`` and ``<a>  </a>`` gives None; an element or a processing instruction before the
    text gives None, and a comment or CDATA section after it ends it (tinyxml2.cpp
    ``XMLElement::GetText``, ``XMLDocument::Identify``). An element without children is read
    from its ``text`` (a CDATA section inside such a text is not told apart).
    """
    if not len(element):
        text = element.text
        return text if text is not None and text.strip(_XML_SPACE) else None
    for node in _NODES(element):
        if isinstance(node, str):  # text or CDATA
            if node.strip(_XML_SPACE):
                return str(node)
        elif not isinstance(node, etree._Comment):
            return None
    return None


_NODES = etree.XPath("node()")


def first_child_text(element: etree._Element, name: str) -> str | None:
    """Text of the first ``name`` child (``""`` when it is empty), or None."""
    found = children(element, name)
    return text_of(found[0]) if found else None


def _first_text(kids: dict[str, list[etree._Element]], name: str) -> str | None:
    """:func:`first_child_text` over a :func:`~txtool.model.robot.child_index`."""
    found = kids.get(name)
    return text_of(found[0]) if found else None


def _location(element: etree._Element, locator: Locator | None) -> Location | None:
    if locator is None:
        return None
    position = locator.position(element)
    return Location(path=locator.source.path, line=position.line, column=position.column)


def ros1_type(element: etree._Element) -> str:
    """``<type>`` text, else the legacy ``type=`` attribute, else ``""``."""
    return _ros1_type(element, child_index(element))


def _ros1_type(element: etree._Element, kids: dict[str, list[etree._Element]]) -> str:
    typed = _first_text(kids, "type")
    if typed is not None and typed.strip():
        return typed.strip()
    return (element.get("type") or typed or "").strip()


def _read_ros1(element: etree._Element, locator: Locator | None,
               kids: dict[str, list[etree._Element]]) -> Transmission:
    type_string = _ros1_type(element, kids)
    kind = kind_of(type_string)
    joints = tuple([_ros1_member(j, locator) for j in kids.get("joint", ())])
    actuators = [_ros1_member(a, locator) for a in kids.get("actuator", ())]
    legacy = kids.get("mechanicalReduction")
    if legacy and len(actuators) == 1 and actuators[0].mechanical_reduction is None:
        # Pre-Hydro form: the reduction stands under <transmission>, meaning the actuator's.
        actuators[0] = replace(actuators[0], mechanical_reduction=_ros1_number(legacy[0]))
    return _new_transmission(
        name=element.get("name", ""),
        type=type_string,
        kind=kind,
        joints=joints,
        actuators=tuple(actuators),
        parameters=_parameters(kids) if "param" in kids else (),
        dialect="ros1",
        location=_location(element, locator) if locator is not None else None,
        xml=_xml(element) if kind == "other" else None,
    )


def _ros1_member(element: etree._Element, locator: Locator | None) -> Member:
    role: str | None = None
    reduction: Number | None = None
    offset: Number | None = None
    interfaces: list[str] = []
    for child in element[:]:  # one pass: the first role, reduction and offset, each interface
        tag = child.tag
        if tag.__class__ is not str:
            continue  # a comment or processing instruction
        tag = tag.rpartition("}")[2]
        if tag == "hardwareInterface":
            text = (child.text or "").strip()
            if text:
                interfaces.append(text)
        elif tag == "mechanicalReduction":
            if reduction is None:
                reduction = _ros1_number(child)
        elif tag == "offset":
            if offset is None:
                offset = _ros1_number(child)
        elif tag == "role" and role is None:
            role = (child.text or "").strip()
    return _new_member(
        name=element.get("name", ""),
        role=role,
        mechanical_reduction=reduction,
        offset=offset,
        interfaces=tuple(interfaces),
        location=_location(element, locator) if locator is not None else None,
    )


def _ros1_number(element: etree._Element) -> Number:
    return _ros1_number_of(element.text or "")


# One value for each text (the models are immutable): a document writes its numbers with a
# few texts, which these read once.
@lru_cache(maxsize=4096)
def _ros1_number_of(text: str) -> Number:
    return _new_number(value=parse_ros1(text), text=text)


@lru_cache(maxsize=4096)
def _ros2_number_of(text: str) -> Number:
    return _new_number(value=parse_ros2(text), text=text)


def _read_ros2(
    element: etree._Element,
    locator: Locator | None,
    dialect: Dialect,
    components: dict[etree._Element, Declarations],
    kids: dict[str, list[etree._Element]],
) -> Transmission:
    plugins = kids.get("plugin")
    # component_parser.cpp get_text_for_element: GetText() stripped, "" where it is null
    type_string = (get_text(plugins[0]) or "").strip(C_SPACE) if plugins else ""
    component_element = enclosing_component(element)
    component = None
    if component_element is not None:
        component = components.get(component_element)
        if component is None:
            component = components[component_element] = Declarations(component_element)
    kind = kind_of(type_string)
    return _new_transmission(
        name=element.get("name", "").strip(C_SPACE),
        type=type_string,
        kind=kind,
        joints=tuple([_ros2_member(j, locator, component) for j in kids.get("joint", ())]),
        actuators=tuple([_ros2_member(a, locator, None) for a in kids.get("actuator", ())]),
        parameters=_parameters(kids) if "param" in kids else (),
        dialect=dialect,
        location=_location(element, locator) if locator is not None else None,
        ros2_control=component.name if component is not None else None,
        xml=_xml(element) if kind == "other" else None,
    )


def _ros2_number(found: list[etree._Element]) -> Number:
    """The number of the ``found`` children of one name, as ros2_control takes it: the first
    whose GetText() is not null, and its default where that text does not convert
    (component_parser.cpp get_parameter_value_or)."""
    for child in found:
        text = get_text(child)
        if text is not None:
            return _ros2_number_of(text)
    return _ros2_number_of("")  # none: the default (a value of None, as "" reads)


def _ros2_member(
    element: etree._Element, locator: Locator | None, component: Declarations | None
) -> Member:
    role_element: etree._Element | None = None
    reductions: list[etree._Element] = []
    offsets: list[etree._Element] = []
    for child in element[:]:  # one pass: the first <role>, each reduction and offset
        tag = child.tag
        if tag.__class__ is not str:
            continue  # a comment or processing instruction
        tag = tag.rpartition("}")[2]
        if tag == "mechanical_reduction":
            reductions.append(child)
        elif tag == "offset":
            offsets.append(child)
        elif tag == "role" and role_element is None:
            role_element = child
    role = element.get("role")
    if role is not None:
        role = role.strip(C_SPACE)  # component_parser.cpp get_attribute_value strips
    elif role_element is not None:
        role = (role_element.text or "").strip()
    name = element.get("name", "").strip(C_SPACE)
    commands, states = component.interfaces(name) if component is not None else _UNDECLARED
    read_only = element.get("read_only")
    return _new_member(
        name=name,
        role=role,
        mechanical_reduction=_ros2_number(reductions) if reductions else None,
        offset=_ros2_number(offsets) if offsets else None,
        interfaces=commands,
        state_interfaces=states,
        read_only=read_only is not None and read_only.strip(C_SPACE).lower() == "true",
        location=_location(element, locator) if locator is not None else None,
    )


def _parameters(kids: dict[str, list[etree._Element]]) -> tuple[tuple[str, str], ...]:
    return tuple((p.get("name", ""), (p.text or "").strip()) for p in kids.get("param", ()))


def _xml(element: etree._Element) -> str:
    return etree.tostring(element, encoding="unicode", with_tail=False)
