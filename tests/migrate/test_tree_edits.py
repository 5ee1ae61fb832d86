"""A change made to parsed elements, said as edits of the bytes they were parsed from: only
what changed is written, everything else keeps its bytes."""

from __future__ import annotations

import textwrap
from collections.abc import Callable

import pytest
from hypothesis import example, given
from hypothesis import strategies as st
from lxml import etree

from txtool.io.xmlio import InputError, parse_bytes
from txtool.rules import all_rules
from txtool.transform.edits.core import EditedText
from txtool.transform.edits.spans import NotIndexed, SpanIndex
from txtool.transform.edits.tree_edits import (
    NotEditable,
    TreeChange,
    reads_as,
    reads_as_serialized,
    serialization,
)
from txtool.transform.migrate import MigrateOptions, migrate_file

FIXES = [rule for rule in all_rules().values() if rule.fixable]


def _changed(data: bytes, change: Callable[[etree._Element], None]) -> bytes:
    tree = parse_bytes(data, "robot.urdf")
    text = EditedText(data)
    index = SpanIndex(text.data, tree.getroot())
    recorded = TreeChange([tree.getroot()])
    change(tree.getroot())
    written = text.applied(recorded.edits(text, index))
    assert reads_as(written, tree, "robot.urdf")
    return written


def test_attribute_values_keep_their_quotes_and_new_ones_come_last() -> None:
    data = b"<robot name = 'r' x:a='1' xmlns:x='urn:x'  />"

    def change(root: etree._Element) -> None:
        root.set("name", "it's <r>")
        root.set("{urn:x}a", "2")
        root.set("new", 'say "hi"\n')

    assert _changed(data, change) == (
        b"<robot name = 'it&apos;s &lt;r&gt;' x:a='2' xmlns:x='urn:x' new=\"say &quot;hi&quot;"
        b'&#10;"  />')


def test_a_dropped_attribute_takes_the_space_before_it() -> None:
    data = b'<robot>\r\n  <t name="t"\r\n     type="x" >\r\n  </t>\r\n</robot>\r\n'
    assert _changed(data, lambda root: root[0].attrib.pop("type")) == (
        b'<robot>\r\n  <t name="t" >\r\n  </t>\r\n</robot>\r\n')


def test_a_new_attribute_in_a_namespace_cannot_be_edited() -> None:
    with pytest.raises(NotEditable, match="in a namespace"):
        _changed(b"<robot/>", lambda root: root.set("{urn:x}a", "1"))


def test_an_element_written_empty_gets_its_content_and_end_tag() -> None:
    def change(root: etree._Element) -> None:
        root[0].text = "\n    "
        etree.SubElement(root[0], "hardwareInterface").text = "a & b"
        root[0][0].tail = "\n  "

    data = b'<robot>\r\n  <joint name="j" />\r\n</robot>\r\n'
    assert _changed(data, change) == (
        b'<robot>\r\n  <joint name="j">\r\n    <hardwareInterface>a &amp; b</hardwareInterface>'
        b"\r\n  </joint>\r\n</robot>\r\n")


def test_children_inserted_and_removed_between_kept_ones() -> None:
    data = textwrap.dedent("""\
        <robot>
          <a   x='1'/>
          <!-- kept -->
          <b/>
          <c>&#65;</c>
        </robot>
        """).encode()

    def change(root: etree._Element) -> None:
        gone = root[2]  # <b/>
        root[1].tail = gone.tail
        root.remove(gone)
        new = etree.Element("d")
        new.tail = "\n  "
        root.insert(0, new)

    assert _changed(data, change) == textwrap.dedent("""\
        <robot>
          <d/>
          <a   x='1'/>
          <!-- kept -->
          <c>&#65;</c>
        </robot>
        """).encode()


def test_reordered_children_are_written_anew() -> None:
    data = b"<robot><a x='1'/><b/></robot>"

    def change(root: etree._Element) -> None:
        root.append(root[0])

    assert _changed(data, change) == b'<robot><b/><a x="1"/></robot>'


def test_a_new_element_that_would_declare_a_namespace_cannot_be_edited() -> None:
    with pytest.raises(NotEditable, match="would declare a namespace"):
        _changed(b"<robot>\n</robot>", lambda root: etree.SubElement(root, "{urn:x}a"))


def test_a_namespaced_transmission_gets_its_type_in_its_namespace(tmp_path) -> None:
    """TX302 adds a <type> in the transmission's namespace, which the document declares
    already: it is not declared again."""
    path = tmp_path / "robot.urdf"
    path.write_bytes(textwrap.dedent("""\
        <x:robot xmlns:x="urn:x">
          <x:transmission name='t' type="SimpleTransmission">
            <x:joint name="j"><x:hardwareInterface>hardware_interface/EffortJointInterface</x:hardwareInterface></x:joint>
            <x:actuator name="m"/>
          </x:transmission>
        </x:robot>
        """).encode())
    result = migrate_file(str(path), FIXES, MigrateOptions())
    assert result.fixes == {"TX302": 1} and result.edits is not None
    assert result.data.decode().splitlines()[1:3] == [
        "  <x:transmission name='t'>",
        "    <x:type>transmission_interface/SimpleTransmission</x:type>"]


def test_a_text_that_writes_as_before_is_no_edit() -> None:
    data = b"<robot><a/></robot>"
    tree = parse_bytes(data, "robot.urdf")
    text, root = EditedText(data), tree.getroot()
    index, recorded = SpanIndex(data, root), TreeChange([root])
    root.text = ""
    assert recorded.edits(text, index) == []


def test_a_removed_element_is_said_where_it_stands_when_no_line_repeats_it() -> None:
    def change(root: etree._Element) -> None:
        root[0].tail += root[1].tail
        root.remove(root[1])

    data = b"<robot>\n  <a/> x<b/>\n</robot>"
    assert _changed(data, change) == b"<robot>\n  <a/> x\n</robot>"


@pytest.mark.parametrize(("written", "same"), [
    (b'<robot xmlns:x="urn:a"><x:t/></robot>', True),
    (b'<robot xmlns:y="urn:a"><y:t/></robot>', False),  # another prefix (tinyxml2 reads it)
    (b'<robot xmlns:x="urn:b"><x:t/></robot>', False),  # another namespace
    (b'<robot><x:t xmlns:x="urn:a"/></robot>', True),  # declared where it is used
    (b'<robot xmlns:x="urn:a" xmlns:u="urn:unused"><x:t/></robot>', True),  # used by no name
    (b'<robot xmlns:x="urn:a"><x:t/><!-- c --></robot>', False),  # a comment more
    (b"<robot xmlns:x='urn:a'>\n<x:t></x:t></robot>", False),  # a text more
])
def test_bytes_read_as_a_tree_by_names_texts_and_comments(written: bytes, same: bool) -> None:
    """The canonical forms compared are the exclusive ones: a namespace declaration that no
    name uses is not compared, nor where a used one stands (no loader reads either); names
    with their prefixes and namespaces, texts and comments are."""
    tree = etree.fromstring(b'<robot xmlns:x="urn:a"><x:t/></robot>').getroottree()
    assert reads_as(written, tree, "robot.urdf") is same


def test_bytes_lxml_would_write_for_the_tree_are_told_without_canonical_forms(monkeypatch
                                                                            ) -> None:
    """The serializations are compared first (a third of the time): the canonical forms
    are made only where they differ."""
    from txtool.transform.edits import tree_edits

    made = []

    def canonical(tree):
        made.append(tree)
        return etree.tostring(tree, method="c14n", exclusive=True)

    monkeypatch.setattr(tree_edits, "canonical", canonical)
    tree = parse_bytes(b"<robot name='r'>\n  <link name=\"l\" ></link>\n</robot>", "r.urdf")
    assert reads_as(b'<robot name="r">\n  <link name="l"/>\n</robot>', tree, "r.urdf")
    assert made == []
    assert not reads_as(b'<robot name="r">\n  <link name="m"/>\n</robot>', tree, "r.urdf")
    assert len(made) == 2


@pytest.mark.parametrize(("written", "same", "canonical_forms"), [
    (b'<robot name="r"><role>a</role></robot>', True, 0),  # as lxml writes the tree
    (b'<robot name="r"><role/></robot>', True, 2),  # an empty text: read back as none
    (b"<robot name='r'><role></role></robot>", True, 2),  # the same, as a person writes it
    (b'<robot name="r"><role>b</role></robot>', False, 2),
    (b'<robot name="r"><role>a</role><!-- c --></robot>', False, 2),
])
def test_a_converted_tree_kept_as_its_serialization_is_told_as_the_tree_is(
        written, same, canonical_forms, monkeypatch) -> None:
    """The conversion's check keeps the converted document as lxml writes it, so that the
    tree can go before the written bytes are parsed (the parse reuses its memory): where the
    serializations differ, the canonical form of the serialization parsed decides, as the
    tree's own would (an element whose text a conversion set empty is written <a></a> and
    read back as <a/>)."""
    from txtool.transform.edits import tree_edits

    made = []
    canonical = tree_edits.canonical
    monkeypatch.setattr(tree_edits, "canonical", lambda tree: made.append(1) or canonical(tree))
    root = etree.Element("robot", name="r")
    etree.SubElement(root, "role").text = "" if canonical_forms and same else "a"
    tree = root.getroottree()
    text = serialization(tree)
    read = parse_bytes(written, "r.urdf")
    assert reads_as_serialized(read, text, "r.urdf") is same
    assert len(made) == canonical_forms
    assert reads_as(written, tree, "r.urdf") is same  # the verdict of the tree itself


def test_a_serialization_that_does_not_parse_reads_as_no_tree() -> None:
    read = parse_bytes(b"<robot/>", "r.urdf")
    assert not reads_as_serialized(read, "<robot>", "r.urdf")


def test_bytes_that_do_not_parse_do_not_read_as_the_tree() -> None:
    assert not reads_as(b"<robot>", parse_bytes(b"<robot/>", "robot.urdf"), "robot.urdf")


@pytest.mark.parametrize(("failing", "reason"), [
    ("SpanIndex", "the bytes do not read as parsed (refused)"), ("TreeChange.edits", "refused"),
    ("reads_as", "what the edits write does not read as the fixed document"),
])
def test_where_the_edits_cannot_say_the_fixes_the_file_is_refused(failing, reason, tmp_path,
                                                                  monkeypatch) -> None:
    """No other writer stands behind the edits: a change they cannot say is one line naming
    the file, and nothing is written."""
    from txtool.transform import migrate
    from txtool.transform.edits.spans import SpanError

    def refuse(*_args, **_kwargs):
        if failing == "reads_as":
            return False
        raise (SpanError if failing == "SpanIndex" else NotEditable)("refused")

    data = (b'<robot>\n  <transmission name="t" type="SimpleTransmission">\n    '
            b'<joint name="j"><hardwareInterface>EffortJointInterface</hardwareInterface>'
            b'</joint>\n    <actuator name="m"/>\n  </transmission>\n</robot>\n')
    path = tmp_path / "robot.urdf"
    path.write_bytes(data)
    edited = migrate_file(str(path), FIXES, MigrateOptions())
    assert edited.edits is not None and edited.fixes == {"TX300": 1, "TX302": 1}
    target, _, attribute = failing.partition(".")
    monkeypatch.setattr(getattr(migrate, target) if attribute else migrate, attribute or target,
                        refuse)
    with pytest.raises(InputError) as refused:
        migrate_file(str(path), FIXES, MigrateOptions(mode="write"))
    assert str(refused.value).startswith(f"{path}: cannot fix: {reason}")
    assert path.read_bytes() == data


def test_a_new_attribute_in_a_namespace_takes_a_prefix_in_scope() -> None:
    data = b"<robot xmlns:x='urn:x'><t name='t'/></robot>"
    tree = parse_bytes(data, "robot.urdf")
    text = EditedText(data)
    element = tree.getroot()[0]
    index = SpanIndex(text.data, tree.getroot(), [element])
    change = TreeChange([element])
    element.set("{urn:x}a", "1")
    with pytest.raises(NotEditable):
        change.edits(text, index)
    assert text.applied(change.edits(text, index, redeclare=True)) == (
        b"<robot xmlns:x='urn:x'><t name='t' x:a=\"1\"/></robot>")


def test_a_fixed_document_loses_its_late_declaration(tmp_path) -> None:
    path = tmp_path / "robot.urdf"
    path.write_bytes(b'<!-- licence -->\n<?xml version="1.0"?>\n<robot>\n  <transmission name="t">\n'
                     b"    <type>transmission_interface/SimpleTransmission</type>\n"
                     b'    <joint name="j"><hardwareInterface>EffortJointInterface'
                     b'</hardwareInterface></joint>\n    <actuator name="m"/>\n'
                     b"  </transmission>\n</robot>\n")
    result = migrate_file(str(path), FIXES, MigrateOptions())
    assert result.data.startswith(b"<!-- licence -->\n<robot>\n")
    assert b"hardware_interface/EffortJointInterface" in result.data


_TAILS = st.sampled_from([None, "", " ", "\n", "\n  ", "\n\n    ", "x"])


def _robot_of(children: list[tuple[str, str | None]], text: str | None
              ) -> tuple[etree._ElementTree, EditedText, SpanIndex]:
    """A robot of ``children`` (markup and tail) after ``text``: its tree, bytes and index."""
    data = ("<robot>" + (text or "") + "".join(markup + (tail or "")
                                              for markup, tail in children) + "</robot>").encode()
    tree = parse_bytes(data, "robot.urdf")
    edited = EditedText(data)
    return tree, edited, SpanIndex(edited.data, tree.getroot())


def _change(root: etree._Element, changes: list[tuple[str, int, str | None]]) -> None:
    """Change the children of ``root`` as ``changes`` say: a kind of change, where (taken
    modulo the children), and a tail or text."""
    for kind, at, tail in changes:
        kids = list(root)
        if kind == "insert":
            new = etree.Element("n")
            new.tail = tail
            root.insert(at % (len(kids) + 1), new)
        elif kind == "text":
            root.text = tail
        elif kids and kind == "remove":
            root.remove(kids[at % len(kids)])
        elif kids and kind == "tail":
            kids[at % len(kids)].tail = tail
        elif kids and kind == "move":
            root.append(kids[at % len(kids)])

_CHILD = st.sampled_from(["<a/>", "<b n='1'/>", "<c>t</c>", "<d><e/></d>", "<!-- c -->"])


@given(st.lists(st.tuples(_CHILD, _TAILS), max_size=10), _TAILS,
       st.lists(st.tuples(st.sampled_from(["remove", "insert", "tail", "text", "move"]),
                          st.integers(0, 20), _TAILS), max_size=5))
def test_children_changed_at_random_are_written_and_kept_ones_keep_their_bytes(
        children: list[tuple[str, str | None]], text: str | None,
        changes: list[tuple[str, int, str | None]]) -> None:
    tree, edited, index = _robot_of(children, text)
    root = tree.getroot()
    spans = {child: (index[child].start, index[child].end) for child in root}
    recorded = TreeChange([], [root])
    _change(root, changes)
    edits = recorded.edits(edited, index)
    written = edited.applied(edits)
    assert reads_as(written, tree, "robot.urdf")
    if not changes:
        assert edits == []
    kept_in_order = [child for child in root if child in spans]
    if kept_in_order == sorted(kept_in_order, key=lambda child: spans[child][0]):
        # Unless the change reordered them, no edit writes over a kept child.
        for child in kept_in_order:
            start, end = spans[child]
            assert not any(edit.start < end and start < edit.end for edit in edits), child


_FOUR = [("<a/>", None), ("<b n='1'/>", "\n"), ("<c>t</c>", None), ("<d><e/></d>", "\n")]


@given(st.lists(st.tuples(_CHILD, _TAILS), min_size=1, max_size=10), _TAILS,
       st.lists(st.tuples(st.sampled_from(["remove", "insert", "tail", "text", "move"]),
                          st.integers(0, 20), _TAILS), max_size=5), st.integers(1, 10))
# At the window's edge (two passed over): the last one passed over taken out, one put in
# before the first recorded, the tail before it, the text, the first recorded moved last.
@example(_FOUR, None, [("remove", 1, None)], 2)
@example(_FOUR, None, [("insert", 2, None)], 2)
@example(_FOUR, None, [("tail", 1, " ")], 2)
@example(_FOUR, None, [("text", 0, " ")], 2)
@example(_FOUR, None, [("move", 2, None)], 2)
def test_a_window_over_the_first_children_gives_the_same_edits_or_asks_for_the_whole(
        children: list[tuple[str, str | None]], text: str | None,
        changes: list[tuple[str, int, str | None]], skip: int) -> None:
    """A container recorded past its first children (a robot's links and joints before its
    transmissions) gives the edits of one recorded whole, or, where the change reached the
    children it passed over, asks for the whole (:class:`NotIndexed`): never other edits."""
    tree, edited, index = _robot_of(children, text)
    root = tree.getroot()
    window = min(skip, len(root))
    before, text_before = [(child, child.tail) for child in root], root.text
    first = root[window] if window < len(root) else None  # the first child recorded
    whole = TreeChange([], [root])
    windowed = TreeChange([], [root], None if first is None else {root: first})
    taken = window if first is not None else 0
    assert windowed.children_before(root) == [child for child, _ in before[taken:]]
    _change(root, changes)
    edits = whole.edits(edited, index)
    after = [(child, child.tail) for child in root]
    kept = [child for child, _ in after if any(child is old for old, _ in before)]
    untouched = (root.text == text_before and after[:taken + 1] == before[:taken + 1]
                 and kept == [old for old, _ in before if old in kept])
    if after[:max(taken - 1, 0)] != before[:max(taken - 1, 0)]:
        return  # changed further among those passed over: not seen (the read-back tells)
    try:
        assert windowed.edits(edited, index) == edits
    except NotIndexed:
        assert not untouched
