"""What each loader binds from a transmission (``txtool show --effective`` and its JSON).

The parameters are :func:`txtool.model.semantics.effective`'s; this module adds where each
came from and which joint's and actuator's data the maths maps at each index:

* ros_control (ROS 1) indexes parameters by ``<role>`` (ros-controls/ros_control
  transmission_interface/src/four_bar_linkage_transmission_loader.cpp:49 @17b626a, likewise
  the differential loader) but fills the data vectors in XML order: ``jnt_state_data.position[i]``
  is ``transmission_info.joints_[i]`` (transmission_interface/src/
  joint_state_interface_provider.cpp:132 @133d768; actuators through ``getActuatorHandles(
  transmission_info.actuators_)`` in the same file). When the XML order differs from the role
  order, a joint is mapped with the other joint's parameters.
* ros2_control (ROS 2) reads coupled parameters in XML order (ros-controls/ros2_control
  transmission_interface/src/four_bar_linkage_transmission_loader.cpp:34-41 @7714d16) and
  orders the handles by name: ``get_names`` collects them in a ``std::set``
  (transmission_interface/include/transmission_interface/accessor.hpp:43-45 @433ae5d), which
  ``configure`` of the differential and four-bar transmissions uses for every interface.
* ros2_control's parser appends an actuator ``actuator1`` (reduction 1, offset 0) to every
  transmission of a ``type="actuator"`` component, and throws unless that transmission has
  exactly one joint (hardware_interface/src/component_parser.cpp:546-558 @157446a); in any
  component a transmission joint must be one of the component's joints (same file, :519-531).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

from lxml import etree

from txtool.dialects.read import Found, enclosing_component
from txtool.model.core import TYPE_PREFIX, Member, Number, Transmission
from txtool.model.distro import Distro, numbers_of
from txtool.model.numbers import C_SPACE, format_float, parse_ros2
from txtool.model.robot import Component, children, component_of
from txtool.model.semantics import (
    ROLES_ACTUATOR,
    ROLES_JOINT,
    Effective,
    NotLoadable,
    by_role,
    effective,
    loader_of,
    ros2_values_differ,
)
from txtool.model.show_document import Binding, Field, Slot

ADDED_ACTUATOR = "actuator1"
PARSER_REFUSES = "ros2_control's parser refuses the component: "
# The ROS 2 builds that read numbers differently: Humble's istringstream, Jazzy's from_chars
# (Kilted and Rolling read as Jazzy).
_ROS2_BUILDS = ((Distro.HUMBLE, "Humble"), (Distro.JAZZY, "Jazzy, Kilted and Rolling"))


def bindings_of(found: Sequence[Found], distro: Distro | None = None) -> list[Binding]:
    """The binding of each transmission read from ``found`` (its component matters).

    ``distro`` picks the ROS 2 build whose number reading applies; None: every ROS 2
    distribution may read the file, and where they read a number differently the binding is
    Jazzy's with a note giving Humble's values.
    """
    components: dict[object, Component] = {}  # each <ros2_control> read once
    result = []
    for item in found:
        element = enclosing_component(item.element)
        component = None
        if element is not None:
            component = components.get(element)
            if component is None:
                component = components[element] = component_of(element)
        result.append(_per_distro(item, component, distro))
    return result


def _per_distro(item: Found, component: Component | None, distro: Distro | None) -> Binding:
    t = item.transmission
    if distro is not None or not ros2_values_differ(t):
        return binding(t, component, distro, item.element)
    bound = {d: binding(t, component, d, item.element) for d, _ in _ROS2_BUILDS}
    newest = bound[Distro.JAZZY]
    if bound[Distro.HUMBLE].slots == newest.slots:
        return newest
    notes = [f"{label} {_values(bound[d], label)}" for d, label in _ROS2_BUILDS]
    import dataclasses

    return dataclasses.replace(newest, notes=(
        "ROS 2 distributions read the numbers differently: " + "; ".join(notes),
        *newest.notes))


def _values(b: Binding, label: str) -> str:
    verb = "bind" if " and " in label else "binds"
    if not b.loadable:
        return f"{'do' if verb == 'bind' else 'does'} not load it ({b.reason})"
    return f"{verb} " + ", ".join(
        f"#{s.index} joint reduction {_value(s, 'joint_reduction', s.joint_reduction)} offset "
        f"{_value(s, 'joint_offset', s.joint_offset)}"
        + ("" if "actuator_reduction" in s.not_read
           else f" actuator reduction {_value(s, 'actuator_reduction', s.actuator_reduction)}")
        for s in b.slots)


def binding(t: Transmission, component: Component | None = None, distro: Distro | None = None,
            element: etree._Element | None = None) -> Binding:
    """What ``t``'s loader binds; ``component`` is its enclosing ``<ros2_control>``, if any,
    ``element`` the ``<transmission>`` it was read from (what the parser requires of its
    attributes), ``distro`` as in :func:`bindings_of`."""
    loader = loader_of(t)
    component_type = (component.type.strip(C_SPACE)
                      if loader == "ros2" and component is not None else None)
    added = (ADDED_ACTUATOR,) if component_type == "actuator" else ()
    refused = _unbound(t, component if loader == "ros2" else None,
                       element if loader == "ros2" else None)
    if refused is not None:
        loadable, reason = refused
        return Binding(loader=loader, loadable=loadable, reason=reason,
                       component_type=component_type,
                       added_actuators=() if reason.startswith(PARSER_REFUSES) else added)
    try:
        eff = effective(t, distro, added)
    except NotLoadable as exc:
        return Binding(loader=loader, loadable=False, reason=str(exc),
                       component_type=component_type, added_actuators=added)
    slots = _ros1_slots(t, eff) if loader == "ros1" else _ros2_slots(t, eff, distro)
    coupled = t.kind != "simple"
    return Binding(
        loader=loader,
        loadable=True,
        parameter_order=("role" if loader == "ros1" else "xml") if coupled else None,
        data_order=("xml" if loader == "ros1" else "name") if coupled else None,
        slots=slots,
        component_type=component_type,
        added_actuators=added,
        notes=tuple(_notes(t, slots, loader, component is not None, added)),
    )


def _unbound(t: Transmission, component: Component | None,
             element: etree._Element | None) -> tuple[bool | None, str] | None:
    """(loadable, reason) for what no standard loader binds: refused (False) or unknown."""
    refusal = _parser_refusal(t, component, element)
    if refusal:
        return False, refusal
    if t.kind != "other":
        return None
    if t.type.strip().startswith(TYPE_PREFIX):
        # Both loaders resolve the type through pluginlib, whose transmission_interface/
        # classes are the three standard ones (ros2_control_plugins.xml, ros_control_plugins.xml).
        return False, (f"no transmission plugin is named '{t.type.strip()}' "
                       "(transmission_interface has SimpleTransmission, "
                       "DifferentialTransmission and FourBarLinkageTransmission)")
    return None, (f"type '{t.type}' is not a standard transmission: a plugin, if one is "
                  "installed, decides what it binds")


def _parser_refusal(t: Transmission, component: Component | None,
                    element: etree._Element | None) -> str | None:
    if component is None:
        return None
    written = _written_refusal(element) if element is not None else None
    if written:
        return PARSER_REFUSES + written
    declared: set[str] | None = None
    for joint in t.joints:
        if component.joint(joint.name) is not None:
            continue
        if declared is None:  # the parser compares stripped names
            declared = {j.name.strip(C_SPACE) for j in component.joints}
        if joint.name not in declared:
            return (f"{PARSER_REFUSES}joint '{joint.name}' is not declared in "
                    f"<ros2_control name=\"{component.name}\">")
    if component.type.strip(C_SPACE) == "actuator" and len(t.joints) != 1:
        return (f"{PARSER_REFUSES}a transmission of an actuator component must have exactly "
                f"one joint, found {len(t.joints)}")
    return None


def _written_refusal(element: etree._Element) -> str | None:
    """What ros2_control's parser throws on in the ``<transmission>`` itself
    (component_parser.cpp parse_transmission_from_xml :589, parse_transmission_joint_from_xml
    :553 and parse_transmission_actuator_from_xml :568): no name, no ``<plugin>``, a member
    without a name or a ``role`` attribute, a ``read_only`` other than true or false (any
    case; parse_bool in lexical_casts.cpp)."""
    if element.get("name") is None:
        return "a <transmission> has no name attribute"
    if not children(element, "plugin"):
        return f"transmission '{element.get('name')}' has no <plugin>"
    for member in element:
        tag = member.tag if isinstance(member.tag, str) else ""
        if tag not in ("joint", "actuator"):
            continue
        for attribute in ("name", "role"):
            if member.get(attribute) is None:
                return f"a <{tag}> of transmission '{element.get('name')}' has no {attribute}"
        read_only = member.get("read_only")
        if read_only is not None and read_only.strip(C_SPACE).lower() not in ("true", "false"):
            return (f"<{tag} name=\"{member.get('name')}\"> read_only=\"{read_only}\" is not "
                    "true or false")
    return None


def _defaults(loader: str, joint: Member, actuator: Member | None,
              not_read: tuple[Field, ...], distro: Distro | None = None) -> tuple[Field, ...]:
    """Fields whose value is the loader's fallback rather than the document's number
    (ros2_control: absent, or a text ``distro``'s build does not read)."""
    numbers: dict[Field, Number | None] = {"joint_reduction": joint.mechanical_reduction,
                                           "joint_offset": joint.offset}
    if actuator is not None:
        numbers["actuator_reduction"] = actuator.mechanical_reduction
    return tuple(
        field for field, number in numbers.items()
        if field not in not_read and (number is None or (loader == "ros2" and _unread(number,
                                                                                     distro)))
    )


def _unread(number: Number, distro: Distro | None) -> bool:
    if distro is None:
        return number.value is None
    return parse_ros2(number.text, numbers_of(distro)) is None


def _by_name(members: Sequence[Member], name: str) -> Member:
    return next(m for m in members if m.name == name)


def _ros1_slots(t: Transmission, eff: Effective) -> tuple[Slot, ...]:
    # ros_control's simple transmission reads the actuator's reduction only.
    not_read: tuple[Field, ...] = ("joint_reduction",) if t.kind == "simple" else ()
    joints, actuators = t.joints, t.actuators
    if t.kind != "simple":  # parameters by <role>, data (t.joints[i]) in XML order
        joints = tuple(by_role(t.joints, ROLES_JOINT, "joint"))
        actuators = tuple(by_role(t.actuators, ROLES_ACTUATOR, "actuator"))
    slots = []
    for i in range(len(eff.joints)):
        joint, actuator = joints[i], actuators[i]
        slots.append(Slot(
            index=i,
            joint_parameters_of=joint.name,
            joint_reduction=eff.joint_reduction[i],
            joint_offset=eff.joint_offset[i],
            actuator_parameters_of=actuator.name,
            actuator_reduction=eff.actuator_reduction[i],
            joint=t.joints[i].name,
            actuator=t.actuators[i].name,
            defaults=_defaults("ros1", joint, actuator, not_read),
            not_read=not_read,
        ))
    return tuple(slots)


def _ros2_slots(t: Transmission, eff: Effective, distro: Distro | None) -> tuple[Slot, ...]:
    # ros2_control's simple transmission reads the joint's reduction only.
    not_read: tuple[Field, ...] = ("actuator_reduction",) if t.kind == "simple" else ()
    slots = []
    for i in range(len(eff.joints)):
        joint = t.joints[i]  # the loader's joints.at(i)
        actuator = t.actuators[i] if i < len(t.actuators) else None
        slots.append(Slot(
            index=i,
            joint_parameters_of=joint.name,
            joint_reduction=eff.joint_reduction[i],
            joint_offset=eff.joint_offset[i],
            actuator_parameters_of=actuator.name if actuator else eff.actuators[i],
            actuator_reduction=eff.actuator_reduction[i],
            joint=eff.joints[i],
            actuator=eff.actuators[i],
            defaults=_defaults("ros2", joint, actuator, not_read, distro),
            not_read=not_read,
        ))
    return tuple(slots)


def _notes(t: Transmission, slots: tuple[Slot, ...], loader: str, in_component: bool,
           added: tuple[str, ...]) -> list[str]:
    why = ("ros_control orders parameters by <role> and data by XML order" if loader == "ros1"
           else "ros2_control takes parameters in XML order and orders handles by name")
    notes = []
    for slot in slots:
        for noun, data, source in (("joint", slot.joint, slot.joint_parameters_of),
                                   ("actuator", slot.actuator, slot.actuator_parameters_of)):
            if data != source:
                notes.append(f"{noun} '{data}' is mapped with the parameters written on "
                             f"'{source}' ({why})")
    notes.extend(_unparsed(t, slots) if loader == "ros2" else [])
    notes.extend(_ignored(t, loader))
    if added:
        notes.append(f"ros2_control's parser appends actuator '{added[0]}' (reduction 1, "
                     "offset 0) to a transmission of an actuator component")
    elif loader == "ros2" and not t.actuators:
        notes.append(f"no <actuator>: the hardware plugin names the actuator handle "
                     f"('{slots[0].actuator}' stands in here)")
    if loader == "ros2" and not in_component:
        notes.append("not inside a <ros2_control> element here: ros2_control reads it only "
                     "where it ends up inside one")
    return notes


def _unparsed(t: Transmission, slots: tuple[Slot, ...]) -> list[str]:
    """ros2_control's silent defaults for text that is not a number, on the fields it reads."""
    notes = []
    for slot in slots:
        joint = _by_name(t.joints, slot.joint_parameters_of)
        actuator = next((a for a in t.actuators if a.name == slot.actuator_parameters_of), None)
        for field, member, tag, number, default in (
            ("joint_reduction", joint, "mechanical_reduction", joint.mechanical_reduction, 1),
            ("joint_offset", joint, "offset", joint.offset, 0),
            ("actuator_reduction", actuator, "mechanical_reduction",
             actuator.mechanical_reduction if actuator else None, 1),
        ):
            if field in slot.defaults and member is not None and number is not None:
                notes.append(f"'{member.name}' {tag} {(number.text or '').strip()!r} is not a "
                             f"number: ros2_control silently uses {default}")
    return notes


def _ignored(t: Transmission, loader: str) -> list[str]:
    if t.kind != "simple":
        return []
    if loader == "ros1":
        written = [j for j in t.joints[:1] if j.mechanical_reduction is not None]
        return [f"joint '{j.name}' reduction is ignored: ros_control's simple transmission "
                "reads the actuator's" for j in written]
    written = [a for a in t.actuators[:1] if a.mechanical_reduction is not None]
    return [f"actuator '{a.name}' reduction is ignored: ros2_control's simple transmission "
            "reads the joint's" for a in written]


def number(value: float | None) -> str:
    return "-" if value is None else format_float(value)


LOADERS = {"ros1": "ros_control", "ros2": "ros2_control"}
ORDERS = {"role": "parameters by <role>", "xml": "parameters in XML order"}
DATA = {"xml": "data in XML order", "name": "handles sorted by name"}
WIDTH = 100


def shown_json(transmissions: Sequence[Transmission], bindings: Sequence[Binding]) -> list:
    """Each transmission as written plus its ``effective`` binding, as JSON-ready data."""
    import dataclasses

    from txtool.model.core import dump
    from txtool.model.show_document import ShownTransmission

    return [
        dump(ShownTransmission(**{f.name: getattr(t, f.name) for f in dataclasses.fields(t)},
                               effective=b))
        for t, b in zip(transmissions, bindings, strict=True)
    ]


def effective_text(path: str, transmissions: Sequence[Transmission],
                   bindings: Sequence[Binding], unread: Sequence[str] = (),
                   verdicts: Mapping[str, Sequence[str]] | None = None) -> str:
    """The effective view as plain text, at most 100 columns wide. ``unread``: the names of
    the transmissions none of the file's readers reads (shown as what their dialect's loader
    would bind, and said so)."""
    import io

    from rich.console import Console

    from txtool.io.printable import printable

    buffer = io.StringIO()
    out = Console(file=buffer, width=WIDTH, color_system=None, highlight=False,
                  emoji=False)
    out.print(printable(path), soft_wrap=True, markup=False)
    out.print(f"{len(transmissions)} transmission(s), as their loaders bind them", markup=False)
    for t, b in zip(transmissions, bindings, strict=True):
        out.print()
        for line in _block(t, b, t.name in unread, (verdicts or {}).get(t.name, ())):
            if isinstance(line, str):  # names from the file: one line each, no escapes
                out.print(printable(line), soft_wrap=True, markup=False)
            else:
                out.print(line)
    # Padding fills lines to the console's width; the text view needs no trailing blanks.
    return "".join(line.rstrip() + "\n" for line in buffer.getvalue().splitlines())


def _block(t: Transmission, b: Binding, unread: bool = False,
           verdicts: Sequence[str] = ()) -> list:
    import textwrap

    from rich.padding import Padding

    where = f" (line {t.location.line})" if t.location and t.location.line else ""
    kind = t.type.removeprefix("transmission_interface/") or "(no type)"
    lines: list = [_fit(f"{t.name}{where}: {kind}")]
    how = f"read by {LOADERS[b.loader]}"
    refused = [v.split(":", 1)[0].split(" ", 1)[1] for v in verdicts if v.startswith("error ")]
    if refused:  # read, then refused or changed: as validate says (its errors' promise)
        how += f", which refuses it or reads it other than written ({', '.join(refused)})"
    if unread:
        how = (f"read by none of this file's readers (written for {LOADERS[b.loader]}; "
               "below, what it would bind)")
    if b.component_type:
        how += f" in {_article(b.component_type)} {b.component_type} component"
    if b.loadable:
        orders = [ORDERS[b.parameter_order]] if b.parameter_order else []
        orders += [DATA[b.data_order]] if b.data_order else []
        how = "; ".join([how, ", ".join(orders)]) if orders else how
    elif b.loadable is None:
        how += f"; {b.reason}"
    else:
        how += f"; not loaded: {b.reason}"
    lines += textwrap.wrap(how, WIDTH, initial_indent="  ", subsequent_indent="    ")
    if b.loadable:
        lines.append(Padding(_table(b), (0, 0, 0, 2)))
    for note in b.notes:
        lines += textwrap.wrap(note, WIDTH, initial_indent="  note: ", subsequent_indent="    ")
    for verdict in verdicts:
        lines += textwrap.wrap(verdict, WIDTH, initial_indent="  validate: ",
                               subsequent_indent="    ")
    return lines


def _article(word: str) -> str:
    return "an" if word[:1].lower() in "aeiou" else "a"


def _fit(text: str) -> str:
    return text if len(text) <= WIDTH else text[: WIDTH - 1] + "…"


def _table(b: Binding):
    from rich.box import SIMPLE_HEAD
    from rich.table import Table

    table = Table(box=SIMPLE_HEAD, padding=(0, 1), pad_edge=False, show_edge=False,
                  width=None)
    for column, justify in (("#", "right"), ("joint", "left"), ("reduction", "right"),
                            ("offset", "right"), ("actuator", "left"), ("reduction", "right")):
        # Names wrap rather than lose their end to an ellipsis.
        table.add_column(column, justify=justify, overflow="fold")  # type: ignore[arg-type]
    for s in b.slots:
        table.add_row(
            str(s.index),
            _member(s.joint, s.joint_parameters_of),
            _value(s, "joint_reduction", s.joint_reduction),
            _value(s, "joint_offset", s.joint_offset),
            _member(s.actuator, s.actuator_parameters_of),
            _value(s, "actuator_reduction", s.actuator_reduction),
        )
    return table


def _member(data: str, source: str):
    from rich.text import Text

    from txtool.io.printable import printable

    return Text(printable(data if data == source else f"{data} (values of {source})"))


def _value(slot: Slot, field: Field, value: float | None) -> str:
    if field in slot.not_read:
        return "(not read)"
    return f"{number(value)} (default)" if field in slot.defaults else number(value)
