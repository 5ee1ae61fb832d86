"""Rewriting a document keeps how it is written: its encoding (UTF-8, UTF-16 or UTF-32, either
byte order), its byte-order mark or the lack of one, its XML declaration, its line endings (LF,
CRLF or CR) and its final newline. ``validate`` places findings in such files by line and
column, ``migrate --diff`` shows their text, and a declaration that names another encoding than
the bytes are in is one line.
"""

from __future__ import annotations

import codecs

import pytest
from click.testing import CliRunner
from hypothesis import given, settings
from hypothesis import strategies as st

from tests.foundation.test_convert_bytes import convert, documents
from tests.hardening.hostile_inputs import one_line_error, run
from txtool.cli import cli

# Named, not the default placeholder (which a written conversion points out): what these
# tests check is elsewhere.
MOCK = "mock_components/GenericSystem"

BEFORE = """\
<?xml version="1.0" encoding="{encoding}"?>
<robot name="arm">
  <!-- Gelenk für den Ellbogen: ä ö ü -->
  <link name='a' />
  <link name="b"/><joint name="elbow" type="continuous"><parent link="a"/><child link="b"/></joint>
  <transmission name="elbow_trans">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="elbow"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>
    <actuator name="elbow_motor"><mechanicalReduction>50</mechanicalReduction></actuator>
  </transmission>
</robot>
"""
# The transmission becomes a <ros2_control> block; every other line keeps its text (the link
# keeps its quotes and spaces: the change is written as edits, not the whole document
# serialized).
AFTER = """\
<?xml version="1.0" encoding="{encoding}"?>
<robot name="arm">
  <!-- Gelenk für den Ellbogen: ä ö ü -->
  <link name='a' />
  <link name="b"/><joint name="elbow" type="continuous"><parent link="a"/><child link="b"/></joint>
  <ros2_control name="arm" type="system">
    <hardware>
      <plugin>mock_components/GenericSystem</plugin>
    </hardware>
    <joint name="elbow">
      <command_interface name="effort"/>
      <state_interface name="position"/>
      <state_interface name="velocity"/>
      <state_interface name="effort"/>
    </joint>
    <transmission name="elbow_trans">
      <plugin>transmission_interface/SimpleTransmission</plugin>
      <actuator name="elbow_motor" role="actuator1"/>
      <joint name="elbow" role="joint1">
        <mechanical_reduction>50</mechanical_reduction>
      </joint>
    </transmission>
  </ros2_control>
</robot>
"""

# name: (byte-order mark, codec of the rest, name in the declaration)
FORMS = {
    "UTF-16LE with BOM": (codecs.BOM_UTF16_LE, "utf-16-le", "UTF-16"),
    "UTF-16BE with BOM": (codecs.BOM_UTF16_BE, "utf-16-be", "UTF-16"),
    "UTF-16LE without BOM": (b"", "utf-16-le", "UTF-16"),
    "UTF-16BE without BOM": (b"", "utf-16-be", "UTF-16BE"),
    "UTF-32LE with BOM": (codecs.BOM_UTF32_LE, "utf-32-le", "UTF-32"),
    "UTF-32BE with BOM": (codecs.BOM_UTF32_BE, "utf-32-be", "UTF-32"),
    "UTF-32LE without BOM": (b"", "utf-32-le", "UTF-32LE"),
    "UTF-32BE without BOM": (b"", "utf-32-be", "UTF-32"),
    "UTF-8 with BOM": (codecs.BOM_UTF8, "utf-8", "UTF-8"),
    "UTF-8": (b"", "utf-8", "UTF-8"),
}
NEWLINES = {"LF": "\n", "CRLF": "\r\n", "CR": "\r"}
# Each command that writes a document, and the file it writes.
WRITES = {
    "migrate --write": (["migrate", "--to", "ros2-p2", "--hardware-plugin", MOCK, "--write", "robot.urdf"], "robot.urdf"),
    "convert --write": (["convert", "--to", "ros2-p2", "--hardware-plugin", MOCK, "robot.urdf", "-o", "robot.urdf",
                         "--write"], "robot.urdf"),
    "convert -o": (["convert", "--to", "ros2-p2", "--hardware-plugin", MOCK, "robot.urdf", "-o", "out.urdf"], "out.urdf"),
}


def encode(text: str, form: str, newline: str) -> bytes:
    mark, codec, declared = FORMS[form]
    return mark + text.format(encoding=declared).replace("\n", newline).encode(codec)


def assert_written_as(data: bytes, form: str, newline: str) -> None:
    """``data`` is AFTER in ``form``: the mark as it was, then the expected text, decoded."""
    mark, codec, declared = FORMS[form]
    assert data[:len(mark)] == mark
    assert data[len(mark):len(mark) + 2] != codecs.BOM_UTF16_LE[:2]  # no mark added
    text = data[len(mark):].decode(codec)
    assert text == AFTER.format(encoding=declared).replace("\n", newline)


@pytest.mark.parametrize("newline", NEWLINES)
@pytest.mark.parametrize("form", FORMS)
@pytest.mark.parametrize("write", WRITES)
def test_a_rewritten_document_keeps_its_encoding_mark_and_line_endings(
    tmp_path, monkeypatch, write, form, newline
):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "robot.urdf").write_bytes(encode(BEFORE, form, NEWLINES[newline]))
    args, written = WRITES[write]
    code, _, err = run(*args)
    assert code == 0, err
    assert_written_as((tmp_path / written).read_bytes(), form, NEWLINES[newline])


def stored(document: bytes, form: str) -> bytes:
    """A UTF-8 document (without BOM) in ``form``, its declaration naming that encoding."""
    mark, codec, declared = FORMS[form]
    text = document.decode().replace("encoding='UTF-8'", f"encoding='{declared}'", 1)
    return mark + text.encode(codec)


@settings(max_examples=80, deadline=None)
@given(documents(), st.sampled_from(list(FORMS)), st.sampled_from(["ros2-p1", "ros2-p2"]))
def test_converting_any_document_gives_its_utf8_conversion_in_its_encoding(document, form,
                                                                          target):
    """Declaration or none, comments, blank lines, CRLF or CR, ``<x></x>``, character
    references: what a UTF-16/32 document becomes is what its UTF-8 twin becomes, stored alike;
    and converting back gives the document again, byte for byte, as for the twin."""
    plain = document[0].removeprefix(codecs.BOM_UTF8)
    there = convert(plain, target)
    assert convert(stored(plain, form), target) == stored(there, form)
    assert convert(stored(there, form), "ros1") == stored(convert(there, "ros1"), form)


@pytest.mark.parametrize("form", FORMS)
def test_convert_to_stdout_writes_the_document_in_its_encoding(tmp_path, form):
    (tmp_path / "robot.urdf").write_bytes(encode(BEFORE, form, "\n"))
    result = CliRunner().invoke(cli, ["convert", "--to", "ros2-p2", "--hardware-plugin", MOCK, str(tmp_path / "robot.urdf")])
    assert (result.exit_code, result.stderr) == (0, "")
    assert_written_as(result.stdout_bytes, form, "\n")


@pytest.mark.parametrize("form", FORMS)
def test_a_document_with_nothing_to_change_is_left_byte_for_byte(tmp_path, form):
    document = tmp_path / "robot.urdf"
    document.write_bytes(encode(AFTER, form, "\r"))
    before = document.read_bytes()
    assert run("migrate", "--to", "ros2-p2", "--hardware-plugin", MOCK, "--write", str(document))[0] == 0
    assert document.read_bytes() == before


# Findings name the line and the column (in characters) as an editor shows them.
BROKEN = """\
<?xml version="1.0" encoding="{encoding}"?>
<robot name="ärm">
  <joint name="elbow" type="revolute"><parent link="a"/><child link="b"/></joint>
  <joint name="wrist" type="revolute"><parent link="b"/><child link="c"/></joint>
  <transmission name="elbow_trans">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="elbow"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>
    <!-- txtool: disable-next-line TX106; Übersetzung noch offen -->
    <actuator name="elbow_motor"><mechanicalReduction>0</mechanicalReduction></actuator>
  </transmission>
  <transmission name="wrist_trans">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="wrist"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>
    <!-- Übersetzung: --> <actuator name="wrist_motor"><mechanicalReduction>0</mechanicalReduction></actuator>
  </transmission>
</robot>
"""
# The suppression comment silences the first zero reduction (so it is found on its line).
ZERO_REDUCTION = ("robot.urdf:14:56: error TX106 zero-reduction: reduction of actuator "
                  "'wrist_motor' of transmission 'wrist_trans' is zero: ros_control refuses it "
                  '("Transmission reduction ratio cannot be zero")\n')


@pytest.mark.parametrize("newline", NEWLINES)
@pytest.mark.parametrize("form", FORMS)
def test_validate_places_findings_by_line_and_column(tmp_path, monkeypatch, form, newline):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "robot.urdf").write_bytes(encode(BROKEN, form, NEWLINES[newline]))
    code, out, err = run("validate", "--select", "TX1", "robot.urdf")
    assert (code, out, err) == (1, ZERO_REDUCTION + "Found 1 error in 1 file.\n", "")

    broken = BROKEN.replace("</transmission>\n</robot>", "</transmision>\n</robot>")
    (tmp_path / "robot.urdf").write_bytes(encode(broken, form, NEWLINES[newline]))
    code, out, err = run("validate", "--select", "TX001", "robot.urdf")
    assert (code, err) == (1, "")
    assert out == ("robot.urdf:15:17: error TX001 xml-syntax: Opening and ending tag mismatch: "
                   "transmission line 11 and transmision\nFound 1 error in 1 file.\n")


@pytest.mark.parametrize("newline", NEWLINES)
@pytest.mark.parametrize("form", FORMS)
def test_validate_finds_a_misplaced_declaration_in_any_encoding(tmp_path, monkeypatch, form,
                                                                newline):
    monkeypatch.chdir(tmp_path)
    document = tmp_path / "robot.urdf"
    document.write_bytes(encode("<!-- licence -->\n" + BEFORE, form, NEWLINES[newline]))
    assert run("validate", "--select", "TX0", "robot.urdf")[1].splitlines()[0] == (
        "robot.urdf:2:1: error TX001 xml-syntax: XML declaration not at the start of the "
        "document (it follows a comment): not well-formed, so xacro and other strict XML "
        "parsers reject the file")
    document.write_bytes(encode("\n  " + BEFORE, form, NEWLINES[newline]))
    assert run("validate", "--select", "TX004", "robot.urdf")[1].splitlines()[0].startswith(
        "robot.urdf:2:3: warning TX004 space-before-declaration: whitespace before the XML "
        "declaration")


@pytest.mark.parametrize("form", ["UTF-16LE with BOM", "UTF-32BE without BOM", "UTF-8 with BOM"])
def test_migrate_diff_shows_the_text(tmp_path, monkeypatch, form):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "robot.urdf").write_bytes(encode(BEFORE, form, "\n"))
    code, out, err = run("migrate", "--to", "ros2-p2", "--hardware-plugin", MOCK, "--diff", "robot.urdf")
    assert (code, err) == (1, "would change robot.urdf (1 transmission(s) to ros2-p2)\n"
                              "1 file(s) would be changed\n")
    declared = FORMS[form][2]
    assert out.startswith(
        "--- a/robot.urdf\n+++ b/robot.urdf\n@@ -3,9 +3,22 @@\n"
        "   <!-- Gelenk für den Ellbogen: ä ö ü -->\n   <link name='a' />\n")
    assert "\x00" not in out and "\ufeff" not in out and declared not in out
    assert "+  <ros2_control name=\"arm\" type=\"system\">\n" in out


def test_migrate_diff_of_a_utf16_document_applies_to_its_text(tmp_path, monkeypatch):
    """The diff is of the text: applied to the text decoded, it gives the text written."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "robot.urdf").write_bytes(encode(BEFORE, "UTF-16LE with BOM", "\n"))
    out = run("migrate", "--to", "ros2-p2", "--hardware-plugin", MOCK, "--diff", "robot.urdf")[1]
    removed = [line[1:] for line in out.splitlines()[3:] if line[:1] in " -"]
    added = [line[1:] for line in out.splitlines()[3:] if line[:1] in " +"]
    before = BEFORE.format(encoding="UTF-16").splitlines()
    after = AFTER.format(encoding="UTF-16").splitlines()
    assert (before[2:], after[2:]) == (removed, added)


# A declaration that names an encoding the bytes are not in (libxml2 would silently follow the
# byte-order mark, or fail with "Blank needed here"): one line, exit 2, naming both.
MISMATCHES = {
    "UTF-8 bytes declared UTF-16": (
        BEFORE.format(encoding="UTF-16").encode(),
        'the XML declaration says encoding="UTF-16", but the document is not written in '
        "UTF-16 (it has no byte-order mark and one byte per ASCII character); correct the "
        "declaration or save the file as UTF-16"),
    "UTF-16LE with BOM declared ISO-8859-1": (
        codecs.BOM_UTF16_LE + BEFORE.format(encoding="ISO-8859-1").encode("utf-16-le"),
        'the XML declaration says encoding="ISO-8859-1", but the document is written in '
        "UTF-16LE (by its byte-order mark); correct the declaration or save the file as "
        "ISO-8859-1"),
    "UTF-16BE without BOM declared UTF-16LE": (
        BEFORE.format(encoding="UTF-16LE").encode("utf-16-be"),
        'the XML declaration says encoding="UTF-16LE", but the document is written in '
        "UTF-16BE (by the zero bytes around its first letters); correct the declaration "
        "or save the file as UTF-16LE"),
    "UTF-32LE declared UTF-16": (
        codecs.BOM_UTF32_LE + BEFORE.format(encoding="UTF-16").encode("utf-32-le"),
        'the XML declaration says encoding="UTF-16", but the document is written in '
        "UTF-32LE (by its byte-order mark); correct the declaration or save the file as "
        "UTF-16"),
    "UTF-8 BOM declared ISO-8859-1": (
        codecs.BOM_UTF8 + BEFORE.format(encoding="ISO-8859-1").encode(),
        'the XML declaration says encoding="ISO-8859-1", but the document is written in '
        "UTF-8 (by its byte-order mark); correct the declaration or save the file as "
        "ISO-8859-1"),
}


@pytest.mark.parametrize("case", MISMATCHES)
def test_a_declaration_that_names_another_encoding_is_one_line(tmp_path, case):
    data, reason = MISMATCHES[case]
    document = tmp_path / "robot.urdf"
    document.write_bytes(data)
    expected = f"txtool: {document}:1:31: {reason}"
    for args in (["show"], ["convert", "--to", "ros2-p2", "--hardware-plugin", MOCK]):
        code, out, err = run(*args, str(document))
        assert (code, out, one_line_error(err)) == (2, "", expected), args
    code, out, err = run("migrate", "--to", "ros2-p2", "--hardware-plugin", MOCK, "--write", str(document))
    assert (code, out, err) == (2, "", f"{expected}\n1 file(s) could not be read or written\n")
    assert document.read_bytes() == data
    code, out, err = run("validate", str(document))
    assert (code, err) == (1, "")
    assert out == (f"{document}:1:31: error TX001 xml-syntax: {reason}\n"
                   "Found 1 error in 1 file.\n")
