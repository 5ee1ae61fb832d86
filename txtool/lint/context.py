"""Everything a lint rule may look at for one document."""

from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import TYPE_CHECKING, Any, Generic, TypeVar, overload

from lxml import etree

from txtool.dialects.read import Found, transmission_elements
from txtool.io.xmlio import Source, is_xacro_element, local
from txtool.lint.facts import Facts, Hints, LintFound, facts_of
from txtool.lint.problem import Note, Problem, Severity
from txtool.lint.text import scanned_form
from txtool.model.robot import (
    Component,
    JointInfo,
    JointsOnDemand,
    components,
    joint_elements,
)

if TYPE_CHECKING:
    from txtool.io.locate import Locator, Position
    from txtool.lint.macro_calls import Tracer
    from txtool.model.readers import Assumption, Sim, Stated


_T = TypeVar("_T")


class lazy(Generic[_T]):  # noqa: N801 - a decorator, lower case like functools.cached_property
    """``functools.cached_property`` without its lock: the value is computed on first access and
    stored in the instance's ``__dict__``, where later reads find it without calling anything.

    Python 3.11's version takes a lock on every first access (3.12 dropped it), which costs
    validate of many small files measurably; a LintContext belongs to one thread.
    """

    def __init__(self, compute: Callable[[Any], _T]) -> None:
        self.compute = compute
        self.name = compute.__name__
        self.__doc__ = compute.__doc__

    def __set_name__(self, owner: type, name: str) -> None:
        self.name = name

    @overload
    def __get__(self, instance: None, owner: type | None = None) -> lazy[_T]: ...
    @overload
    def __get__(self, instance: object, owner: type | None = None) -> _T: ...
    def __get__(self, instance: object | None, owner: type | None = None) -> Any:
        if instance is None:
            return self
        value = instance.__dict__[self.name] = self.compute(instance)
        return value


_WALKED = ("transmission", "joint", "ros2_control")
_WALKED_TAGS = {name: f"{{*}}{name}" for name in _WALKED}


class LintContext:
    """One parsed document (after xacro expansion when the input is xacro).

    ``found`` are the transmissions with their elements; ``joints`` the URDF joints (names,
    types and mimics: their limits are not read);
    ``components`` the ``<ros2_control>`` elements. ``is_robot`` is False for bare
    fragments (a ``<transmission>`` or ``<ros2_control>`` root, or a xacro macro library
    without a robot), where cross-checks against the robot's joints do not apply.

    ``literal`` is True when a xacro file is linted as written (a macro library, or when
    expansion is off or failed): values containing ``${...}`` or ``$(...)`` are then unknown
    (see :meth:`unknown`). ``options`` holds each rule's validated options by code.
    """

    def runs(self, code: str) -> bool:
        """Whether the rule ``code`` runs on this document."""
        return self.enabled is None or code in self.enabled

    def __init__(self, source: Source, found: list[Found] | None = None, literal: bool = False,
                 options: Mapping[str, Any] | None = None, stated: Stated | None = None,
                 enabled: frozenset[str] | None = None) -> None:
        self.source = source
        # The rules that run (None: all), for a rule whose finding another one's covers.
        self.enabled = enabled
        self.stated = stated
        self.literal = literal
        self.options: Mapping[str, Any] = {} if options is None else options
        # Facts about the whole document that several rules share (see txtool.lint.rule_helpers).
        self.memo: dict[str, Any] = {}
        if not found:
            # Each transmission's model is read when a rule first asks for it (see facts).
            components: dict[etree._Element, Component] = {}
            found = [
                LintFound(element, components)
                for element in transmission_elements(source.root, self._walked["transmission"])
            ]
        self.found: list[Found] = found

    def release(self) -> None:
        """Drop the facts kept with each transmission once the rules are done.

        Facts and their transmission refer to each other (a cycle): left alone, each document
        (its tree included) would wait for the garbage collector, whose passes over the
        growing heap cost validate of many small files about a tenth of its time.
        """
        for found in self.found:
            found.memo.clear()

    @lazy
    def _walked(self) -> dict[str, list[etree._Element]]:
        """One walk of the tree for the elements rules look for at any depth."""
        # One walk per name: lxml matches tags in C, and reading each element's tag in Python
        # to sort one walk's elements costs more than the two extra walks.
        root = self.source.root
        return {name: list(root.iter(tag)) for name, tag in _WALKED_TAGS.items()}

    @lazy
    def facts(self) -> list[Facts]:
        """What the rules read of each transmission some reader of this document reads (see
        :mod:`txtool.lint.facts`), in order: a transmission no reader reads gets one finding
        (TX305), not the verdicts of a loader that never sees it."""
        every = self.every_fact
        unread = self.unread
        if not unread:
            return every
        skipped = {id(tx) for tx in unread}
        return [tx for tx in every if id(tx) not in skipped]

    @lazy
    def every_fact(self) -> list[Facts]:
        """The facts of every transmission, read by a reader of this document or not."""
        hints = self.hints
        return [facts_of(found, hints) for found in self.found]

    @lazy
    def readers(self) -> Assumption:
        """The programs that read this document (see :mod:`txtool.model.readers`)."""
        from txtool.lint.readers import assumption_of
        from txtool.model.readers import Stated

        return assumption_of(self.source, self.stated or Stated())

    @lazy
    def unread(self) -> list[Facts]:
        """The transmissions no reader of this document reads (none when nothing decides the
        readers). In a xacro file read as written, a macro's transmission may be instantiated
        anywhere: its form tells where it is meant to stand (a ROS 1 one at the top level,
        where only ros_control looks; a ROS 2 one inside ``<ros2_control>``)."""
        readers = self.readers
        if not readers.decided:
            return []
        from txtool.model.readers import Placement, placement_of

        unread = []
        for tx in self.every_fact:
            element = tx.found.element
            if self.in_macro(element):
                placement = Placement.TOP_LEVEL if tx.ros1 else Placement.IN_COMPONENT
            else:
                placement = placement_of(element)
            if not readers.reads(placement):
                unread.append(tx)
        return unread

    def in_macro(self, element: etree._Element) -> bool:
        """In a xacro file read as written: whether ``element`` stands in a macro body."""
        if not self.literal:
            return False
        parent = element.getparent()
        while parent is not None:
            if is_xacro_element(parent) and local(parent) == "macro":
                return True
            parent = parent.getparent()
        return False

    @lazy
    def hints(self) -> Hints:
        """What the bytes rule out: without a CDATA section an element's text nodes are its
        text; without the word, no role attribute and no ``<mimic>`` element (tag and attribute
        names stand in the bytes as they are). Only where the tree is the bytes as parsed: a
        source that is not an expansion (``Source.tree`` is then the file itself)."""
        form = None if self.source.expanded else scanned_form(self.source.data)
        return Hints(
            plain=form is not None and b"<![CDATA[" not in form,
            components=bool(self._walked["ros2_control"]),
            roles=form is None or b"role" in form,
            mimics=form is None or b"mimic" in form,
        )

    @lazy
    def locator(self) -> Locator:
        from txtool.io.locate import Locator  # only a document with findings needs positions

        return Locator(self.source)

    @lazy
    def joint_elements(self) -> dict[str, etree._Element]:
        """The robot's ``<joint>`` elements by name (see :attr:`joints`)."""
        return joint_elements(self.source.root, self._walked["joint"])

    @lazy
    def joints(self) -> Mapping[str, JointInfo]:
        return JointsOnDemand(self.joint_elements, limits=False)

    @lazy
    def components(self) -> list[Component]:
        return components(self.source.root, self._walked["ros2_control"])

    @lazy
    def is_robot(self) -> bool:
        return (not self.literal and local(self.source.root) == "robot"
                and bool(self.joint_elements))

    def unknown(self, text: str | None) -> bool:
        """True for a value only xacro can tell: it contains ``${...}`` or ``$(...)``."""
        return text is not None and ("${" in text or "$(" in text)

    def option(self, code: str) -> Any:
        """The options of rule ``code`` (its ``Options`` model), or None."""
        return self.options.get(code)

    def position(self, element: etree._Element) -> Position:
        return self.locator.position(element)

    def problem(
        self, code: str, element: etree._Element, message: str, *, fixable: bool | None = None,
        loader_severity: Severity | None = None, refuses_whole: bool = False,
    ) -> Problem:
        """A problem at ``element``; marks positions only traced through xacro.

        ``fixable=False`` marks a finding the rule's fix declines by design;
        ``loader_severity`` lowers a finding that the file's own loader accepts;
        ``refuses_whole`` marks one for which the reader refuses the whole document.
        """
        traced = self.traced(element) if self.source.expanded else None
        if traced is not None:  # at the macro call, the macro's body related
            where, related = traced
            return Problem(self.source.path, where.line, where.column, code, message,
                           fixable=fixable, loader_severity=loader_severity, related=related)
        where = self.position(element)
        if where.expanded:
            message = f"{message} (after xacro expansion)"
        return Problem(self.source.path, where.line, where.column, code, message, fixable=fixable,
                       loader_severity=loader_severity, refuses_whole=refuses_whole)

    def traced(self, element: etree._Element) -> tuple[Position, tuple[Note, ...]] | None:
        """In an expansion: where a finding at ``element`` goes (the macro call that made it)
        and its related places, see :mod:`txtool.lint.macro_calls`; None where no call made
        it."""
        known = self._traced.get(element)
        if known is None and element not in self._traced:
            known = self._traced[element] = self.tracer.position(element)
        return known

    @lazy
    def _traced(self) -> dict[etree._Element, tuple[Position, tuple[Note, ...]] | None]:
        return {}

    @lazy
    def tracer(self) -> Tracer:
        from txtool.lint.macro_calls import Tracer

        return Tracer(self.locator, self.source.path)

    @property
    def gazebo_sim(self) -> Sim | None:
        """The ``<plugin>`` that loads this robot into Gazebo through gazebo_ros_control, with
        a RobotHWSim whose rules are known, when it is one of this document's readers (see
        :class:`txtool.model.readers.Sim`)."""
        return self.readers.sim
