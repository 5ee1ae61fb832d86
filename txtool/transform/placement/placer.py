"""Where converted transmissions go, so that converting back puts everything where it was.

ROS 1 -> ROS 2: top-level transmissions move into the ``<ros2_control>`` that declares their
joints; the others into one block that txtool generates, which takes the place of the first of
them. Transmissions that stood together keep the blank lines between them inside that block.
ROS 2 -> ROS 1: a block that is exactly what txtool generates for its transmissions is replaced
by them, at its place; from any other block they move out to stand just before it.
Removing an element removes its lines and keeps the blank lines around it.

What the placer moves is a :class:`.moves.Move`; whether a block is one txtool generates is
told by :mod:`.recognition`, which builds it again through the placer (:meth:`Placer.block`,
:meth:`Placer.build`); the xacro conditionals a transmission stands in, by :mod:`.scope`.
"""

from __future__ import annotations

import copy
from collections.abc import Callable

from lxml import etree

from txtool import dialects
from txtool.dialects.read import detect_dialect, enclosing_component
from txtool.io.xmlio import local
from txtool.model.core import Dialect, Transmission
from txtool.model.robot import children
from txtool.transform.placement.bindable import (
    RobotJoints,
    left_as_written,
    not_mimicking,
)
from txtool.transform.placement.layout import (
    append,
    become,
    child_indentation,
    cut,
    indentation,
    namespace_of,
    qualifier,
    reindent,
    restyle_roles,
    runs_of,
    with_comments,
)
from txtool.transform.placement.macros import (
    MacroCalls,
    calls_in,
    enclosing_macro,
    per_call,
    refusal,
    times,
)
from txtool.transform.placement.moves import Carried, Move
from txtool.transform.placement.recognition import generated_from
from txtool.transform.placement.scope import between, is_condition, prefixed

# ros2_control's mock hardware (hardware_interface/src/mock_components/generic_system.cpp):
# it sets each state to its command and drives nothing, a stand-in for the robot's own plugin.
DEFAULT_HARDWARE_PLUGIN = "mock_components/GenericSystem"

class Placer:
    """Puts converted elements where their target dialect expects them; call :meth:`finish`
    once every transmission has been placed."""

    def __init__(self, root: etree._Element, hardware_plugin: str, *,
                 macro_calls: MacroCalls | None = None) -> None:
        """``macro_calls``: where the files converted with this one call each macro
        (:mod:`.macros`)."""
        self.root = root
        self.macro_calls = macro_calls or {}
        self._calls: MacroCalls | None = None  # the document's, when asked
        self.hardware_plugin = hardware_plugin
        self.notes: list[str] = []
        self._into_new: list[Move] = []
        self._in_place: dict[etree._Element, list[Move]] = {}  # by the parent they stand in
        self._out_of: dict[etree._Element, list[Move]] = {}
        self._components: list[etree._Element] | None = None
        self._declared: dict[etree._Element, set[str]] = {}
        self.built: dict[etree._Element, etree._Element] = {}  # old element -> the last built
        # What the conversion cannot do as the document asks (it says why).
        self.losses: list[str] = []
        # What to look at, though nothing is lost (a transmission left as written).
        self.warnings: list[str] = []
        # The document's URDF joints: which a <ros2_control> may declare, and how.
        self.joints = RobotJoints(root)
        # Set when a block names the placeholder plugin: which blocks, and what to do.
        self.placeholder: str | None = None
        self._placeholders: list[str] = []  # blocks generated with the default plugin
        # Old elements that go back to ROS 1 just after their <ros2_control>, where they
        # stood before --reversible moved them in (:mod:`txtool.transform.reversible`); the
        # rest go before.
        self.after: set[etree._Element] = set()
        # The names of the <ros2_control> elements in the document (stripped, as ros2_control
        # reads them), once known: a block txtool adds takes a name none has.
        self._taken: set[str] | None = None

    def place(self, old: etree._Element, t: Transmission, carried: Carried | None = None,
              dialect: Dialect | None = None) -> bool:
        """Place the conversion ``t`` of ``old``; ``carried``: children of ``old`` (by
        owner) that go along as written; ``dialect``: ``old``'s, when known. Whether it is
        placed: one on a joint no ``<ros2_control>`` may declare is left as written
        (:mod:`.bindable`)."""
        move = Move(old, t, carried)
        component = enclosing_component(old)
        moving_out = t.dialect == "ros1" and component is not None
        moving_in = (t.dialect != "ros1" and component is None and old.getparent() is not None
                     and (dialect or detect_dialect(old)) == "ros1")
        if moving_in and not self._bindable(t.name, [j.name for j in t.joints]):
            return False
        if moving_out and component.getparent() is not None:
            if not self._conditions_between(old, component, t.name):
                return
            self._out_of.setdefault(component, []).append(move)
        elif moving_in and old.getparent() is self.root and local(self.root) == "robot":
            existing = self._component_for(lambda: {j.name for j in t.joints})
            if existing is None:
                self._not_in_scope(t)
                self._into_new.append(move)
            else:
                cut(old)
                append(existing, self.build(move, *child_indentation(existing), existing))
        elif moving_in:
            # Inside a xacro macro or conditional (or a file whose root is not a <robot>): a
            # <ros2_control> in place, one for those that stand together (:mod:`.macros`), so
            # that the transmission stays in the scope of its ${...} parameters.
            self._in_place.setdefault(old.getparent(), []).append(move)
        elif t.dialect != "ros1" and (dialect or detect_dialect(old)) != "ros1":
            restyle_roles(old, t.dialect)  # Proposal 1 <-> 2: only the roles change
        else:
            new = self.build(move, *indentation(old), old)
            new.tail = old.tail
            if old.getparent() is None:
                become(old, new)  # a bare <transmission> fragment
            else:
                old.getparent().replace(old, new)
        return True

    def _bindable(self, name: str, joints: list[str]) -> bool:
        """Whether a ``<ros2_control>`` may declare ``joints`` (a warning where not)."""
        refusal = self.joints.refusal(joints)
        if refusal is not None:
            self.warnings.append(left_as_written(name, refusal))
        return refusal is None

    def finish(self) -> None:
        if self._into_new:
            self._generate(self._into_new)
        for moves in self._in_place.values():
            self._wrap_in_place(moves)
        self._placeholder_warning()
        for component, moves in self._out_of.items():
            sources = generated_from(component, moves, self.root.get("name", "robot"), self)
            if sources is not None:
                for move, source in zip(moves, sources, strict=True):
                    move.new = source
                self._ungenerate(component, moves)
                self.notes.append(
                    f"<ros2_control name=\"{component.get('name')}\"> is what txtool generates "
                    "for its transmissions; replaced by them"
                )
                continue
            self._move_out(component, moves)

    def _move_out(self, component: etree._Element, moves: list[Move]) -> None:
        """Put the ROS 1 conversions of ``moves`` beside ``component``: just before it, or
        just after it for those in :attr:`after`; each inside copies of the ``xacro:if`` /
        ``xacro:unless`` it stood in within the block, so that the robot has it for the same
        arguments."""
        indent, step = indentation(component)
        anchor = component
        for move in moves:
            chain = between(move.old, component)
            cut(move.old)
            for condition in chain:
                if len(condition) == 0 and not (condition.text or "").strip():
                    cut(condition)  # left empty: it held the transmission alone
            new = self.build(move, indent + step * len(chain), step, component)
            for depth, condition in enumerate(chain, start=1):
                # Made in the document, where its namespace is declared already.
                wrapper = etree.SubElement(component.getparent(), condition.tag,
                                           dict(condition.attrib))
                wrapper.text = "\n" + indent + step * (len(chain) - depth + 1)
                new.tail = "\n" + indent + step * (len(chain) - depth)
                wrapper.append(new)
                new = wrapper
            if move.old in self.after:
                new.tail = anchor.tail
                anchor.tail = "\n" + indent
                anchor.addnext(new)
                anchor = new
            else:
                new.tail = "\n" + indent
                component.addprevious(new)

    # ROS 1 -> ROS 2 ----------------------------------------------------------------------

    def _generate(self, moves: list[Move]) -> None:
        first = moves[0].old
        indent, step = indentation(first)
        name = self._fresh_name(self.root.get("name", "robot"),
                                "the <ros2_control> generated for the document")
        block = self.block(name, self.hardware_plugin, moves, first, indent, step)
        self._put(block, moves, indent, step)

    def _put(self, block: etree._Element, moves: list[Move], indent: str, step: str) -> None:
        """Put ``block`` (built for ``moves``) at the place of the first of them: those that
        stood together with it stand together in the block, keeping the blank lines between
        them; the others are cut from where they stood."""
        runs = runs_of([move.old for move in moves])
        for old in runs[0][:-1]:
            self.built[old].tail = reindent(old.tail, indent + step)
        block.tail = runs[0][-1].tail
        for run in runs[1:]:
            for old in run:
                cut(old)
        first = runs[0][0]
        parent = first.getparent()
        for later in runs[0][1:]:
            # With its tail (the block's is the run's last); emptied once built (see
            # build()), it is removed without a walk through what it held.
            parent.remove(later)
        parent.replace(first, block)
        self._components = None

    def block(self, name: str, plugin: str, moves: list[Move], like: etree._Element,
               indent: str, step: str, *, record: bool = True,
               transmissions: bool = True) -> etree._Element:
        """A ``<ros2_control type="system">`` block declaring the joints of the converted
        transmissions and holding them (unless ``transmissions`` is false), as txtool
        generates it (``record``: as :meth:`build`)."""
        q = qualifier(like)
        block = etree.Element(q("ros2_control"), name=name, type="system")
        hardware = etree.SubElement(block, q("hardware"))
        etree.SubElement(hardware, q("plugin")).text = plugin
        self._fill(block, _declared(moves), moves if transmissions else [], like, indent, step,
                   record)
        notes = not_mimicking(block, self.joints)
        if record:
            self.notes.extend(notes)
        return block

    def _document_calls(self) -> MacroCalls:
        """The macro calls of the document (:func:`.macros.calls_in`), read once."""
        if self._calls is None:
            self._calls = {name: tuple(calls) for name, calls in calls_in(self.root).items()}
        return self._calls

    def _fill(self, block: etree._Element, declared: list[tuple[str, tuple]],
              moves: list[Move], like: etree._Element, indent: str, step: str, record: bool
              ) -> None:
        """Declare the joints in ``block`` and put in the transmissions built for ``moves``,
        laid out as :func:`dialects.pretty` lays out the block."""
        q = qualifier(like)
        inner = "\n" + indent + step
        declarations: dict[tuple, etree._Element] = {}  # by interfaces: copied, then named
        for name, interfaces in declared:
            if interfaces not in declarations:
                declarations[interfaces] = _declaration(q, *interfaces)
                dialects.pretty(declarations[interfaces], indent + step, step)
                declarations[interfaces].tail = inner
            declaration = copy.deepcopy(declarations[interfaces])
            declaration.set("name", name)
            block.append(declaration)
        hardware = block[0]
        dialects.pretty(hardware, indent + step, step)
        hardware.tail, block.text = inner, inner
        block[-1].tail = "\n" + indent
        for move in moves:
            append(block, self.build(move, indent + step, step, like, record=record))

    def _component_for(self, joints: Callable[[], set[str]]) -> etree._Element | None:
        """The first ``<ros2_control>`` that declares all of ``joints()``."""
        if self._components is None:
            self._components = list(self.root.iter("{*}ros2_control"))
        if not self._components:
            return None
        names = joints()
        for element in self._components:
            # One inside a xacro:if or macro is not there for every argument set: a
            # transmission moved into it would be too.
            if element.getparent() is self.root and names <= self._joints_of(element):
                return element
        return None

    def _not_in_scope(self, t: Transmission) -> None:
        """A loss when the joints of ``t``, going into a block of their own, are declared by
        a ``<ros2_control>`` that stands in a xacro conditional or macro: moving ``t`` in
        there would take it out of the robot for other arguments, and its own block declares
        the joints a second time where that one is there too."""
        if not self._components:
            return
        names = {j.name for j in t.joints}
        for element in self._components:
            shared = names & self._joints_of(element)
            if shared and element.getparent() is self.root:
                # It declares some of them (the transmission would go in had it declared
                # them all): a block of its own would declare those a second time.
                self.losses.append(
                    f"transmission '{t.name}': <ros2_control name=\"{element.get('name')}\"> "
                    f"declares its joint(s) {', '.join(sorted(shared))} but not "
                    f"{', '.join(sorted(names - shared))}: a <ros2_control> of its own would "
                    "declare them a second time (two hardware components claiming one joint); "
                    "declare all its joints in one <ros2_control>, then convert again")
                return
            if element.getparent() is not self.root and shared:
                scope = element.getparent()
                self.losses.append(
                    f"transmission '{t.name}': <ros2_control name=\"{element.get('name')}\"> "
                    f"declares its joints but stands inside <{prefixed(scope)}>: the "
                    "transmission is not moved in there (the robot would lose it for other "
                    "arguments), and the block generated for it declares them again; place "
                    "it by hand")
                return

    def _placeholder_warning(self) -> None:
        """Which generated blocks name the placeholder plugin, which must be replaced."""
        names = self._placeholders
        if not names:
            return
        shown = ", ".join(f"'{name}'" for name in names[:3]) + (", ..." if len(names) > 3
                                                               else "")
        blocks = (f"<ros2_control name=\"{names[0]}\">" if len(names) == 1 else
                  f"{len(names)} <ros2_control> blocks ({shown})")
        self.placeholder = (
            f"{blocks} generated with the placeholder hardware plugin "
            f"'{DEFAULT_HARDWARE_PLUGIN}' (ros2_control's mock hardware: it copies commands "
            "to states and drives no robot); replace it with the robot's hardware plugin, "
            "or convert with --hardware-plugin PLUGIN")

    def _fresh_name(self, base: str, what: str) -> str:
        """``base``, or ``base_2``, ``base_3``... when another ``<ros2_control>`` has that name
        (ros2_control's resource manager refuses two hardware components of one name:
        ros2_control hardware_interface/src/resource_manager.cpp,
        ResourceManager::load_and_initialize_components, "Hardware name %s is duplicated"; the
        component parser strips the names first). ``what``: the block, for the note."""
        if self._taken is None:
            self._taken = {(e.get("name") or "").strip()
                           for e in self.root.iter("{*}ros2_control")}
        name, number = base, 1
        while name.strip() in self._taken:
            number += 1
            name = f"{base}_{number}"
        self._taken.add(name.strip())
        if self.hardware_plugin == DEFAULT_HARDWARE_PLUGIN:
            self._placeholders.append(name)
        if name != base:
            self.notes.append(f"{what} is named '{name}': another <ros2_control> is named "
                              f"'{base}' (ros2_control refuses two hardware components of "
                              "one name)")
        return name

    def _conditions_between(self, old: etree._Element, component: etree._Element,
                            name: str) -> bool:
        """Whether ``old`` can move out of ``component``: what stands between them is
        ``xacro:if`` / ``xacro:unless`` at most (copied around it), not a macro."""
        for parent in between(old, component):
            if not is_condition(parent):
                self.losses.append(
                    f"transmission '{name}': stands inside <{prefixed(parent)}> within "
                    f"<ros2_control name=\"{component.get('name')}\">: a ROS 1 transmission "
                    "must stand outside the block, and it cannot leave that element; left as "
                    "written")
                return False
        return True

    def _joints_of(self, component: etree._Element) -> set[str]:
        if component not in self._declared:
            self._declared[component] = {j.get("name") for j in children(component, "joint")}
        return self._declared[component]

    def _wrap_in_place(self, moves: list[Move]) -> None:
        """One ``<ros2_control>`` around ``moves`` (which stand in one parent), at the place
        of the first: refused (a loss) in a macro that the document calls several times."""
        old = moves[0].old
        macro = enclosing_macro(old)
        name = (macro.get("name") or "").strip() if macro is not None else ""
        known = self.macro_calls or self._document_calls()
        count = times(name, known) if macro is not None else 0
        if count > 1:
            self.losses.append(refusal([m.new.name for m in moves], macro, count,
                                       list(known[name]), "the files migrated with it expand"
                                       if self.macro_calls else "this file expands"))
        indent, step = indentation(old)
        fresh = self._fresh_name(moves[0].new.name, f"the <ros2_control> around transmission "
                                 f"'{moves[0].new.name}'")
        block = self.block(fresh, self.hardware_plugin, moves, old, indent, step)
        self._put(block, moves, indent, step)
        if macro is not None and not count:
            self.notes.append(per_call(block.get("name"), macro))

    # ROS 2 -> ROS 1 ----------------------------------------------------------------------

    def _ungenerate(self, component: etree._Element, moves: list[Move]) -> None:
        indent, step = indentation(component)
        parent = component.getparent()
        news = [self.build(m, indent, step, component) for m in moves]
        for move, new in zip(moves, news, strict=True):
            new.tail = reindent(move.old.tail, indent)
        news[-1].tail = component.tail
        anchor = component
        for new in news:
            anchor.addnext(new)
            anchor = new
        parent.remove(component)
        for move in moves:
            # Each replaced element stands alone: lxml frees an element of a detached subtree
            # by scanning that whole subtree, so a block of N would cost N squared.
            component.remove(move.old)

    # Building ----------------------------------------------------------------------------

    def build(self, move: Move, indent: str, step: str, like: etree._Element, *,
               record: bool = True) -> etree._Element:
        """The converted element at ``indent``, in the namespace of ``like``, with the
        comments and carried children of the old one; ``record``: as what replaces the old
        one (:attr:`built`), not a trial build to compare with."""
        t = move.new
        new = dialects.build(t, t.dialect, indent=indent, step=step,
                             namespace=namespace_of(like))
        for (kind, name), elements in (move.carried or {}).items():
            owner = new if kind == "transmission" else next(
                (m for m in children(new, kind) if m.get("name") == name), new)
            owner.extend(copy.deepcopy(e) for e in elements)
        if with_comments(new, move.old) or move.carried:
            dialects.pretty(new, indent, step)  # build() laid out all but these
        if record:
            self.built[move.old] = new
            # What the old element held is read (the new one is built, its comments and
            # carried children copied): freed now rather than with the tree, so that the old
            # and the new transmissions of a document are not held at once. The element
            # itself stays, empty, where the edits will look for it.
            del move.old[:]
        return new


def _declared(moves: list[Move]) -> list[tuple[str, tuple]]:
    """The joints a generated block declares (names and interfaces, in order: the first of
    each name)."""
    seen: set[str] = set()
    declared: list[tuple[str, tuple]] = []
    for move in moves:
        for joint in move.new.joints:
            if joint.name not in seen:
                seen.add(joint.name)
                declared.append((joint.name, (joint.interfaces, joint.state_interfaces)))
    return declared


def _declaration(q: Callable[[str], str], commands: tuple[str, ...],
                 states: tuple[str, ...]) -> etree._Element:
    """A ``<joint>`` declaring these interfaces, its name still empty (the first attribute)."""
    element = etree.Element(q("joint"), name="")
    for name in commands:
        etree.SubElement(element, q("command_interface"), name=name)
    for name in states:
        etree.SubElement(element, q("state_interface"), name=name)
    return element
