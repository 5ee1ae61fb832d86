"""The span index: where each node of a parsed document is written in its bytes."""

from __future__ import annotations

import time

import pytest
from hypothesis import given
from hypothesis import strategies as st
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


def _chain(links: int, tail: str = "") -> bytes:
    body = "".join(f'\n  <link name="l{i}"/><joint name="j{i}" type="fixed">'
                   f'<parent link="l{i}"/><child link="l{i + 1}"/></joint>'
                   for i in range(links))
    return (f'<robot name="r">{body}\n  <transmission name="t">\n    <type>x</type>\n'
            f"  </transmission>{tail}\n</robot>\n").encode()


def test_the_scan_jumps_past_what_nothing_asks_about_to_the_same_spans() -> None:
    _same_spans(_chain(300), lambda root: [root[-1], root[-2], root[-3]], lambda root: {
        "within": [], "shallow": [root], "near": {root[-1], root[-2], root[-3]}})


@pytest.mark.parametrize("tail", [
    "",  # the transmission's start tag first on its line
    '<link name="x"/>',
])
@pytest.mark.parametrize("head", [
    '\n  <transmission name="t">',  # a line of its own: a jump lands there
    '<transmission\n     name="t">',  # its start tag over two lines: no jump, read through
    '\n  <!-- a --><transmission name="t">',  # a node before it on its line: read through
    '\n  <x/><transmission name="t">',  # an element before it on its line: read through
    '\n  <x>\n</x><transmission name="t">',  # an end tag before it: the jump lands
])
def test_a_landing_that_could_be_wrong_is_not_taken(head: str, tail: str) -> None:
    data = _chain(20, tail).replace(b'\n  <transmission name="t">', head.encode())

    def transmission(root):
        return next(root.iter("transmission"))

    _same_spans(data, lambda root: [transmission(root)], lambda root: {
        "within": [transmission(root)], "shallow": [root], "near": {transmission(root)}})


@pytest.mark.parametrize("inside", [
    "<!-- </joint> -->", "<?pi </joint>?>", "<joint name='in'/>", "<![CDATA[</joint>]]>",
    "<joint name='in'><x/></joint>",
])
def test_what_could_hide_an_end_tag_is_read_through(inside: str) -> None:
    data = (f'<robot name="r">\n  <joint name="a">{inside}<parent link="p"/></joint>\n'
            '  <link name="b"/>\n</robot>\n').encode()
    _same_spans(data, lambda root: [root[1]], lambda root: {"within": [], "shallow": [root]})


def test_a_robots_links_and_joints_are_jumped_over(monkeypatch) -> None:
    from txtool.transform.edits import spans

    landed = []
    past = spans._Jumps.past

    def counted(self, node):
        landing = past(self, node)
        landed.append(landing is not None)
        return landing

    monkeypatch.setattr(spans._Jumps, "past", counted)
    data = _chain(300).replace(b'<joint name="j299"', b'\n  <joint name="j299"')
    _same_spans(data, lambda root: [root[-1], root[-2]], lambda root: {
        "within": [], "shallow": [root], "near": {root[-1], root[-2]}})
    assert landed == [True, False]  # from l0 straight to j299; then the transmission
    landed.clear()
    data = _chain(300)  # l299 and j299 on one line, both asked about: landed on the first
    _same_spans(data, lambda root: [root[-2], root[-3]], lambda root: {
        "within": [], "shallow": [root], "near": {root[-2], root[-3]}})
    assert landed == [True, False, True]  # to l299; j299 read; then to the root's end tag


@pytest.mark.parametrize(("after", "jumped"), [
    ("", True),
    ("\n<!-- the end -->\n<?done?>\n", True),
    ("<!-- </robot> -->", False),  # the last </ is in a comment: read through
    ("<?pi </robot> <?y?>", False),  # in an instruction that a later one seems to close
    ("<?pi </x>?>", False),
])
def test_past_the_last_child_asked_about_the_scan_goes_to_the_roots_end_tag(
        after: str, jumped: bool, monkeypatch) -> None:
    """Nothing after the first links is asked about: the scan goes from there straight to
    the root's end tag where the document's last ``</`` is surely that tag, and reads
    through where a comment or instruction after the root could hold it."""
    from txtool.transform.edits import spans

    ends = []
    root_end = spans._Jumps._root_end
    monkeypatch.setattr(spans._Jumps, "_root_end",
                        lambda self: ends.append(root_end(self)) or ends[-1])
    data = _chain(300) + after.encode()
    full, root = _index(data)
    part = SpanIndex(data, root, [], shallow=[root], near={root[0], root[1]})
    assert (part[root].tail_start, part[root].end) == (full[root].tail_start, full[root].end)
    assert (part[root[1]].start, part[root[1]].end) == (full[root[1]].start, full[root[1]].end)
    assert root[-1] not in part and root[2] not in part
    assert ends and {end is not None for end in ends} == {jumped}


@given(st.binary(max_size=60).map(lambda raw: bytes(b"ab\n\r"[byte % 4] for byte in raw)),
       st.lists(st.integers(1, 30), max_size=8))
def test_a_landing_line_starts_where_the_lines_before_it_end(data: bytes, lines) -> None:
    """Where the scan lands on a line, in any order of landings: after the line breaks
    before it as the parser counts them (a bare CR ends a line too)."""
    from txtool.transform.edits.spans import _Jumps

    jumps = _Jumps(data, etree.Element("robot"), set())
    starts = [0, *(at + 1 for at, byte in enumerate(data)
                   if byte == ord("\n") or byte == ord("\r") and data[at + 1:at + 2] != b"\n")]
    for line in lines:
        found = jumps._line_start(line)
        if line <= len(starts):
            assert found == starts[line - 1]
        else:
            assert found is None or found == len(data)  # past the last line: nothing to land on


@pytest.mark.parametrize("step", [1, 5, 97])
def test_the_children_asked_about_are_landed_on_by_their_lines_to_the_same_spans(
        step: int) -> None:
    """Children asked about are ordered by their lines, the root's children not listed:
    the same spans for many of them as for few, two on one line among them."""
    data = _chain(300).replace(b"<joint", b"\n  <joint").replace(
        b'\n  <joint name="j7"', b'<joint name="j7"')

    def asked(root):
        return [kid for place, kid in enumerate(root) if place % step == 3 or place in (15, 16)]

    _same_spans(data, asked, lambda root: {"within": [], "shallow": [root],
                                           "near": set(asked(root))})
