"""A change made to parsed elements, said as edits of the bytes they were parsed from: only
what changed is written, everything else keeps its bytes."""

from __future__ import annotations

import textwrap
from collections.abc import Callable

import pytest
from lxml import etree

from txtool.io.xmlio import parse_bytes
from txtool.rules import all_rules
from txtool.transform.edits import EditedText
from txtool.transform.migrate import MigrateOptions, migrate_file
from txtool.transform.spans import SpanIndex
from txtool.transform.tree_edits import NotEditable, TreeChange, reads_as

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
