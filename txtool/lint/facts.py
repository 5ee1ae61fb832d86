"""What the rules read of each transmission, found once per transmission.

Twenty-five rules look at the same few things of every transmission: its dialect, type and kind,
its name, its ``<type>``/``<plugin>`` element, its joints and actuators with their names,
elements and children, the numbers and interface names its loader reads. :class:`Facts` holds
them, taken from the XML in one pass per transmission as the reader takes them
(:func:`~txtool.dialects.read.detect_dialect`, :func:`~txtool.dialects.read.ros1_type`,
:func:`~txtool.model.core.kind_of`; ``tests/lint/test_facts.py`` holds the two together), so
that a rule reads attributes instead of walking the elements again. The canonical model of a
transmission (:attr:`Found.transmission`, read by
:func:`~txtool.dialects.read.read_transmission`) is read only when a rule asks for it: most
transmissions of most documents never need it (a rule that needs roles, numbers as the model
holds them or the loaded map asks for it).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from lxml import etree

from txtool.dialects.read import Found, detect_dialect, read_transmission
from txtool.model.core import kind_of
from txtool.model.robot import ancestor, child_index, children

if TYPE_CHECKING:
    from txtool.model.core import Member, Transmission
    from txtool.model.robot import Component

# Transmission families with their own loaders (not ros_control's transmission_interface):
# pr2_mechanism / ros_ethercat parse their own XML; franka_hw registers state/model interfaces.
OWN_LOADER_FAMILIES: tuple[str, ...] = ("pr2_mechanism_model/", "sr_mechanism_model/")

Index = dict[str, list[etree._Element]]
_NONE: tuple[etree._Element, ...] = ()


class LintFound(Found):
    """A :class:`~txtool.dialects.read.Found` whose transmission is read on first use.

    ``components`` caches the ``<ros2_control>`` elements read for the document's ROS 2
    transmissions (as :func:`~txtool.dialects.read.read_source` shares them).
    """

    def __init__(self, element: etree._Element, components: dict[etree._Element, Component]
                 ) -> None:
        # The fields set in the instance's dictionary: the frozen dataclass refuses assignment.
        fields = self.__dict__
        fields["element"] = element
        fields["memo"] = {}
        fields["_components"] = components
        fields["_read"] = None

    @property  # type: ignore[override]
    def transmission(self) -> Transmission:
        read: Transmission | None = self._read  # type: ignore[has-type]
        if read is None:
            read = read_transmission(self.element, None, self._components)  # type: ignore[has-type]
            object.__setattr__(self, "_read", read)
        return read


class _Children:
    """An element (``element``) whose children by local name are indexed on first use
    (``_kids``, None until then)."""

    __slots__ = ()
    element: etree._Element
    _kids: Index | None

    @property
    def kids(self) -> Index:
        """The element's children by local name (shared: do not change it)."""
        kids = self._kids
        if kids is None:
            kids = self._kids = child_index(self.element)
        return kids

    def tagged(self, name: str) -> list[etree._Element] | tuple[etree._Element, ...]:
        """The element's children named ``name`` (in any namespace): from :attr:`kids` where
        they were indexed, else looked up alone."""
        kids = self._kids
        if kids is None:
            return children(self.element, name)
        return kids.get(name, _NONE)


class MemberRef(_Children):
    """A joint or actuator of a transmission: its element and name, and (read on first use)
    its children by local name, its interface names and its model."""

    __slots__ = ("noun", "element", "name", "_kids", "_interfaces", "_found", "_index")

    def __init__(self, noun: str, element: etree._Element, found: Found, index: int) -> None:
        self.noun = noun  # "joint" or "actuator"
        self.element = element
        self.name: str = element.get("name", "")  # as the model's Member.name
        # Read when a rule first asks: the rules about a ROS 1 transmission ask for a
        # member's children several times (kept), those about a ROS 2 one for a number or
        # two (looked up without keeping an index: see tagged()).
        self._kids: Index | None = None
        self._interfaces: list[str] | None = None
        self._found = found
        self._index = index

    def __repr__(self) -> str:
        return f"MemberRef({self.noun!r}, {self.name!r})"

    @property
    def interfaces(self) -> list[str]:
        """The non-empty ``<hardwareInterface>`` texts, stripped (for ROS 1, the model's
        Member.interfaces)."""
        known = self._interfaces
        if known is None:
            named = self.kids.get("hardwareInterface")
            known = self._interfaces = texts_of(named) if named else []
        return known

    @property
    def member(self) -> Member:
        """The model of this joint or actuator (reads the transmission when first asked)."""
        t = self._found.transmission
        return (t.joints if self.noun == "joint" else t.actuators)[self._index]


def texts_of(elements: list[etree._Element] | tuple[etree._Element, ...]) -> list[str]:
    """The stripped texts of ``elements``, without the empty ones."""
    if len(elements) == 1:  # the common case, without two list comprehensions
        text = (elements[0].text or "").strip()
        return [text] if text else []
    texts = [(e.text or "").strip() for e in elements]
    return [text for text in texts if text]


class Hints:
    """What a look at the whole document rules out, for every transmission in it.

    ``plain``: no CDATA section (an element's text nodes are its ``text``); ``components``:
    some ``<ros2_control>`` element; ``roles``: a ``role`` attribute may occur; ``mimics``: a
    ``<mimic>`` element may occur. Unsure is False for the first, True for the others (the slow,
    always right answer).
    """

    __slots__ = ("plain", "components", "roles", "mimics")

    def __init__(self, plain: bool = False, components: bool = True, roles: bool = True,
                 mimics: bool = True) -> None:
        self.plain = plain
        self.components = components
        self.roles = roles
        self.mimics = mimics


_UNSURE = Hints()


class Facts(_Children):
    """One transmission as the rules see it (``found`` is the reader's transmission)."""

    __slots__ = (
        "found", "element", "name", "ros1", "type", "kind", "_kids", "type_element",
        "type_text", "typed_ros1", "own_loader", "members", "joints", "actuators", "plain",
        "component", "numbers", "_joint_interfaces", "_actuator_interfaces",
    )

    def __init__(self, found: Found, hints: Hints = _UNSURE) -> None:
        element = found.element
        kids = child_index(element)
        named = kids.get("joint")
        if named is None:
            joints: list[MemberRef] = []
        elif len(named) == 1:  # the common case, without a list comprehension
            joints = [MemberRef("joint", named[0], found, 0)]
        else:
            joints = [MemberRef("joint", e, found, i) for i, e in enumerate(named)]
        named = kids.get("actuator")
        if named is None:
            actuators: list[MemberRef] = []
        elif len(named) == 1:
            actuators = [MemberRef("actuator", named[0], found, 0)]
        else:
            actuators = [MemberRef("actuator", e, found, i) for i, e in enumerate(named)]
        members = joints + actuators
        # What read_transmission reads first: the dialect (detect_dialect's first test: no
        # role attribute, no <plugin>, no enclosing <ros2_control> is ROS 1; else its own
        # answer), then the type (ros1_type: the <type> text, else the legacy attribute) and
        # the kind. tests/lint/test_facts.py holds these to the model, document by document.
        components = hints.components
        if components or "plugin" in kids or (hints.roles and _role_attribute(members)):
            ros1 = detect_dialect(element, kids) == "ros1"
        else:
            ros1 = True
        typed = kids.get("type" if ros1 else "plugin")
        if typed is None:
            self.type_element = self.type_text = None
            text = (element.get("type") or "").strip() if ros1 else ""
        else:
            self.type_element = typed[0]
            text = self.type_text = (typed[0].text or "").strip()  # that element's
            if not text and ros1:
                text = (element.get("type") or "").strip()
        self.type = text
        self.found = found
        self.element = element
        self.name: str = element.get("name", "")  # as the model's Transmission.name
        self.ros1 = ros1
        self.kind = kind_of(text)
        # Kept for the rules that read a transmission's children again, all about ROS 1 (a
        # ROS 2 transmission's are indexed again if one asks).
        self._kids = kids if ros1 else None
        # ros_control gets past parsing only with a <type> element (the pre-Hydro type=
        # attribute alone is skipped before any loader runs) and a name.
        self.typed_ros1 = ros1 and typed is not None
        self.own_loader = text.startswith(OWN_LOADER_FAMILIES)
        self.joints = joints
        self.actuators = actuators
        self.members = members
        self.numbers: object = None  # the numbers its loader reads (see support.numbers_of)
        # The document holds no CDATA section: an element's text nodes are its ``text``.
        self.plain = hints.plain
        self._joint_interfaces: frozenset[str] | None = None
        self._actuator_interfaces: bool | None = None
        # The enclosing <ros2_control> (none to look for when the document has none).
        self.component = ancestor(element, "ros2_control") if components else None

    @property
    def parsed(self) -> bool:
        """Whether the loader gets past parsing it (ros_control: a ``<type>`` and a name)."""
        return not self.ros1 or (self.typed_ros1 and bool(self.name.strip()))

    @property
    def group(self) -> tuple[object, ...]:
        """Transmissions read by the same loader instance: ROS 1, or one ``<ros2_control>``."""
        return ("ros1",) if self.ros1 else ("ros2", self.component)

    @property
    def transmission(self) -> Transmission:
        """The canonical model (read on first use)."""
        return self.found.transmission

    @property
    def joint_interfaces(self) -> frozenset[str]:
        """Every interface name of the joints (see :attr:`MemberRef.interfaces`)."""
        known = self._joint_interfaces
        if known is None:
            joints = self.joints
            if len(joints) == 1:
                known = frozenset(joints[0].interfaces)
            else:
                names: set[str] = set()
                for ref in joints:
                    names.update(ref.interfaces)
                known = frozenset(names)
            self._joint_interfaces = known
        return known

    @property
    def actuator_interfaces(self) -> bool:
        """Whether some actuator names an interface (see :attr:`MemberRef.interfaces`)."""
        known = self._actuator_interfaces
        if known is None:
            known = False
            for ref in self.actuators:
                if ref.interfaces:
                    known = True
                    break
            self._actuator_interfaces = known
        return known

    @property
    def label(self) -> str:
        """``transmission 'name'`` for messages (or ``unnamed transmission``)."""
        name = self.name
        return f"transmission '{name}'" if name else "unnamed transmission"


def _role_attribute(members: list[MemberRef]) -> bool:
    return any(ref.element.get("role") is not None for ref in members)


def facts_of(found: Found, hints: Hints = _UNSURE) -> Facts:
    """The facts of one transmission, built on first use and kept with it."""
    known = found.memo.get("facts")
    if known is None:
        known = found.memo["facts"] = Facts(found, hints)
    return known  # type: ignore[return-value]
