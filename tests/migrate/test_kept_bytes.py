"""What a migration does not change keeps its bytes: quotes, spaces, line endings, marks."""

from __future__ import annotations

import textwrap

from txtool.rules import all_rules
from txtool.transform.migrate import MigrateOptions, migrate_file, unified_diff

FIXES = [rule for rule in all_rules().values() if rule.fixable]


def _migrate(tmp_path, text: str, **options) -> bytes:
    path = tmp_path / "robot.urdf"
    path.write_bytes(textwrap.dedent(text).lstrip("\n").encode())
    return migrate_file(str(path), FIXES, MigrateOptions(**options)).data


def test_formatting_outside_the_changed_lines_is_kept(tmp_path):
    data = _migrate(tmp_path, """
        <robot name='r'>
          <link
              name = 'base' />
          <joint name="j" type='revolute'><parent link="base"/><child link="tip"/></joint>
          <transmission name="t" type="SimpleTransmission">
            <type>transmission_interface/SimpleTransmission</type>
            <joint name="j"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>
            <actuator name="m"/>
          </transmission>
          <gazebo reference='tip' >&#x20;<mu1 value = "1"/></gazebo>
        </robot>
        """)
    assert data.decode() == textwrap.dedent("""\
        <robot name='r'>
          <link
              name = 'base' />
          <joint name="j" type='revolute'><parent link="base"/><child link="tip"/></joint>
          <transmission name="t">
            <type>transmission_interface/SimpleTransmission</type>
            <joint name="j"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>
            <actuator name="m"/>
          </transmission>
          <gazebo reference='tip' >&#x20;<mu1 value = "1"/></gazebo>
        </robot>
        """)


def test_a_changed_start_tag_keeps_the_quotes_and_spaces_of_what_it_did_not_change(tmp_path):
    """Only the dropped attribute (and the space before it) goes: the name keeps its quotes
    and the tag its space before ``>`` (a line-based writer wrote the whole line anew)."""
    data = _migrate(tmp_path, """
        <robot name="r">
          <transmission name='t' type='SimpleTransmission' >
            <type>transmission_interface/SimpleTransmission</type>
            <joint name="j"/>
            <actuator name="m"/>
          </transmission>
        </robot>
        """)
    assert data.decode() == textwrap.dedent("""\
        <robot name="r">
          <transmission name='t' >
            <type>transmission_interface/SimpleTransmission</type>
            <joint name="j"/>
            <actuator name="m"/>
          </transmission>
        </robot>
        """)


def test_a_missing_final_newline_is_marked_in_the_diff():
    assert unified_diff("/abs/r.urdf", b"<a/>", b"<b/>") == (
        "--- a/abs/r.urdf\n+++ b/abs/r.urdf\n@@ -1 +1 @@\n"
        "-<a/>\n\\ No newline at end of file\n"
        "+<b/>\n\\ No newline at end of file\n"
    )


def test_cr_line_endings_and_a_byte_order_mark_are_kept(tmp_path):
    path = tmp_path / "robot.urdf"
    text = ("<?xml version='1.0'?>\r<robot name='r'>\r  <link name='a'></link>\r"
            "  <transmission name='t'>\r"
            "    <type>transmission_interface/SimpleTransmission</type>\r"
            "    <joint name='j'><hardwareInterface>EffortJointInterface</hardwareInterface>"
            "</joint>\r    <actuator name='m'><mechanicalReduction>2</mechanicalReduction>"
            "</actuator>\r  </transmission>\r</robot>\r")
    path.write_bytes(b"\xef\xbb\xbf" + text.encode())
    data = migrate_file(str(path), FIXES, MigrateOptions()).data
    # Only the prefix comes in: the rest of the changed line keeps its quotes.
    assert data == b"\xef\xbb\xbf" + text.replace(
        "<hardwareInterface>EffortJointInterface",
        "<hardwareInterface>hardware_interface/EffortJointInterface").encode()
