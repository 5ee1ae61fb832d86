"""Convert the transmissions of a whole document, keeping everything else as written.

Only transmissions whose dialect differs from the target are rewritten; comments, other
elements, attribute order, namespaces and the XML declaration are untouched. ROS 1 -> ROS 2
moves each transmission into the ``<ros2_control>`` that declares its joints (or a new one);
ROS 2 -> ROS 1 moves it out to the top level, just before its ``<ros2_control>``.
Every conversion is checked by reading the result back and converting it back.
"""

from __future__ import annotations

import copy
from collections.abc import Callable
from dataclasses import dataclass, field

from lxml import etree

from txtool import dialects
from txtool.dialects.read import enclosing_component, read_source
from txtool.dialects.translate import family, is_expression, translate
from txtool.io.xmlio import Source, local, parse_bytes, serialize
from txtool.model.core import Dialect, Transmission
from txtool.model.robot import children
from txtool.model.semantics import NotLoadable, effective
from txtool.views.tables import differences

DEFAULT_HARDWARE_PLUGIN = "mock_components/GenericSystem"
KNOWN_CHILDREN = {
    "ros1": {
        "transmission": {"type", "joint", "actuator", "mechanicalReduction"},
        "joint": {"hardwareInterface", "role", "offset", "mechanicalReduction"},
        "actuator": {"hardwareInterface", "role", "mechanicalReduction"},
    },
    "ros2": {
        "transmission": {"plugin", "joint", "actuator", "param"},
        "joint": {"mechanical_reduction", "offset", "role"},
        "actuator": {"mechanical_reduction", "offset", "role"},
    },
}


@dataclass
class Conversion:
    data: bytes
    target: Dialect
    losses: list[str] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    converted: int = 0


def convert_source(
    source: Source, target: Dialect, *, hardware_plugin: str = DEFAULT_HARDWARE_PLUGIN
) -> Conversion:
    tree = copy.deepcopy(source.tree)
    originals = read_source(Source(source.path, source.data, tree))
    result = Conversion(data=b"", target=target)
    placer = _Placer(tree.getroot(), hardware_plugin)
    for found in originals:
        t = found.transmission
        if t.dialect == target or t.kind == "other" and family(t.dialect) == family(target):
            continue
        if target == "ros1" and enclosing_component(found.element) is tree.getroot():
            result.losses.append(
                f"transmission '{t.name}': a bare <ros2_control> fragment has no place for a "
                "top-level ROS 1 transmission; convert the robot description that holds it"
            )
            continue
        translation = translate(t, target)
        result.losses.extend(translation.losses)
        result.notes.extend(translation.notes)
        if t.kind == "other":
            continue
        result.losses.extend(_unknown_children(found.element, t, target))
        _behaviour(t, translation.transmission, result)
        placer.place(found.element, translation.transmission)
        result.converted += 1
    result.data = serialize(tree, source.data)
    result.losses.extend(_check(source, result, originals))
    return result


def _unknown_children(element: etree._Element, t: Transmission, target: Dialect) -> list[str]:
    known = KNOWN_CHILDREN[family(t.dialect)]
    lost = []
    for parent in [element, *children(element, "joint"), *children(element, "actuator")]:
        allowed = known["transmission" if parent is element else local(parent)]
        for child in parent:
            if isinstance(child.tag, str) and local(child) not in allowed:
                owner = f"{local(parent)} '{parent.get('name', '')}'"
                lost.append(f"{owner}: <{local(child)}> has no place in {target}; dropped")
    return lost


def _behaviour(before: Transmission, after: Transmission, result: Conversion) -> None:
    """A loss when the target loader would bind the values differently (never silent)."""
    numbers = [n for m in before.joints + before.actuators
               for n in (m.mechanical_reduction, m.offset)]
    if any(is_expression(n) for n in numbers):
        result.notes.append(f"transmission '{before.name}': xacro expressions are carried "
                            "verbatim; check the expanded result")
        return
    try:
        old = effective(before)
    except NotLoadable as exc:
        result.notes.append(f"transmission '{before.name}': the original is not loadable ({exc})")
        return
    try:
        new = effective(after)
    except NotLoadable as exc:
        result.losses.append(f"transmission '{after.name}': the result is not loadable ({exc})")
        return
    if _same_binding(old, new):
        return
    if old.joints != new.joints:
        reason = (f"joints {', '.join(new.joints)} take the values written for "
                  f"{', '.join(old.joints)} (ros2_control orders handles by name; see TX401)")
    else:
        reason = "the loaded reductions or offsets differ"
    result.losses.append(
        f"transmission '{before.name}': behaves differently under {new.loader}: {reason}"
    )


def _same_binding(old, new) -> bool:
    fields = ("kind", "joints", "actuators", "actuator_reduction", "joint_reduction",
              "joint_offset")
    if old.kind == "simple":
        same_names = (old.joints, old.actuators) == (new.joints, new.actuators)
        return same_names and old.joint_offset == new.joint_offset and (
            old.actuator_reduction[0] * old.joint_reduction[0]
            == new.actuator_reduction[0] * new.joint_reduction[0]
        )
    return all(getattr(old, f) == getattr(new, f) for f in fields)


def _check(source: Source, result: Conversion, originals) -> list[str]:
    """Read the output back, convert it back, and compare with the original."""
    tree = parse_bytes(result.data, source.path)
    written = {f.transmission.name: f.transmission for f in read_source(
        Source(source.path, result.data, tree))}
    problems = []
    for found in originals:
        t = found.transmission
        if t.kind == "other" or t.name not in written:
            continue
        back = translate(written[t.name], t.dialect).transmission
        for diff in differences(t, back):
            problems.append(f"transmission '{t.name}' did not survive the round trip: {diff}")
    return problems


class _Placer:
    """Puts converted elements where their target dialect expects them."""

    def __init__(self, root: etree._Element, hardware_plugin: str) -> None:
        self.root = root
        self.hardware_plugin = hardware_plugin
        self.created: etree._Element | None = None
        # Joint names declared per <ros2_control>, kept up to date by _declare: looking them up
        # afresh for every transmission made a conversion quadratic in their number.
        self._declared: dict[etree._Element, set[str]] = {}
        self._last_joint: dict[etree._Element, etree._Element] = {}
        self._components: list[etree._Element] | None = None  # None: look again

    def place(self, old: etree._Element, t: Transmission) -> None:
        component = enclosing_component(old)
        moving_out = t.dialect == "ros1" and component is not None
        moving_in = t.dialect != "ros1" and component is None and old.getparent() is not None
        if moving_out and component.getparent() is not None:
            _remove(old)
            _insert_before(component, self._build(t, component, old))
        elif moving_in and old.getparent() is self.root and local(self.root) == "robot":
            component = self._component_for(t)
            _remove(old)
            _append(component, self._build_inside(t, component, old))
        elif moving_in and local(self.root) == "robot":
            # Inside a xacro macro or conditional: a <ros2_control> of its own, in place,
            # so that the transmission stays in the scope of its ${...} parameters.
            self._wrap_in_place(old, t)
        else:
            new = self._build(t, old, old)
            new.tail = old.tail
            if old.getparent() is None:
                _become(old, new)  # a bare <transmission> fragment
            else:
                old.getparent().replace(old, new)

    def _component(self, name: str, like: etree._Element, indent: str,
                   step: str) -> etree._Element:
        """A ``<ros2_control type="system">`` with its ``<hardware><plugin>``."""
        q = _qualifier(like)
        component = etree.Element(q("ros2_control"), name=name, type="system")
        hardware = etree.SubElement(component, q("hardware"))
        etree.SubElement(hardware, q("plugin")).text = self.hardware_plugin
        dialects.pretty(component, indent, step)
        return component

    def _wrap_in_place(self, old: etree._Element, t: Transmission) -> None:
        component = self._component(t.name, old, *_indentation(old))
        component.tail = old.tail
        old.getparent().replace(old, component)
        self._components = None
        for joint in t.joints:
            self._declare(component, joint)
        _append(component, self._build_inside(t, component, old))

    def _build(self, t: Transmission, sibling: etree._Element,
               old: etree._Element) -> etree._Element:
        indent, step = _indentation(sibling)
        return _with_comments(dialects.build(t, t.dialect, indent=indent, step=step,
                                             namespace=_namespace(sibling)), old, indent, step)

    def _build_inside(self, t: Transmission, parent: etree._Element,
                      old: etree._Element) -> etree._Element:
        indent, step = _child_indentation(parent)
        return _with_comments(dialects.build(t, t.dialect, indent=indent, step=step,
                                             namespace=_namespace(parent)), old, indent, step)

    def _component_for(self, t: Transmission) -> etree._Element:
        names = {j.name for j in t.joints}
        if self._components is None:
            self._components = list(self.root.iter("{*}ros2_control"))
        for element in self._components:
            if names <= self._joints_of(element):
                return element
        if self.created is None:
            self.created = self._new_component()
        for joint in t.joints:
            self._declare(self.created, joint)
        return self.created

    def _new_component(self) -> etree._Element:
        component = self._component(self.root.get("name", "robot"), self.root,
                                     *_child_indentation(self.root))
        _append(self.root, component)
        self._components = None
        return component

    def _joints_of(self, component: etree._Element) -> set[str]:
        if component not in self._declared:
            self._declared[component] = {j.get("name") for j in children(component, "joint")}
        return self._declared[component]

    def _declare(self, component: etree._Element, joint) -> None:
        declared = self._joints_of(component)
        if joint.name in declared:
            return
        declared.add(joint.name)
        q = _qualifier(component)
        element = etree.Element(q("joint"), name=joint.name)
        for name in joint.interfaces:
            etree.SubElement(element, q("command_interface"), name=name)
        for name in joint.state_interfaces:
            etree.SubElement(element, q("state_interface"), name=name)
        indent, step = _child_indentation(component)
        dialects.pretty(element, indent, step)
        anchor = self._anchor(component)
        if anchor is not None:
            element.tail = anchor.tail
            anchor.tail = "\n" + _leading_space(anchor)
            anchor.addnext(element)
        else:
            _append(component, element)
        self._last_joint[component] = element

    def _anchor(self, component: etree._Element) -> etree._Element | None:
        """The element a new joint declaration goes after: the last joint, else <hardware>."""
        if component in self._last_joint:
            return self._last_joint[component]
        declared = children(component, "joint") or children(component, "hardware")
        return declared[-1] if declared else None


def _with_comments(new: etree._Element, old: etree._Element, indent: str,
                   step: str) -> etree._Element:
    """Carry the comments of the old element: under the same joint or actuator when they
    stood there, else at the top of the transmission."""
    targets = {(local(m), m.get("name")): m for m in new if isinstance(m.tag, str)}
    for parent in [old, *children(old, "joint"), *children(old, "actuator")]:
        target = new if parent is old else targets.get((local(parent), parent.get("name")), new)
        comments = [etree.Comment(c.text) for c in parent if isinstance(c, etree._Comment)]
        for position, comment in enumerate(comments):
            if target is new:
                new.insert(position, comment)
            else:
                target.append(comment)
    if any(isinstance(c, etree._Comment) for c in new.iter()):
        dialects.pretty(new, indent, step)
    return new


def _namespace(element: etree._Element) -> str | None:
    tag = element.tag
    return tag[1:].split("}", 1)[0] if isinstance(tag, str) and tag.startswith("{") else None


def _become(old: etree._Element, new: etree._Element) -> None:
    """Give the root element ``new``'s content, keeping its place among top-level comments."""
    old.tag = new.tag
    old.attrib.clear()
    old.attrib.update(new.attrib)
    old.text = new.text
    for child in list(old):
        old.remove(child)
    old.extend(list(new))


def _qualifier(like: etree._Element) -> Callable[[str], str]:
    """Tag names in the default namespace of ``like`` (some URDFs declare one)."""
    ns = _namespace(like)
    return (lambda tag: f"{{{ns}}}{tag}") if ns else (lambda tag: tag)


def _leading_space(element: etree._Element) -> str:
    previous = element.getprevious()
    text = previous.tail if previous is not None else (
        element.getparent().text if element.getparent() is not None else "")
    text = text or ""
    return text.rsplit("\n", 1)[-1] if "\n" in text else ""


def _indentation(element: etree._Element) -> tuple[str, str]:
    indent = _leading_space(element)
    first = next((c for c in element if isinstance(c.tag, str)), None)
    step = "  "
    if first is not None:
        inner = _leading_space(first)
        if inner.startswith(indent) and len(inner) > len(indent):
            step = inner[len(indent):]
    return indent, step


def _child_indentation(parent: etree._Element) -> tuple[str, str]:
    outer, step = _indentation(parent)
    last = next((c for c in reversed(parent) if isinstance(c.tag, str)), None)
    if last is not None:
        return _leading_space(last), step
    return outer + step, step


def _remove(element: etree._Element) -> None:
    parent = element.getparent()
    previous = element.getprevious()
    if element.getnext() is None:
        # The last child's tail carries the indentation of the parent's closing tag.
        if previous is not None:
            previous.tail = element.tail
        else:
            parent.text = element.tail
    parent.remove(element)


def _insert_before(anchor: etree._Element, element: etree._Element) -> None:
    element.tail = "\n" + _leading_space(anchor)
    anchor.addprevious(element)


def _append(parent: etree._Element, element: etree._Element) -> None:
    last = next(parent.iterchildren(reversed=True), None)  # len(parent) walks every child
    if last is not None:
        element.tail = last.tail or ""
        last.tail = "\n" + _leading_space(last)
    else:
        indent, _ = _indentation(parent)
        element.tail = "\n" + indent
    parent.append(element)
