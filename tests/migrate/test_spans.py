"""The span index: where each node of a parsed document is written in its bytes."""

from __future__ import annotations

import time

import pytest
from lxml import etree

from txtool.io.xmlio import parse_bytes
from txtool.transform.edits.spans import SpanError, SpanIndex

DOCUMENT = b"""<?xml version="1.0"?>
<!DOCTYPE robot [ <!ELEMENT robot ANY> <!-- a ] in a comment --> ]>
<!-- before the root -->
<robot xmlns:xacro="http://www.ros.org/wiki/xacro" name='r'>
  <transmission
      name = "t" xacro:if='${a > b}'>
    <![CDATA[ <not a="tag"/> ]]>
    <joint name="j"/><?pi with > inside?>
    <!-- <actuator name="fake"/> -->
    <actuator name="m" ></actuator>
  </transmission>
</robot>
<!-- after -->
"""


def _index(data: bytes) -> tuple[SpanIndex, etree._Element]:
    root = parse_bytes(data, "robot.urdf").getroot()
    return SpanIndex(data, root), root


def test_each_node_its_tags_and_attributes_as_written() -> None:
    index, root = _index(DOCUMENT)
    transmission = root[0]
    span = index[transmission]
    assert DOCUMENT[span.start:span.head_end].startswith(b"<transmission\n")
    assert DOCUMENT[span.tail_start:span.end] == b"</transmission>"
    attributes = index.attributes(transmission)
    name = attributes[b"name"]
    assert DOCUMENT[name.lead:name.end] == b'\n      name = "t"'
    condition = attributes[b"xacro:if"]
    assert (DOCUMENT[condition.value_start:condition.value_end], condition.quote) == (
        b"${a > b}", b"'")
    assert DOCUMENT[span.attributes_end:span.head_end] == b">"
    joint, instruction, comment, actuator = transmission
    assert index[joint].empty and DOCUMENT[index[joint].close:index[joint].end] == b"/>"
    assert DOCUMENT[index[instruction].start:index[instruction].end] == b"<?pi with > inside?>"
    assert DOCUMENT[index[comment].start:index[comment].end].startswith(b"<!-- <actuator")
    actuator_span = index[actuator]
    assert DOCUMENT[actuator_span.attributes_end:actuator_span.head_end] == b" >"
    assert actuator_span.head_end == actuator_span.tail_start  # <actuator ...></actuator>
    assert index[root].end == DOCUMENT.index(b"</robot>") + len(b"</robot>")
    assert etree.Element("other") not in index


def test_a_root_written_empty_and_lines_ended_by_cr() -> None:
    data = b"<?xml version='1.0'?>\r<!-- c -->\r<robot name='r'\r/>\r<!-- after -->"
    index, root = _index(data)
    assert data[index[root].start:index[root].end] == b"<robot name='r'\r/>"


@pytest.mark.parametrize("data, tree", [
    (b"<robot><a/></robot>", b"<robot><b/></robot>"),  # another name
    (b"<robot><a/></robot>", b"<robot><a/><b/></robot>"),  # a node the bytes do not have
    (b"<robot><a/><b/></robot>", b"<robot><a/></robot>"),  # one the tree does not have
    (b"<robot>\n<a/></robot>", b"<robot><a/></robot>"),  # on another line
    (b"<robot><a x='1' <b/></robot>", b"<robot><a/></robot>"),  # no markup read there
    (b"<robot><a/></robot>", b"<robot><!--a--></robot>"),  # a comment, not an element
    (b"<robot><a/></robot>", b"<robot><?a?></robot>"),  # an instruction
    (b"<robot><a/>", b"<robot><a/></robot>"),  # the root never ends
])
def test_bytes_that_do_not_read_as_the_tree_are_refused(data: bytes, tree: bytes) -> None:
    with pytest.raises(SpanError):
        SpanIndex(data, etree.fromstring(tree))


def test_the_index_costs_time_linear_in_the_document() -> None:
    """20,000 elements with attributes, comments between them: each token is matched once
    (a search from the start for each would read 10 GB)."""
    data = b"<robot>" + b'<link name="l" a=\'1\'/><!-- c -->\n' * 10000 + b"</robot>"
    root = parse_bytes(data, "big.urdf", limit=None).getroot()
    start = time.process_time()
    index = SpanIndex(data, root)
    assert time.process_time() - start < 2.0  # 0.2 s now
    assert index[root[-1]].end == len(data) - len(b"\n</robot>")  # the last comment


def test_names_are_read_in_the_documents_encoding() -> None:
    data = '<?xml version="1.0" encoding="ISO-8859-1"?><robot><é a="1"/></robot>'.encode("latin-1")
    root = parse_bytes(data, "robot.urdf").getroot()
    index = SpanIndex(data, root, codec="iso8859-1")
    assert data[index[root[0]].start:index[root[0]].end] == '<é a="1"/>'.encode("latin-1")


def test_only_the_elements_asked_for_are_indexed() -> None:
    index, root = _index(DOCUMENT)
    part = SpanIndex(DOCUMENT, root, [root[0][0]])  # the <joint>
    assert root[0][0] in part and root[0] not in part and root[0][3] not in part
    assert part[root[0][0]].start == index[root[0][0]].start


def _same_spans(data: bytes, pick, options) -> None:
    """The spans of the nodes ``pick(root)`` names, indexed with ``options(root)``, are those
    of the full index."""
    full, root = _index(data)
    part = SpanIndex(data, root, **options(root))
    for node in pick(root):
        assert (part[node].start, part[node].end) == (full[node].start, full[node].end)


@pytest.mark.parametrize("inside", [
    "<!-- </joint> -->", "<?pi </joint>?>", "<joint name='in'/>", "<![CDATA[</joint>]]>",
    "<joint name='in'><x/></joint>",
])
def test_what_could_hide_an_end_tag_is_read_through(inside: str) -> None:
    data = (f'<robot name="r">\n  <joint name="a">{inside}<parent link="p"/></joint>\n'
            '  <link name="b"/>\n</robot>\n').encode()
    _same_spans(data, lambda root: [root[1]], lambda root: {"within": [], "shallow": [root]})


def test_nodes_past_line_65535_are_paired_by_kind_and_name() -> None:
    """libxml2 may report a line one off past 65,535 (the line after a start tag): there the
    index pairs nodes by kind and name, and a robot that long converts."""
    data = (b"<robot>\n" + b'<link name="l"/>\n' * 65_540 + b'<transmission name="t">\n'
            b"  <type>x</type>\n</transmission>\n</robot>\n")
    root = parse_bytes(data, "long.urdf", limit=None).getroot()
    index = SpanIndex(data, root, [root[-1]])
    span = index[root[-1][0]]
    assert data[span.start:span.end] == b"<type>x</type>"
