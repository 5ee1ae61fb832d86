"""TX004: whitespace before the XML declaration is read, with a warning.

tinyxml2 (urdfdom, ros2_control) skips whitespace before the declaration; expat (xacro) and
libxml2 reject it.
"""

from __future__ import annotations

from tests.rules.helpers import check, problems

BODY = """<robot name="r">
  <transmission name="t">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="j">
      <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
    </joint>
    <actuator name="m"><mechanicalReduction>0</mechanicalReduction></actuator>
  </transmission>
</robot>
"""


def test_blank_line_before_the_declaration_is_read_and_warned():
    xml = "\n \t\n<?xml version='1.0' encoding='UTF-8'?>\n" + BODY  # the helper drops one \n
    found = problems(xml)
    assert [(p.line, p.column, p.code, p.severity) for p in found] == [
        (2, 1, "TX004", "warning"), (9, 24, "TX106", "error")
    ]
    assert "strict XML parsers (xacro's expat, libxml2) reject it" in found[0].message
    assert "tinyxml2 (urdfdom, ros2_control) skips it" in found[0].message


def test_spaces_on_the_declaration_line_are_reported_at_the_declaration():
    assert check("   <?xml version='1.0'?>\n" + BODY, select=["TX004"]) == [
        (1, 4, "TX004", "warning")
    ]


def test_declaration_first_or_no_declaration_passes():
    assert check("<?xml version='1.0'?>\n" + BODY, select=["TX004", "TX001"]) == []
    assert check("\n\n" + BODY, select=["TX004", "TX001"]) == []


def test_a_comment_before_the_declaration_is_still_tx001():
    found = problems("<!-- licence -->\n<?xml version='1.0'?>\n" + BODY, select=["TX001", "TX004"])
    assert [(p.line, p.column, p.code, p.severity) for p in found] == [(2, 1, "TX001", "error")]


def test_a_byte_order_mark_then_spaces_is_read_too(tmp_path):
    from txtool.io.xmlio import parse_bytes

    data = b"\xef\xbb\xbf \r\n<?xml version='1.0' encoding='UTF-8'?>\r\n" + BODY.encode()
    assert parse_bytes(data, "r.urdf").getroot().get("name") == "r"


def test_xacro_itself_refuses_it_so_a_xacro_file_also_gets_tx002():
    xacro = BODY.replace('<robot name="r">',
                         '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">')
    found = problems("\n  <?xml version='1.0'?>\n" + xacro, filename="r.urdf.xacro",
                     select=["TX002", "TX004"])
    assert [(p.code, p.severity) for p in found] == [("TX002", "error"), ("TX004", "warning")]
    assert "XML or text declaration not at start of entity" in found[0].message
