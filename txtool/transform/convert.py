"""Convert the transmissions of a whole document, keeping everything else as written.

Only transmissions whose dialect differs from the target are rewritten, and the change is
said as edits of the original bytes (:mod:`txtool.transform.edits.document`), so every byte
the conversion does not change stays as written. Where converted transmissions go is
:mod:`txtool.transform.placement.placer`. Every conversion is checked by reading the result back and
converting it back.
"""

from __future__ import annotations

import copy
from dataclasses import dataclass, field

from lxml import etree

from txtool.dialects.read import Found, enclosing_component, read_source
from txtool.dialects.translate import family, is_expression, translate
from txtool.io.xmlio import Source, serialize
from txtool.model.core import Dialect, Transmission
from txtool.model.semantics import Effective, NotLoadable, effective, listed_against_roles
from txtool.transform.check import Verdict, round_trip
from txtool.transform.edits.core import Edit
from txtool.transform.edits.document import DocumentEdits, conversion_edits, read_back
from txtool.transform.edits.tree_edits import serialization
from txtool.transform.next_steps import gazebo_plugin
from txtool.transform.placement.macros import MacroCalls
from txtool.transform.placement.placer import DEFAULT_HARDWARE_PLUGIN, Placer
from txtool.transform.reversible import Carrier

__all__ = ["DEFAULT_HARDWARE_PLUGIN", "ConvertedDocument", "convert_source"]

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
class ConvertedDocument:
    """What :func:`convert_source` made of a document: its bytes, what was lost, noted and
    warned about, and how many transmissions it found, converted or found converted already
    (the library's :class:`txtool.transform.api.Conversion` is made from it)."""

    data: bytes
    target: Dialect
    losses: list[str] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)  # to look at; nothing is lost
    converted: int = 0
    found: int = 0  # transmissions in the document
    already: int = 0  # of them, already in the target dialect
    # Which generated blocks name the placeholder plugin (the default --hardware-plugin),
    # said as a warning where losses are accepted (--allow-lossy): the result is then
    # written to be finished by hand, and that plugin must be replaced.
    placeholder: str | None = None
    # The edits of the original (its UTF-8 form if UTF-16/32) that make ``data``; None for
    # an unchanged document or a xacro expansion (written whole).
    edits: list[Edit] | None = None


def convert_source(
    source: Source, target: Dialect, *, hardware_plugin: str = DEFAULT_HARDWARE_PLUGIN,
    consume: bool = False, reversible: bool = False, check: bool = True,
    macro_calls: MacroCalls | None = None, found: list[Found] | None = None,
) -> ConvertedDocument:
    """Convert ``source``: read its transmissions, change the tree, say the change as edits
    of ``source.data`` (:mod:`.edits.document`; the result's ``edits``), make them once, and
    read the result back (:func:`.edits.document.read_back`) and judge it (:mod:`.check`). A
    xacro expansion, which has no bytes of its own, is written whole.

    With ``consume`` the caller gives up ``source.tree``: it is converted in place instead of
    in a copy (an empty document is left in its place). With ``reversible`` each transmission
    converted to ROS 2 carries its original block (:mod:`.reversible`); the originals carried
    by a document are put back whenever it goes back to ROS 1. ``check=False`` leaves out the
    judgements (the read-back, how the target loader binds each transmission, the Gazebo
    plugin), for a caller that judges the result itself (``roundtrip``).
    ``macro_calls``: where the files converted with this one call each xacro macro
    (:func:`.placement.macros.calls_in_files`; ``migrate`` gives those of its files).
    ``found``: the transmissions of ``source.tree`` as :func:`.read_source` reads them
    (``locate=False``), for a caller that has read them and gives the tree up (``consume``).
    """
    if found is not None and not consume:
        raise ValueError("found: the transmissions of a tree converted in place (consume)")
    result, tree, originals, restored, writer = _converted(
        source, target, hardware_plugin, consume, reversible, macro_calls, check, found)
    if consume:
        source.tree = etree.ElementTree(etree.Element("consumed"))
    if check and not restored:
        # Judged on the converted tree before its bytes are made: the transmissions as read
        # go before the edits and the bytes take their place.
        _take_verdict(result, round_trip(originals, tree.getroot()))
        originals = []
    expected = None
    if writer is None:  # an expansion, written whole
        result.data = serialize(tree, source.data)
    else:
        edits = writer.said()
        result.edits = edits or None
        if not restored:
            # What the edits must write, kept as its digest: the tree goes before their
            # bytes are made, the read-back parses them in its place.
            expected = serialization(tree) if check and edits else None
            del tree
        result.data = writer.text.applied(edits)
    del writer
    if not check:
        return result
    changed = result.data != source.data
    # Originals put back are written as their bytes: only a parse of the output shows what
    # it holds.
    if restored and not changed:
        _take_verdict(result, round_trip(originals, tree.getroot()))
    if changed:  # (what a parse reads: nested no deeper than its limit)
        written = read_back(result.data, source.path, expected)
        if restored:
            _take_verdict(result, round_trip(originals, written.getroot()))
    return result


def _take_verdict(result: ConvertedDocument, verdict: Verdict) -> None:
    result.losses.extend(verdict.losses)
    result.notes.extend(verdict.notes)


def _converted(source: Source, target: Dialect, hardware_plugin: str, consume: bool,
               reversible: bool, macro_calls: MacroCalls | None, check: bool,
               found: list[Found] | None
               ) -> tuple[ConvertedDocument, etree._ElementTree, list[Transmission], bool,
                          DocumentEdits | None]:
    """:func:`convert_source` up to the bytes: the result, the converted tree, the
    transmissions as read, whether originals are put back as their bytes, and the writer
    that says the change as edits (None for an expansion, written whole). What the conversion
    held besides (the placer, the elements replaced) is let go at the return."""
    carry = Carrier(source, target, reversible)
    tree = source.tree if consume else copy.deepcopy(source.tree)
    root = tree.getroot()
    if found is None:
        found = read_source(Source(source.path, source.data, tree), locate=False)
    elements = [f.element for f in found]
    writer = None if source.expanded else conversion_edits(
        source.path, source.data, root, elements, target)
    result = ConvertedDocument(data=b"", target=target, found=len(elements))
    placer = Placer(root, hardware_plugin, macro_calls=macro_calls)
    placer.after = carry.after_block
    originals = _place_each(found, tree, target, result, placer, carry, check)
    del found
    placer.finish()
    restored = carry.after(tree, placer.built)
    result.notes.extend(placer.notes)
    result.losses.extend(placer.losses)
    result.warnings.extend(placer.warnings)
    if check and target != "ros1" and result.converted:
        result.warnings.extend(gazebo_plugin(root))
    result.placeholder = placer.placeholder
    if writer is not None:
        for node, block in restored:
            writer.substitute(node, block)
    result.notes.extend(carry.notes)
    return result, tree, originals, bool(restored), writer


def _place_each(found: list[Found], tree: etree._ElementTree, target: Dialect,
                result: ConvertedDocument, placer: Placer, carry: Carrier, check: bool
                ) -> list[Transmission]:
    """Convert and place each transmission: the transmissions as read, in order."""
    originals = []
    for each in found:
        t = each.transmission
        originals.append(t)
        if t.dialect == target:
            result.already += 1
        if _convert_one(each, tree, target, result, placer, carry, check):
            result.converted += 1
    return originals


def _convert_one(found: Found, tree: etree._ElementTree, target: Dialect,
                 result: ConvertedDocument, placer: Placer, carry: Carrier, check: bool
                 ) -> bool:
    """Convert one transmission (whether it is converted: those already in the target
    dialect, and some others, are not)."""
    t = found.transmission
    if t.dialect == target or t.kind == "other" and family(t.dialect) == family(target):
        return False
    if target == "ros1" and enclosing_component(found.element) is tree.getroot():
        result.losses.append(
            f"transmission '{t.name}': a bare <ros2_control> fragment has no place for a "
            "top-level ROS 1 transmission; convert the robot description that holds it"
        )
        return False
    if t.kind == "other":
        result.warnings.append(
            f"transmission '{t.name}': custom type '{t.type}' is not converted (txtool "
            f"knows only the standard types); left as written, in {family(t.dialect)} form"
        )
        return False
    translation = translate(t, target)
    result.losses.extend(translation.losses)
    result.notes.extend(translation.notes)
    result.warnings.extend(translation.warnings)
    carried = _other_children(found.element, t, target, result)
    if check:
        _behaviour(t, translation.transmission, result)
    carry.before(found)
    return placer.place(found.element, translation.transmission, carried, t.dialect)


def _other_children(
    element: etree._Element, t: Transmission, target: Dialect, result: ConvertedDocument,
) -> dict[tuple[str, str | None], list[etree._Element]]:
    """Children that neither dialect reads are carried as written (both loaders skip elements
    they do not know); one that the target loader would read (its own spelling, written in the
    other dialect) is dropped: carrying it would change what the target loads."""
    known = KNOWN_CHILDREN[family(t.dialect)]
    theirs = KNOWN_CHILDREN[family(target)]
    carried: dict[tuple[str, str | None], list[etree._Element]] = {}
    members: dict[str, list[etree._Element]] = {"joint": [], "actuator": []}

    def look(kind: str, parent: etree._Element) -> None:
        ours = known[kind]
        for child in parent:
            tag = child.tag
            if tag.__class__ is not str:
                continue  # a comment or processing instruction
            name = tag.rpartition("}")[2]
            if name in ours:
                if kind == "transmission" and name in members:
                    members[name].append(child)
                continue  # a child its own dialect reads
            owner = f"{kind} '{parent.get('name', '')}'"
            if name in theirs[kind]:
                result.losses.append(f"{owner}: <{name}> is not read in {family(t.dialect)} "
                                     f"but would be in {target}; dropped")
                continue
            carried.setdefault((kind, parent.get("name")), []).append(child)
            result.notes.append(f"{owner}: <{name}> is read by neither loader; carried as "
                                "written")

    look("transmission", element)  # (and its members found on the way, looked at after it)
    for kind in ("joint", "actuator"):
        for member in members[kind]:
            look(kind, member)
    return carried


def _behaviour(before: Transmission, after: Transmission, result: ConvertedDocument) -> None:
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
    result.losses.append(
        f"transmission '{before.name}': behaves differently under {new.loader}: "
        f"{_binding_difference(before, old, new)}"
    )


def _binding_difference(before: Transmission, old: Effective, new: Effective) -> str:
    """Why the target binds other values: the source's XML order, or names against roles."""
    loader = "ros_control" if old.loader == "ros1" else "ros2_control"
    moved = [f"'{name}' would take the values {loader} applies to '{source}'"
             for name, source in _sources(old, new)]
    detail = "; ".join(moved) or "the loaded reductions or offsets differ"
    if old.loader == "ros1" and listed_against_roles(before):
        return (f"{detail}. ros_control takes the values by <role> but the data in XML "
                "order, and this transmission lists its members against their roles (TX404): "
                "list them in role order first (this changes what ros_control does: check it "
                "on the robot), then convert again; --allow-lossy writes it as it is")
    if new.loader == "ros2":
        return (f"{detail} (ros2_control orders handles by name, not by role; see TX401). "
                "To convert it, rename the members so that the joint1 name sorts before the "
                "joint2 name (likewise actuator1 before actuator2), then convert again; "
                "--allow-lossy writes it as it is")
    return detail


def _sources(old: Effective, new: Effective) -> list[tuple[str, str]]:
    """Members whose index (and so whose values) differ between the two bindings."""
    changed = []
    for names_old, names_new in ((old.joints, new.joints), (old.actuators, new.actuators)):
        for i, name in enumerate(names_new):
            if i < len(names_old) and names_old[i] != name:
                changed.append((name, names_old[i]))
    return changed


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
