"""Convert the transmissions of a whole document, keeping everything else as written.

Only transmissions whose dialect differs from the target are rewritten, and the change is
said as edits of the original bytes (:mod:`txtool.transform.edits.conversion_edits`), so every byte
the conversion does not change stays as written. Where converted transmissions go is
:mod:`txtool.transform.placement.placer`. Every conversion is checked by reading the result back and
converting it back.
"""

from __future__ import annotations

import copy
from collections import Counter
from collections.abc import Callable, Hashable
from dataclasses import dataclass, field
from functools import cache
from operator import attrgetter
from typing import Any

from lxml import etree

from txtool.dialects.read import (
    Found,
    enclosing_component,
    read_transmission,
    transmission_elements,
    transmissions_with_those_at_root,
)
from txtool.dialects.translate import family, is_expression, translate
from txtool.io.encodings import SCANNABLE, detect_encoding
from txtool.io.xmlio import MAX_DEPTH, InputError, Source, XMLSyntax, local, parse_bytes, serialize
from txtool.model.core import Dialect, Transmission
from txtool.model.robot import children
from txtool.model.semantics import Effective, NotLoadable, effective, listed_against_roles
from txtool.transform.edits.conversion_edits import ConversionEdits, Expected, check_written
from txtool.transform.edits.core import Edit
from txtool.transform.edits.spans import NotIndexed
from txtool.transform.next_steps import gazebo_plugin
from txtool.transform.placement.macros import MacroCalls
from txtool.transform.placement.placer import DEFAULT_HARDWARE_PLUGIN, Placer
from txtool.transform.repeated.block_text import Written, fill, read_back
from txtool.transform.repeated.cycle_collector import paused
from txtool.transform.repeated.nameless_shapes import shape
from txtool.transform.repeated.renamings import Follower, Memo, Record, Renaming
from txtool.transform.reversible import Carrier
from txtool.views.tables import FIELDS, view

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
    # said as a warning wherever the result is written: that plugin must be replaced.
    placeholder: str | None = None
    # The edits of the original (its UTF-8 form if UTF-16/32) that make ``data``; None for
    # an unchanged document or a xacro expansion (written whole).
    edits: list[Edit] | None = None


@paused
def convert_source(
    source: Source, target: Dialect, *, hardware_plugin: str = DEFAULT_HARDWARE_PLUGIN,
    consume: bool = False, reversible: bool = False, check: bool = True, repeats: bool = True,
    macro_calls: MacroCalls | None = None,
) -> ConvertedDocument:
    """Convert ``source``: the change is said as edits of ``source.data``
    (:mod:`.edits.conversion_edits`; the result's ``edits``), unless ``source`` is a xacro
    expansion, which is written whole.

    With ``consume`` the caller gives up ``source.tree``: it is converted in place instead of
    in a copy, and released (an empty document is left in its place) before the result is
    read back, so a large document needs one tree at a time. With ``reversible`` each
    transmission converted to ROS 2 carries its original block (:mod:`.reversible`); the
    originals carried by a document are put back whenever it goes back to ROS 1.
    ``check=False`` leaves out the read-back check, for a caller that judges the result
    itself (``roundtrip``).

    ``repeats`` is the one switch of the fast path for robots that repeat a transmission
    under other names: each is converted once and copied (:mod:`.repeated.renamings`,
    :mod:`.repeated.templates`), and the block generated for the document is written as text
    (:mod:`.repeated.block_text`). Off, every transmission is converted in full; the bytes and
    messages are the same either way.

    ``macro_calls``: where the files converted with this one call each xacro macro
    (:func:`.placement.macros.calls_in_files`; ``migrate`` gives those of its files).
    """
    try:
        result, expected = _convert_document(source, target, hardware_plugin, consume,
                                             reversible, check, repeats, macro_calls,
                                             near=True)
    except NotIndexed:
        # The placer changed the root's children next to one the index passed over: again,
        # with every child of the root indexed (a conversion in place consumed the tree).
        if consume:
            source.tree = parse_bytes(source.data, source.path, limit=None)
        result, expected = _convert_document(source, target, hardware_plugin, consume,
                                             reversible, check, repeats, macro_calls,
                                             near=False)
    if expected is not None:  # the converted tree, and nothing else of the conversion
        assert result.edits is not None
        check_written(result.data, result.edits, source.path, expected)
    return result


def _convert_document(source: Source, target: Dialect, hardware_plugin: str, consume: bool,
                      reversible: bool, check: bool, repeats: bool,
                      macro_calls: MacroCalls | None, *, near: bool
                      ) -> tuple[ConvertedDocument, Expected | None]:
    """:func:`convert_source`, and what the written bytes must read as (checked by the
    caller); ``near``: as :class:`.ConversionEdits` takes it."""
    carry = Carrier(source, target, reversible)
    # Back to ROS 1 (each element may carry its original) and --reversible convert in full.
    memo = Memo() if repeats and not carry.reversible and target != "ros1" else None
    tree = source.tree if consume else copy.deepcopy(source.tree)
    elements, at_root = transmissions_with_those_at_root(
        tree.getroot(), None if source.expanded else source.data)
    # (a transmission at the root stands far from the limit: none is asked for its depth)
    deep = len(at_root) < len(elements) and _near_depth_limit(elements, tree.getroot())
    writer = None if source.expanded else ConversionEdits(
        source.path, source.data, tree.getroot(), elements, at_root, target, near=near)
    result = ConvertedDocument(data=b"", target=target, found=len(elements))
    placer = Placer(tree.getroot(), hardware_plugin, components=source.expanded or (
        detect_encoding(source.data).codec not in SCANNABLE or b"ros2_control" in source.data),
        macro_calls=macro_calls)
    placer.after = carry.after_block
    items, olds = _place_each(elements, tree, target, result, placer, carry, memo,
                              all_top=len(at_root) == len(elements))
    names = Counter(map(attrgetter("name"), items))
    if check and memo is not None and not detect_encoding(source.data).wide:
        # What the check reads back of a written transmission is paired with it by its name.
        placer.crowded = set() if len(names) == len(items) else {
            item.element if isinstance(item, Follower) else olds[id(item)]
            for item in items if names[item.name] > 1}
    placer.finish()
    restored = carry.after(tree, placer.built)
    if writer is not None:
        for node, block in restored:
            writer.substitute(node, block)
    result.notes.extend(placer.notes)
    result.losses.extend(placer.losses)
    result.warnings.extend(placer.warnings)
    if target != "ros1" and result.converted:
        result.warnings.extend(gazebo_plugin(tree.getroot()))
    result.placeholder = placer.placeholder
    built_for = placer.built.get
    for item in items:
        if item.__class__ is Follower:
            item.built, item.element = built_for(item.element), None  # type: ignore[union-attr]
    del built_for  # it holds the replaced elements too
    virtual = {key: built for key, old in olds.items()
               if isinstance(built := placer.built.get(old), Written)}
    del elements, at_root, olds  # the replaced elements are freed before the document is written
    placer.release()
    if writer is not None:
        writer.change.let_go()
    _write(source, tree, writer, placer, result)
    if placer.unwritten:  # parsed into the tree after all
        for item in items:
            if isinstance(item, Follower) and item.built in placer.unwritten:
                item.built = placer.unwritten[item.built]  # type: ignore[index]
        virtual = {}
    alone, in_tree = placer.alone, True
    del placer
    result.notes.extend(carry.notes)
    if deep:
        _reads_back(result.data, source.path)
    expected = writer.expect(tree, result.edits) if (
        writer is not None and not restored and result.edits) else None
    if consume:
        source.tree = etree.ElementTree(etree.Element("consumed"))
    if check:
        if restored and result.data != source.data:
            # Originals written as their bytes: only a parse of the output shows what it holds.
            del tree
            tree = parse_bytes(result.data, source.path, limit=None)
            alone, in_tree = set(), False
        _check(Source(source.path, result.data, tree), result, items, alone, names, virtual,
               in_tree)
    return result, expected


def _place_each(elements: list[etree._Element], tree: etree._ElementTree, target: Dialect,
                result: ConvertedDocument, placer: Placer, carry: Carrier, memo: Memo | None,
                *, all_top: bool) -> tuple[list[Transmission | Follower],
                                           dict[int, etree._Element]]:
    """Read, key, convert and place each transmission: what each is (a follower of a
    transmission converted before, else as read) in order, and the element of each not a
    follower, by the id of what it is. ``all_top``: every transmission is a child of the
    root."""
    root = tree.getroot()
    top = local(root) != "ros2_control"  # a child of the root is in no <ros2_control>
    all_top = all_top and top
    # The declarations read (freed at the return, while their elements are in the tree: lxml
    # frees an element of a removed subtree, a generated block replaced, by scanning all of
    # that subtree).
    components: dict[etree._Element, Any] = {}
    items: list[Transmission | Follower] = []
    olds: dict[int, etree._Element] = {}
    for element in elements:
        keyed = None
        if memo is not None and (all_top or element.getparent() is root and top
                                 or enclosing_component(element) is None):
            keyed = memo.keyed(element)
        if keyed.__class__ is Follower:
            assert isinstance(keyed, Follower)
            items.append(keyed)
            if placer.place_follower(element, keyed, keyed.record.original.dialect):
                result.converted += 1
            continue
        renaming = keyed if isinstance(keyed, Renaming) else None
        t = read_transmission(element, None, components)
        items.append(t)
        olds[id(t)] = element
        if t.dialect == target:
            result.already += 1
        said = len(result.losses) + len(result.notes) + len(result.warnings)
        if _convert_one(Found(t, element), tree, target, result, placer, carry, memo, renaming,
                        said):
            result.converted += 1
    return items, olds


def _write(source: Source, tree: etree._ElementTree, writer: ConversionEdits | None,
           placer: Placer, result: ConvertedDocument) -> None:
    """Write the converted document into ``result``: as edits of the original, or, for a
    xacro expansion (which has no bytes of its own), serialized. The block the placer left
    as text (:attr:`Placer.written`) is filled in, or parsed into the tree where it cannot
    be."""
    if writer is None:
        data = serialize(tree, source.data)
        if placer.written is not None:
            filled = fill(data, *placer.written)
            if filled is not None:
                result.data = filled
                return
            placer.unwrite()
            data = serialize(tree, source.data)
        result.data = data
        return
    marker = placer.written
    edits = writer.edits(*marker) if marker is not None else writer.edits()
    if edits is None:
        placer.unwrite()
        edits = writer.edits()
        assert edits is not None
    else:  # the block's pieces are in its edit: freed before the document is joined
        placer.written = marker = None
    result.edits = edits or None
    result.data = writer.applied(edits) if edits else source.data


# What replaces a transmission nests at most this many levels below where it stood
# (<ros2_control>, <transmission>, <joint>, <role> or <mechanical_reduction>).
_WRITTEN_DEPTH = 4


def _near_depth_limit(elements: list[etree._Element], root: etree._Element) -> bool:
    """Whether a transmission stands so deep that what is written in its place may nest
    deeper than a parse reads (:data:`~txtool.io.xmlio.MAX_DEPTH`)."""
    for element in elements:
        depth, parent = 1, element.getparent()
        if parent is root:
            continue
        while parent is not None:
            depth += 1
            parent = parent.getparent()
        if depth + _WRITTEN_DEPTH > MAX_DEPTH:
            return True
    return False


def _reads_back(data: bytes, path: str) -> None:
    """Refuse a converted document that txtool (or any reader with libxml2's limits) could
    not read back: it nests elements too deep."""
    try:
        parse_bytes(data, path, limit=None)
    except XMLSyntax as exc:
        raise InputError(
            f"{path}: cannot convert: the result could not be read back; its line {exc.line}: "
            f"{exc.reason}") from None


def _convert_one(found: Found, tree: etree._ElementTree, target: Dialect, result: ConvertedDocument,
                 placer: Placer, carry: Carrier, memo: Memo | None, renaming: Renaming | None,
                 said: int) -> bool:
    """Convert one transmission in full (whether it is converted: those already in the
    target dialect, and some others, are not); ``said``: how many messages came before."""
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
    _behaviour(t, translation.transmission, result)
    carry.before(found)
    clean = not carried and said == len(result.losses) + len(result.notes) + len(
        result.warnings)
    if memo is not None and memo.learn(renaming, t, translation.transmission, clean) is None:
        renaming = None
    return placer.place(found.element, translation.transmission, carried, renaming, t.dialect)


def _other_children(
    element: etree._Element, t: Transmission, target: Dialect, result: ConvertedDocument,
) -> dict[tuple[str, str | None], list[etree._Element]]:
    """Children that neither dialect reads are carried as written (both loaders skip elements
    they do not know); one that the target loader would read (its own spelling, written in the
    other dialect) is dropped: carrying it would change what the target loads."""
    known = KNOWN_CHILDREN[family(t.dialect)]
    theirs = KNOWN_CHILDREN[family(target)]
    carried: dict[tuple[str, str | None], list[etree._Element]] = {}
    for parent in [element, *children(element, "joint"), *children(element, "actuator")]:
        kind = "transmission" if parent is element else local(parent)
        ours = known[kind]
        for child in parent:
            tag = child.tag
            if tag.__class__ is not str or tag.rpartition("}")[2] in ours:
                continue  # a comment, or a child its own dialect reads
            name = local(child)
            owner = f"{kind} '{parent.get('name', '')}'"
            if name in theirs[kind]:
                result.losses.append(f"{owner}: <{name}> is not read in {family(t.dialect)} "
                                     f"but would be in {target}; dropped")
                continue
            carried.setdefault((kind, parent.get("name")), []).append(child)
            result.notes.append(f"{owner}: <{name}> is read by neither loader; carried as "
                                "written")
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


def _check(output: Source, result: ConvertedDocument, originals: list[Transmission | Follower],
           alone: set[etree._Element | Written], names: Counter[str],
           virtual: dict[int, Written], in_tree: bool) -> None:
    """Read the output back, convert it back, and compare with the original: on what the
    transmission itself defines (a value it leaves out is not judged, and interfaces that an
    existing ``<ros2_control>`` declares besides its own are a note, not a loss).

    ``output.tree`` is the converted tree itself when ``output.data`` was written from it as
    edits, which parse to the same canonical document (:func:`.check_written`
    verifies that): reading it reads what a parse of the output would give, without a second
    tree.
    The transmissions of a block written as text (:mod:`.repeated.block_text`) are not in that
    tree: each is read back on its own (a follower's only when it is judged), its name being
    its own (``names``: how many originals have each); ``virtual`` holds those of the originals
    that are not followers, by id.
    A pair whose shape (:func:`.repeated.nameless_shapes.shape`: the same up to the names) already
    came back whole is not judged again: the judgement reads names only to tell members apart. So a
    follower (:mod:`.repeated.renamings`) is not even read back when its record's first came back
    whole from the same place: both with a name of their own, in the block generated for the
    document (``alone``), declaring their joints there themselves.
    When every original is written as text, none is left in a converted tree (``in_tree``):
    it is not searched.
    """
    followers = [item for item in originals if item.__class__ is Follower]
    built = [item.built for item in followers]  # type: ignore[union-attr]
    apart = alone.intersection(built) if len(names) == len(originals) else {
        item.built for item in followers  # type: ignore[union-attr]
        if item.built in alone and names[item.name] == 1}
    firsts = {id(record.original): record for record in _records(followers)}
    components: dict[etree._Element, Any] = {}
    # shapes (:mod:`.repeated.nameless_shapes`) that came back whole
    survived: set[Hashable] = set()
    whole: set[int] = set()  # records whose verdict is in ``survived``, by id
    blocks = cache(lambda: {e.get("name") for e in output.root.iter("{*}ros2_control")})
    all_text = in_tree and len(virtual) == len(originals) - len(followers) and all(
        item.__class__ is Written for item in built)
    written = {} if all_text else _written_transmissions(output.root, apart, components)
    read = dict(zip(virtual, read_back(list(virtual.values())), strict=True))
    for item in originals:
        if item.__class__ is Follower and id(item.record) in whole and (  # type: ignore[union-attr]
                item.built in apart):  # type: ignore[union-attr]
            continue  # judged whole: the test below, first
        is_follower = isinstance(item, Follower)
        record = item.record if is_follower else firsts.get(id(item))
        text = item.built if is_follower and isinstance(item.built, Written) else virtual.get(
            id(item))
        if is_follower and item.built in apart:
            if id(item.record) in whole:
                continue
            if item.record.verdict in survived:  # and stays: a shape's hash is made once
                whole.add(id(item.record))
                continue
            t = item.transmission()
            element = read_back([text])[0] if text is not None else item.built
            out = Found(read_transmission(element, None, components), element)
        elif text is not None:
            t = item.transmission() if is_follower else item
            element = read[id(item)] if id(item) in read else read_back([text])[0]
            out = Found(read_transmission(element, None, components), element)
            if t.kind == "other":
                continue
        else:
            t = item.transmission() if is_follower else item
            queue = written.get((t.name, t.kind == "other"))
            if not queue:
                continue
            out = queue.pop(0)  # same-named transmissions keep their order
            if t.kind == "other":
                continue
        in_component = enclosing_component(out.element) is not None
        key = (shape(t, out.transmission), in_component)
        if record is not None and record.verdict is None and (
                out.element if text is None else text) in alone and names[t.name] == 1:
            record.verdict = key
        if key not in survived and _judge(t, out, in_component, result, blocks):
            survived.add(key)


def _written_transmissions(root: etree._Element, apart: set[etree._Element | Written],
                           components: dict[etree._Element, Any]
                           ) -> dict[tuple[str, bool], list[Found]]:
    """The transmissions of the output's tree (but those ``apart``, judged on their own), read,
    by their name and whether their type is custom, in document order."""
    written: dict[tuple[str, bool], list[Found]] = {}
    for element in transmission_elements(root, (
            e for e in root.iter("{*}transmission") if e not in apart)):
        found = Found(read_transmission(element, None, components), element)
        key = (found.transmission.name, found.transmission.kind == "other")
        written.setdefault(key, []).append(found)
    return written


def _judge(t: Transmission, out: Found, in_component: bool, result: ConvertedDocument,
           blocks: Callable[[], set[str | None]]) -> bool:
    """Convert ``out``, what the output holds of the original ``t``, back to ``t``'s dialect,
    and say in ``result`` what did not survive; whether it came back whole (nothing said).
    ``in_component``: ``out`` stands in a ``<ros2_control>``; ``blocks``: the names of the
    output's ``<ros2_control>`` blocks (asked only where needed)."""
    said = len(result.losses) + len(result.notes)
    back = translate(out.transmission, t.dialect).transmission
    a_view, b_view = view(t), view(back)
    lost = _lost(a_view, b_view)
    if in_component:
        lost.pop("interfaces", None)
        _interfaces(t, *_defined(a_view["interfaces"], b_view["interfaces"]), result)
    elif "interfaces" in lost and t.ros2_control is not None and t.ros2_control in blocks():
        lost.pop("interfaces")
        _kept_declaration(t, *_defined(a_view["interfaces"], b_view["interfaces"]), result)
    for key, change in lost.items():
        result.losses.append(f"transmission '{t.name}' did not survive the round trip: "
                             f"{key}: {change}")
    return len(result.losses) + len(result.notes) == said


def _records(items: list[Transmission | Follower]) -> list[Record]:
    return list({id(item.record): item.record for item in items
                 if isinstance(item, Follower)}.values())


def judge(before: Transmission, after: Transmission) -> dict[str, str]:
    """The fields of ``before`` that ``after`` (its round trip) does not keep, as
    ``before -> after`` texts: judged on what ``before`` itself defines. A value it leaves
    out is not judged (a missing ROS 1 reduction comes back as ros2_control's 1.0), a joint
    that names no valid interface may come back state-only, and command interfaces that a
    ``<ros2_control>`` block declares besides its own are kept, not lost."""
    return _lost(view(before), view(after))


def _lost(a_view: dict[str, Any], b_view: dict[str, Any]) -> dict[str, str]:
    """:func:`judge` on the views of both transmissions."""
    lost = {}
    for key in ("kind", *FIELDS):
        a, b = _defined(a_view[key], b_view[key])
        if key == "interfaces":
            a, b = _without_state(a), _without_state(b)
            if all(kinds <= b.get(joint, frozenset()) for joint, kinds in a.items()):
                continue
        if not _same(a, b):
            lost[key] = f"{_show(a)} -> {_show(b)}"
    return lost


def _defined(a: Any, b: Any) -> tuple[Any, Any]:
    """Both views without the members whose value the original leaves undefined."""
    if not isinstance(a, dict) or not isinstance(b, dict):
        return a, b
    keep = {k for k, v in a.items() if v is not None}
    return ({k: v for k, v in a.items() if k in keep},
            {k: v for k, v in b.items() if k in keep or k not in a})


def _without_state(kinds: dict) -> dict:
    """A joint that names no command interface comes back as state-only: the same."""
    return {joint: names - {"state"} for joint, names in kinds.items()}


def _interfaces(t: Transmission, a: dict, b: dict, result: ConvertedDocument) -> None:
    for joint, kinds in a.items():
        back = b.get(joint, frozenset()) - {"state"}
        kinds = kinds - {"state"}
        if kinds - back:
            result.losses.append(
                f"joint '{joint}': transmission '{t.name}' names {_show(kinds)} but the "
                f"<ros2_control> that declares the joint commands {_show(back) or 'nothing'}; "
                "add the missing command interface there (txtool does not change a hardware "
                "declaration)")
        elif back - kinds:
            result.notes.append(
                f"joint '{joint}': its <ros2_control> declaration also commands "
                f"{_show(back - kinds)}, which transmission '{t.name}' does not name; kept")


def _kept_declaration(t: Transmission, a: dict, b: dict, result: ConvertedDocument) -> None:
    """Back to ROS 1 out of a ``<ros2_control>`` that stays in the document: what the block
    declares besides what the ROS 1 transmission names stays declared there (a file that
    had both before ``--reversible`` took it to ROS 2 gets both back), not a loss."""
    for joint, kinds in a.items():
        back = b.get(joint, frozenset()) - {"state"}
        kinds = kinds - {"state"}
        if back - kinds:
            result.losses.append(
                f"joint '{joint}': transmission '{t.name}' names {_show(back - kinds)} in "
                f"ros1, which <ros2_control name=\"{t.ros2_control}\"> does not command")
        elif kinds - back:
            result.notes.append(
                f"joint '{joint}': <ros2_control name=\"{t.ros2_control}\"> also commands "
                f"{_show(kinds - back)}, which transmission '{t.name}' does not name in ros1; "
                "the block stays")


def _same(x: Any, y: Any) -> bool:
    if isinstance(x, dict) and isinstance(y, dict):
        return x.keys() == y.keys() and all(_same(x[k], y[k]) for k in x)
    return repr(x) == repr(y) if isinstance(x, float) or isinstance(y, float) else x == y


def _show(value: Any) -> str:
    if isinstance(value, dict):
        return "{" + ", ".join(f"{k}: {_show(v)}" for k, v in value.items()) + "}"
    if isinstance(value, frozenset | set):
        return "{" + ", ".join(sorted(value)) + "}"
    return repr(value)
