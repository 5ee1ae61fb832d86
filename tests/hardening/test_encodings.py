"""Encodings and odd documents: BOMs, UTF-16, Latin-1, a late declaration, empty files,
folders, unreadable files and binary data, through show, validate and convert.

Every failure is one line ``txtool: path[:line[:col]]: reason`` with exit 2, except in
``validate``, where a document that is not XML is a TX001 finding (exit 1).
"""

from __future__ import annotations

import gzip
import json
import os
import random
import re
from pathlib import Path

import pytest
from click.testing import CliRunner
from hypothesis import given
from hypothesis import strategies as st
from lxml import etree

from tests.corpus import corpus_dir, corpus_file
from tests.hardening.hostile_inputs import one_line_error, robot, run
from txtool.cli import cli
from txtool.io.encodings import document_text, text_lines
from txtool.io.xmlio import parse_bytes

# Named, not the default placeholder (which a written conversion points out): what these
# tests check is elsewhere.
MOCK = "mock_components/GenericSystem"

GERMAN = robot(joint="gelenk_ä", transmission="getriebe_ä",
               comment="\n  <!-- Getriebe für das Gelenk: ä ö ü ß -->")


def encoded(declared: str | None, codec: str, mark: bytes = b"") -> bytes:
    """GERMAN in ``codec``, with ``declared`` in the XML declaration (or none)."""
    text = GERMAN if declared is None else GERMAN.replace(
        '<?xml version="1.0"?>', f'<?xml version="1.0" encoding="{declared}"?>', 1)
    return mark + text.encode(codec)


ENCODINGS = {
    "utf-8 with BOM": encoded(None, "utf-8", b"\xef\xbb\xbf"),
    "utf-16-le with BOM": encoded("UTF-16", "utf-16-le", b"\xff\xfe"),
    "utf-16-be with BOM": encoded("UTF-16", "utf-16-be", b"\xfe\xff"),
    "latin-1": encoded("ISO-8859-1", "latin-1"),
}


def transmissions(path: Path) -> list[dict]:
    """show's JSON of ``path``, without locations (they differ between documents)."""
    code, out, err = run("show", "--format", "json", str(path))
    assert (code, err) == (0, ""), err
    found = json.loads(out)["transmissions"]
    for transmission in found:
        for member in (transmission, *transmission["joints"], *transmission["actuators"]):
            member.pop("location")
        transmission.pop("dialect")
    return found


@pytest.mark.parametrize("name", ENCODINGS)
def test_encoded_robot_is_read_validated_and_converted(tmp_path, name):
    document = tmp_path / "robot.urdf"
    document.write_bytes(ENCODINGS[name])

    original = transmissions(document)
    assert [t["name"] for t in original] == ["getriebe_ä"]
    assert [j["name"] for j in original[0]["joints"]] == ["gelenk_ä"]
    assert run("validate", str(document)) == (0, "No problems in 1 file.\n", "")

    ros2 = tmp_path / "robot.ros2.urdf"
    back = tmp_path / "robot.back.urdf"
    assert run("convert", "--to", "ros2-p2", "--hardware-plugin", MOCK, str(document), "-o", str(ros2))[0] == 0
    assert run("convert", "--to", "ros1", str(ros2), "-o", str(back))[0] == 0
    for converted in (ros2, back):
        text = document_text(converted.read_bytes())
        assert "gelenk_ä" in text and "Getriebe für das Gelenk: ä ö ü ß" in text
        parse_bytes(converted.read_bytes(), str(converted))
    assert transmissions(back) == original


@pytest.mark.parametrize("name", ["utf-16-le with BOM", "latin-1"])
def test_convert_to_stdout_keeps_the_text(tmp_path, name):
    document = tmp_path / "robot.urdf"
    document.write_bytes(ENCODINGS[name])
    result = CliRunner().invoke(cli, ["convert", "--to", "ros2-p2", "--hardware-plugin", MOCK, str(document)])
    assert (result.exit_code, result.stderr) == (0, "")
    # Written in the encoding the declaration names, as a redirect to a file needs.
    tree = parse_bytes(result.stdout_bytes, "stdout")
    assert {j.get("name") for j in tree.iter("joint")} == {"gelenk_ä"}


def test_utf16_positions_point_at_the_element(tmp_path):
    document = tmp_path / "robot.urdf"
    document.write_bytes(ENCODINGS["utf-16-le with BOM"])
    code, out, _ = run("show", "--format", "json", str(document))
    assert code == 0
    assert json.loads(out)["transmissions"][0]["location"]["column"] == 3


def test_document_text_follows_the_mark_or_declaration():
    for name, data in ENCODINGS.items():
        assert document_text(data) == GERMAN.replace('"1.0"?>', _declared(name), 1), name
    assert document_text(b"<r>\xff</r>") == "<r>\ufffd</r>"


@given(st.text(alphabet="a <>\r\n\x0c\x85\u2028", max_size=40))
def test_lines_are_cut_where_libxml2_counts_lines(text):
    """At CR LF, CR and LF alone (not at form feed, NEL or U+2028, which XML text may hold),
    each line without its break, as a finding's line and column count them."""
    lines = text_lines(text.encode("utf-8"))
    assert list(lines) == re.split(r"\r\n|\r|\n", text)
    assert [lines.text[slice(*lines.span(n))] for n in range(len(lines))] == list(lines)


def _declared(name: str) -> str:
    return {"utf-8 with BOM": '"1.0"?>', "latin-1": '"1.0" encoding="ISO-8859-1"?>'}.get(
        name, '"1.0" encoding="UTF-16"?>')


def test_declaration_after_a_comment_is_read_and_flagged():
    """A corpus file has a licence comment before ``<?xml ...?>``: read, but TX001 in validate."""
    manifest = (corpus_dir() / "MANIFEST.tsv").read_text()
    late = [line.split("\t")[0] for line in manifest.splitlines()
            if "BEFORE the <?xml ...?> declaration" in line]
    assert late == ["shadow__shadowhand_motor.urdf"]
    path = corpus_file(late[0])
    declaration_line = path.read_bytes().split(b"\n").index(
        next(line for line in path.read_bytes().split(b"\n") if line.startswith(b"<?xml"))) + 1

    code, out, err = run("show", "--format", "json", str(path))
    assert (code, err) == (0, "") and len(json.loads(out)["transmissions"]) == 24
    code, out, err = run("validate", "--format", "json", str(path))
    assert (code, err) == (1, "")
    problems = json.loads(out)["problems"]
    assert [(p["code"], p["line"]) for p in problems] == [("TX001", declaration_line)]
    code, out, err = run("convert", "--to", "ros2-p2", "--hardware-plugin", MOCK, str(path))
    # custom types, left as written: no <ros2_control>, which ros2_control refuses whole
    assert (code, out) == (1, "") and err.count("is not converted") == 24
    assert "ros2_control refuses this robot whole" in err
    code, out, err = run("convert", "--to", "ros2-p2", "--hardware-plugin", MOCK,
                         "--allow-lossy", str(path))
    assert code == 0 and err.count("is not converted") == 24
    # Printed byte for byte but for the declaration, which strict parsers refuse there.
    lines = path.read_bytes().split(b"\n")
    del lines[declaration_line - 1]
    assert out.encode() == b"\n".join(lines)
    etree.fromstring(out.encode())


BLANK_REASON = "document is empty"
BINARY_REASON = "not an XML document (binary data)"
ODD_DOCUMENTS = {
    "empty": (b"", BLANK_REASON),
    "whitespace only": (b"  \n\t\n  \n", BLANK_REASON),
    "BOM and whitespace": (b"\xef\xbb\xbf \n", BLANK_REASON),
    "random bytes": (random.Random(6).randbytes(4096), BINARY_REASON),
    "NUL-led bytes": (b"\x00" * 16 + b"<robot/>", BINARY_REASON),
    "PNG": (b"\x89PNG\r\n\x1a\n\x00\x00\x00\rIHDR" + bytes(range(64)), BINARY_REASON),
    "gzip": (gzip.compress(GERMAN.encode(), mtime=0), BINARY_REASON),
    # A UTF-16 mark before UTF-8 text: an odd number of bytes follows it.
    "UTF-16 mark, odd length": (
        b'\xff\xfe<?xml version="1.0"?><robot name="r"/>\n',
        "cannot decode the document: 'utf-16-le' codec can't decode byte 0x0a in position 38: "
        "truncated data"),
}


@pytest.mark.parametrize("name", ODD_DOCUMENTS)
def test_odd_document_is_one_line_and_a_finding_in_validate(tmp_path, name):
    data, reason = ODD_DOCUMENTS[name]
    document = tmp_path / "robot.urdf"
    document.write_bytes(data)
    expected = f"txtool: {document}:1:1: {reason}"
    for args in (["show"], ["convert", "--to", "ros2-p2", "--hardware-plugin", MOCK]):
        code, out, err = run(*args, str(document))
        assert (code, out, one_line_error(err)) == (2, "", expected), args
    code, out, err = run("validate", str(document))
    assert (code, err) == (1, "")
    assert out == (f"{document}:1:1: error TX001 xml-syntax: {reason}\n"
                   "Found 1 error in 1 file.\n")


def test_a_stray_control_character_is_not_called_binary(tmp_path):
    document = tmp_path / "robot.urdf"
    document.write_bytes(GERMAN.replace("getriebe_ä", "getriebe\x0c").encode())
    code, out, err = run("show", str(document))
    assert (code, out) == (2, "")
    assert "binary" not in one_line_error(err) and err.startswith(f"txtool: {document}:")


def test_a_folder_named_like_a_file_is_one_line(tmp_path):
    folder = tmp_path / "robot.urdf"
    folder.mkdir()
    for args in (["show"], ["convert", "--to", "ros1"], ["roundtrip"]):
        code, out, err = run(*args, str(folder))
        assert (code, out, one_line_error(err)) == (2, "", f"txtool: {folder}: is a directory")


def test_an_unreadable_file_is_one_line(tmp_path, monkeypatch):
    document = tmp_path / "robot.urdf"
    document.write_text(GERMAN)
    if os.geteuid() == 0:  # root reads anything: make reading it fail as it would for a user
        real = os.open

        def denied(file, *args, **kwargs):
            if os.fspath(file) == str(document):
                raise PermissionError(13, "Permission denied", str(file))
            return real(file, *args, **kwargs)

        monkeypatch.setattr(os, "open", denied)
    else:
        document.chmod(0)
    expected = f"txtool: {document}: permission denied"
    for args in (["show"], ["convert", "--to", "ros1"]):
        code, out, err = run(*args, str(document))
        assert (code, out, one_line_error(err)) == (2, "", expected), args
    code, out, err = run("validate", str(document))
    assert (code, one_line_error(err)) == (2, expected)
    assert out == "1 file could not be read; nothing was checked.\n"
