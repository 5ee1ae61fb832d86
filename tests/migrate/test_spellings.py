"""What the writer and migrate's quick byte scan must tell apart: a value whose bytes differ
only in quotes or spacing is changed where the change made it so, and kept where it did not;
the scan finds what a fix looks for however XML lets it be spelt."""

from __future__ import annotations

import pytest
from lxml import etree

from txtool.io.xmlio import parse_bytes
from txtool.transform.edits.core import EditedText
from txtool.transform.edits.spans import SpanIndex
from txtool.transform.edits.tree_edits import TreeChange

ORIGINAL = (b"<robot name='r'>\n"
            b"  <link  name = 'a b' />\n"
            b"  <link name='c'/>\n"
            b"  <link name=\"d\"   />\n"
            b"</robot>\n")


def _edited(change) -> bytes:
    """ORIGINAL with ``change`` made to its parse, written as edits."""
    tree = parse_bytes(ORIGINAL, "r.urdf")
    text = EditedText(ORIGINAL)
    root = tree.getroot()
    index = SpanIndex(text.data, root, list(root))
    recorded = TreeChange(list(root))
    change(root)
    return text.applied(recorded.edits(text, index))


@pytest.mark.parametrize("value", ["a  b", "a\tb", "a'b", 'a"b', " a b"])
def test_a_value_the_change_made_differ_only_in_spacing_or_quotes_is_written(value):
    out = _edited(lambda root: root[0].set("name", value))
    assert [link.get("name") for link in etree.fromstring(out)] == [value, "c", "d"]
    # The lines the change left alone keep their bytes, quotes and spacing.
    assert out.splitlines()[2:] == ORIGINAL.splitlines()[2:]
    assert out.splitlines()[1].startswith(b"  <link  name = '")


def test_what_reads_alike_but_for_quotes_and_spacing_keeps_its_bytes():
    out = _edited(lambda root: root[1].set("name", "e"))
    assert out == ORIGINAL.replace(b"  <link name='c'/>\n", b"  <link name='e'/>\n")


LEGACY = """\
<robot name="r">
  <transmission name="t" {attribute}>
    <joint name="j">
      <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
    </joint>
    <actuator name="m">
      <mechanicalReduction>50</mechanicalReduction>
    </actuator>
  </transmission>
</robot>
"""


@pytest.mark.parametrize("attribute", [
    'type="SimpleTransmission"', 'type = "SimpleTransmission"', "type='SimpleTransmission'",
    "type\n    =\n    'SimpleTransmission'", "type\t= 'SimpleTransmission'"])
def test_the_scan_finds_a_type_attribute_however_it_is_spelt(run, write, attribute):
    path = write("r.urdf", LEGACY.format(attribute=attribute))
    code, _, err = run("migrate", "--check", str(path))
    assert (code, err) == (1, f"would change {path} (TX302 x1)\n1 file(s) would be changed\n")


UNPREFIXED = """\
<robot name="r">
  <transmission name="t">
    <type>transmission_interface/SimpleTransmission</type>
    <joint {name}>
      <{tag}>{interface}</hardwareInterface>
    </joint>
    <actuator name="m">
      <mechanicalReduction>50</mechanicalReduction>
    </actuator>
  </transmission>
</robot>
"""


@pytest.mark.parametrize("name", ['name="j"', "name='j'", 'name = "j"', "name\n      ='j'"])
@pytest.mark.parametrize("tag", ["hardwareInterface", "hardwareInterface ",
                                 "hardwareInterface\n      "])
def test_the_scan_finds_an_unprefixed_interface_however_it_is_spelt(run, write, name, tag):
    path = write("r.urdf", UNPREFIXED.format(name=name, tag=tag,
                                             interface="EffortJointInterface"))
    code, _, err = run("migrate", "--check", str(path))
    assert (code, err) == (1, f"would change {path} (TX300 x1)\n1 file(s) would be changed\n")
    prefixed = write("p.urdf", UNPREFIXED.format(
        name=name, tag=tag, interface="hardware_interface/EffortJointInterface"))
    assert run("migrate", "--check", str(prefixed))[0] == 0
