"""A change made to parsed elements, said as edits of the bytes they were parsed from: only
what changed is written, everything else keeps its bytes."""

from __future__ import annotations

import hashlib
import textwrap
import zlib
from collections.abc import Callable

import pytest
from hypothesis import given
from hypothesis import strategies as st
from lxml import etree

from txtool.io.xmlio import InputError, parse_bytes
from txtool.rules import all_rules
from txtool.transform.edits.core import EditedText
from txtool.transform.edits.document import read_back
from txtool.transform.edits.spans import SpanIndex
from txtool.transform.edits.tree_edits import (
    NotEditable,
    Serialized,
    TreeChange,
    reads_as_serialized,
    serialization,
)
from txtool.transform.migrate import MigrateOptions, migrate_file

FIXES = [rule for rule in all_rules().values() if rule.fixable]


def reads_as(data: bytes, tree: etree._ElementTree, path: str) -> bool:
    """Whether the bytes an edit wrote read back as ``tree`` (as every fix's are checked)."""
    try:
        read_back(data, path, serialization(tree), "fix")
    except InputError:
        return False
    return True


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


def test_a_serialization_that_does_not_parse_reads_as_no_tree() -> None:
    read = parse_bytes(b"<robot/>", "r.urdf")
    text = b"<robot>"
    written = Serialized(hashlib.sha256(text).digest(), zlib.compress(text))
    assert not reads_as_serialized(read, written, "r.urdf")


def test_bytes_that_do_not_parse_do_not_read_as_the_tree() -> None:
    assert not reads_as(b"<robot>", parse_bytes(b"<robot/>", "robot.urdf"), "robot.urdf")


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
