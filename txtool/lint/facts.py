"""What the rules read of each transmission, found once per transmission.

Twenty-five rules look at the same few things of every transmission: its dialect and kind, its
``<type>``/``<plugin>`` element, its joints and actuators with their elements and children, the
numbers and interface names its loader reads. :class:`Facts` holds them, built in one pass per
transmission (the child indexes come from the reader's own, see
:func:`~txtool.model.robot.indexed_children`), so that a rule reads attributes instead of
walking the elements again. What few rules need (numbers, interface texts) is found on first use.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from lxml import etree

from txtool.model.robot import ancestor, child_index

if TYPE_CHECKING:
    from txtool.dialects.read import Found
    from txtool.model.core import Member, Transmission

# Transmission families with their own loaders (not ros_control's transmission_interface):
# pr2_mechanism / ros_ethercat parse their own XML; franka_hw registers state/model interfaces.
OWN_LOADER_FAMILIES: tuple[str, ...] = ("pr2_mechanism_model/", "sr_mechanism_model/")

Index = dict[str, list[etree._Element]]
_NONE: tuple[etree._Element, ...] = ()


class MemberRef:
    """A joint or actuator of a transmission, with the element it was read from.

    ``kids`` indexes the element's children by local name (shared: do not change it).
    """

    __slots__ = ("noun", "member", "element", "kids", "_interfaces")

    def __init__(self, noun: str, member: Member, element: etree._Element,
                 kids: Index | None = None) -> None:
        self.noun = noun  # "joint" or "actuator"
        self.member = member
        self.element = element
        self.kids: Index = child_index(element) if kids is None else kids
        self._interfaces: list[str] | None = None

    def __repr__(self) -> str:
        return f"MemberRef({self.noun!r}, {self.member!r})"

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, MemberRef):
            return NotImplemented
        return (self.noun, self.member, self.element) == (other.noun, other.member, other.element)

    def __hash__(self) -> int:
        return hash((self.noun, self.member, self.element))

    def tagged(self, name: str) -> list[etree._Element] | tuple[etree._Element, ...]:
        """The member's children named ``name`` (in any namespace)."""
        return self.kids.get(name, _NONE)

    @property
    def interfaces(self) -> list[str]:
        """The non-empty ``<hardwareInterface>`` texts of the element, stripped."""
        known = self._interfaces
        if known is None:
            known = self._interfaces = texts_of(self.kids.get("hardwareInterface", _NONE))
        return known


def texts_of(elements: list[etree._Element] | tuple[etree._Element, ...]) -> list[str]:
    """The stripped texts of ``elements``, without the empty ones."""
    texts = [(e.text or "").strip() for e in elements]
    return [text for text in texts if text]


class Facts:
    """One transmission as the rules see it (``found`` is the reader's transmission)."""

    __slots__ = (
        "found", "element", "transmission", "ros1", "kind", "kids", "type_element", "type_text",
        "typed_ros1", "parsed", "own_loader", "members", "joints", "actuators", "memo", "plain",
        "component", "group",
    )

    def __init__(self, found: Found, plain: bool = False, components: bool = True) -> None:
        t: Transmission = found.transmission
        element = found.element
        kids = child_index(element)
        ros1 = t.dialect == "ros1"
        self.found = found
        self.element = element
        self.transmission = t
        self.ros1 = ros1
        self.kind = t.kind
        self.kids = kids
        typed = kids.get("type" if ros1 else "plugin")
        self.type_element = typed[0] if typed else None
        self.type_text = (typed[0].text or "").strip() if typed else None  # that element's
        # ros_control gets past parsing only with a <type> element (the pre-Hydro type=
        # attribute alone is skipped before any loader runs) and a name.
        self.typed_ros1 = ros1 and typed is not None
        self.parsed = not ros1 or (self.typed_ros1 and bool(t.name.strip()))
        self.own_loader = t.type.startswith(OWN_LOADER_FAMILIES)
        joints = [MemberRef("joint", member, e)
                  for member, e in zip(t.joints, kids.get("joint", _NONE), strict=True)]
        actuators = [MemberRef("actuator", member, e)
                     for member, e in zip(t.actuators, kids.get("actuator", _NONE), strict=True)]
        self.joints = joints
        self.actuators = actuators
        self.members = joints + actuators
        self.memo: dict[str, object] = {}  # answers a few rules share (see support)
        # The document holds no CDATA section: an element's text nodes are its ``text``.
        self.plain = plain
        # The enclosing <ros2_control> (none to look for when the document has none).
        self.component = ancestor(element, "ros2_control") if components else None
        # Transmissions read by the same loader instance: ROS 1, or one <ros2_control>.
        self.group: tuple[object, ...] = ("ros1",) if ros1 else ("ros2", self.component)

    def tagged(self, name: str) -> list[etree._Element] | tuple[etree._Element, ...]:
        """The transmission's children named ``name`` (in any namespace)."""
        return self.kids.get(name, _NONE)

    @property
    def label(self) -> str:
        """``transmission 'name'`` for messages (or ``unnamed transmission``)."""
        name = self.transmission.name
        return f"transmission '{name}'" if name else "unnamed transmission"


def facts_of(found: Found, plain: bool = False, components: bool = True) -> Facts:
    """The facts of one transmission, built on first use and kept with it."""
    known = found.memo.get("facts")
    if known is None:
        known = found.memo["facts"] = Facts(found, plain, components)
    return known  # type: ignore[return-value]
