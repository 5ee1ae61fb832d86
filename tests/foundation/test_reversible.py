"""``convert --reversible``: A -> ROS 2 -> A gives back every transmission block byte for byte.

Where the blocks stand together, the whole document comes back; where they are scattered (each
beside its joint, as xacro writes them), the blocks and the rest come back and only their place
changes: they return together, where the first stood.
"""

from __future__ import annotations

import re
from itertools import pairwise

import pytest

from tests.corpus import corpus_file, corpus_names
from tests.foundation.test_roundtrip_corpus import NOT_PROMISED, blocks, standard, start_dialect
from txtool.io.load import load
from txtool.io.xmlio import Source, parse_bytes
from txtool.transform.convert import convert_source
from txtool.transform.reversible import MARK


def convert(data: bytes, target: str, reversible: bool = False):
    return convert_source(Source("a.urdf", data, parse_bytes(data, "a.urdf")), target,
                          reversible=reversible)


def together(data: bytes) -> bool:
    """Only blank lines between the standard transmission blocks (a comment between them is
    part of the rest: it stays in order, and the blocks come back together after it)."""
    lines = data.splitlines()
    spans = []
    for found in standard(data):
        start = found.element.sourceline - 1
        end = start
        while not re.search(rb"</([\w.-]+:)?transmission>|/>\s*$", lines[end]):
            end += 1
        spans.append((start, end))
    spans.sort()
    between = [line for (_, end), (start, _) in pairwise(spans) for line in
               lines[end + 1:start]]
    return all(not line.strip() for line in between)


ROS1_FILES = [n for n in corpus_names() if n not in NOT_PROMISED]


@pytest.mark.parametrize("target", ["ros2-p1", "ros2-p2"])
@pytest.mark.parametrize("name", ROS1_FILES)
def test_a_to_ros2_and_back_gives_back_the_original_blocks(name, target):
    original = load(str(corpus_file(name)), expand=False).data
    if start_dialect(original) != "ros1":
        pytest.skip("no ROS 1 transmission to carry")
    there = convert(original, target, reversible=True)
    assert there.losses == []
    assert there.data.count(MARK.encode()) == len(standard(original))
    back = convert(there.data, "ros1")
    assert MARK.encode() not in back.data
    if together(original):
        assert back.data == original
    else:
        rest, taken = blocks(original)
        rest_back, taken_back = blocks(back.data)
        assert rest_back == rest
        # Each block as written, but for the indentation of its first line: that is where
        # it stands now (those of one xacro macro come back together where the first stood).
        assert sorted(map(bytes.lstrip, taken_back)) == sorted(map(bytes.lstrip, taken))


def test_the_corpus_has_both_kinds():
    kinds = {together(load(str(corpus_file(n)), expand=False).data) for n in ROS1_FILES
             if start_dialect(load(str(corpus_file(n)), expand=False).data) == "ros1"}
    assert kinds == {True, False}


ARM = b"""<?xml version="1.0"?>\r
<robot name="arm">\r
  <joint name="j1" type="revolute"><parent link="a"/><child link="b"/></joint>\r
  <!-- the elbow -->\r
  <transmission name="t1" >\r
    <type>transmission_interface/SimpleTransmission</type>\r
    <actuator name='m1'><hardwareInterface>EffortJointInterface</hardwareInterface>\r
      <mechanicalReduction>50.0</mechanicalReduction></actuator>\r
    <joint name="j1"><hardwareInterface>hardware_interface/EffortJointInterface\r
    </hardwareInterface></joint>\r
  </transmission>\r
</robot>\r
"""


def test_what_ros2_cannot_hold_comes_back_crlf_and_all():
    there = convert(ARM, "ros2-p2", reversible=True)
    assert b"<!-- txtool-original " in there.data and b"\r\n" in there.data
    back = convert(there.data, "ros1")
    assert back.data == ARM
    assert back.notes[-1] == ("1 transmission: the original bytes carried by --reversible are "
                              "put back")


def test_without_the_flag_the_block_comes_back_as_txtool_writes_it():
    back = convert(convert(ARM, "ros2-p2").data, "ros1")
    assert back.data != ARM and b"m1" in back.data


def test_an_edited_transmission_is_written_anew_and_said_so():
    there = convert(ARM, "ros2-p2", reversible=True).data
    edited = there.replace(b"<mechanical_reduction>50.0<", b"<mechanical_reduction>60<")
    assert edited != there
    back = convert(edited, "ros1")
    assert b"<mechanicalReduction>60</mechanicalReduction>" in back.data
    assert MARK.encode() not in back.data
    assert ("transmission 't1': changed since it was converted with --reversible; written as "
            "txtool writes it") in back.notes


def test_a_damaged_comment_is_dropped_and_the_block_written_anew():
    there = convert(ARM, "ros2-p2", reversible=True).data
    damaged = re.sub(rb"txtool-original (\S+)", b"txtool-original AAAA!", there)
    back = convert(damaged, "ros1")
    assert MARK.encode() not in back.data and b"<mechanicalReduction>50.0<" in back.data
    assert any("changed since it was converted" in n for n in back.notes)


def test_loaders_see_the_same_document(run, tmp_path):
    plain, carried = tmp_path / "plain.urdf", tmp_path / "carried.urdf"
    plain.write_bytes(convert(ARM, "ros2-p2").data)
    carried.write_bytes(convert(ARM, "ros2-p2", reversible=True).data)
    found = []
    for path in (plain, carried):
        code, out, _ = run("validate", "--format", "json", str(path))
        found.append((code, re.sub(r'"[^"]*(plain|carried)\.urdf"', "F", out)))
    assert found[0] == found[1]


def test_cli_flag(run, tmp_path):
    source = tmp_path / "arm.urdf"
    source.write_bytes(ARM)
    code, out, err = run("convert", str(source), "--to", "ros2-p2", "--reversible")
    assert code == 0 and "txtool-original" in out
    code, _, err = run("convert", str(source), "--to", "ros1", "--reversible")
    assert code == 2
    assert err == ("txtool: --reversible applies to --to ros2-p1 and ros2-p2 (converting back "
                   "to ros1 puts carried originals back by itself)\n")


@pytest.mark.parametrize(("codec", "mark"), [("utf-16-le", b"\xff\xfe"),
                                              ("utf-32-be", b"\x00\x00\xfe\xff")])
def test_a_wide_document_comes_back_in_its_own_encoding(codec, mark):
    original = mark + ARM.decode("utf-8").replace(
        '<?xml version="1.0"?>', f'<?xml version="1.0" encoding="{codec[:6].upper()}"?>'
    ).encode(codec)
    there = convert(original, "ros2-p2", reversible=True)
    assert there.data.startswith(mark) and "txtool-original".encode(codec) in there.data
    assert convert(there.data, "ros1").data == original


def test_a_block_sharing_its_line_is_not_carried_and_says_so():
    shared = ARM.replace(b"  </transmission>\r\n</robot>", b"  </transmission><link name='x'/>\r\n</robot>")
    assert shared != ARM
    there = convert(shared, "ros2-p2", reversible=True)
    assert MARK.encode() not in there.data
    assert ("transmission 't1': shares its lines with other elements; its original is not "
            "carried (--reversible)") in there.notes


def test_an_original_shares_no_line_with_what_the_block_kept():
    """Written back as an edit: the carried original takes the place of the element alone,
    an element after it on its line stays where it was (in the block, which is no longer
    txtool's and so stays)."""
    data = (b'<robot name="r">\n  <link name="a"/>\n  <transmission name="t">   <!-- kept -->\n'
            b"    <type>transmission_interface/SimpleTransmission</type>\n"
            b'    <joint name="j"><hardwareInterface>hardware_interface/EffortJointInterface'
            b"</hardwareInterface></joint>\n"
            b'    <actuator name="m"><mechanicalReduction>50</mechanicalReduction></actuator>\n'
            b"  </transmission>\n</robot>\n")
    there = convert(data, "ros2-p2", reversible=True).data
    shared = there.replace(b"</transmission>\n", b'</transmission><link name="b"/>\n')
    back = convert(shared, "ros1")
    original = data[data.index(b"  <transmission"):data.index(b"</robot>")]
    assert back.data.startswith(data[:data.index(b"  <transmission")] + original
                                + b'  <ros2_control name="r" type="system">\n')
    assert back.data.endswith(b'    </joint>\n    <link name="b"/>\n  </ros2_control>\n</robot>\n')
    assert "1 transmission: the original bytes carried by --reversible are put back" in back.notes
