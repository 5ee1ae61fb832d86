"""The one applier of edits: what it changes, what it refuses, and that every byte outside an
edit stays as it was."""

from __future__ import annotations

import codecs

import pytest
from hypothesis import given
from hypothesis import strategies as st

from txtool.transform.edits.core import Edit, EditedText, apply_edits


def test_an_insertion_a_deletion_and_a_replacement_in_one_pass() -> None:
    original = b'<joint name="j"><hardwareInterface>Effort</hardwareInterface><x/></joint>'
    name, at, gone = original.index(b'"j"') + 1, original.index(b"Effort"), original.index(b"<x/>")
    edits = [Edit.replacement(name, name + 1, b"elbow"),
             Edit.insertion(at, b"hardware_interface/"),
             Edit.deletion(gone, gone + len(b"<x/>"))]
    assert apply_edits(original, reversed(edits)) == (
        b'<joint name="elbow"><hardwareInterface>hardware_interface/Effort'
        b"</hardwareInterface></joint>")


def test_no_edits_give_the_original_itself() -> None:
    assert apply_edits(b"<robot/>", []) == b"<robot/>"


def test_insertions_at_one_offset_keep_the_order_given() -> None:
    assert apply_edits(b"ab", [Edit.insertion(1, b"1"), Edit.insertion(1, b"2"),
                               Edit.replacement(1, 2, b"B")]) == b"a12B"


@pytest.mark.parametrize("edits", [
    [Edit.replacement(0, 3, b"x"), Edit.replacement(2, 4, b"y")],
    [Edit.replacement(0, 3, b"x"), Edit.insertion(1, b"y")],
])
def test_overlapping_edits_are_refused(edits: list[Edit]) -> None:
    with pytest.raises(ValueError, match="overlap at byte"):
        apply_edits(b"abcdef", edits)


def test_an_edit_past_the_end_or_backwards_is_refused() -> None:
    with pytest.raises(ValueError, match="past the end"):
        apply_edits(b"abc", [Edit.deletion(2, 4)])
    with pytest.raises(ValueError, match="not a byte range"):
        Edit(3, 2)


@given(st.binary(max_size=200), st.lists(st.tuples(st.integers(0, 200), st.integers(0, 8),
                                                   st.binary(max_size=6)), max_size=8))
def test_bytes_outside_the_edits_are_the_original_bytes(original: bytes,
                                                        drawn: list[tuple[int, int, bytes]]
                                                        ) -> None:
    edits, taken = [], -1
    for start, length, content in sorted(drawn):
        start = min(start, len(original))
        if start <= taken:
            continue  # the next one starts after the last one ended
        end = min(start + length, len(original))
        edits.append(Edit(start, end, content))
        taken = end
    result = apply_edits(original, edits)
    # Walking the edits in order, the bytes between them are copied one for one.
    at = out = 0
    for edit in edits:
        assert result[out:out + edit.start - at] == original[at:edit.start]
        out += edit.start - at
        assert result[out:out + len(edit.content)] == edit.content
        out += len(edit.content)
        at = edit.end
    assert result[out:] == original[at:]


def test_a_utf16_document_is_edited_in_its_utf8_form_and_stored_back() -> None:
    original = codecs.BOM_UTF16_LE + '<?xml version="1.0" encoding="UTF-16"?>\r\n<robot/>\r\n'.encode(
        "utf-16-le")
    text = EditedText(original)
    assert text.data == b'<?xml version="1.0" encoding="UTF-8"?>\r\n<robot/>\r\n'
    at = text.data.index(b"/>")
    written = text.applied([Edit.replacement(at, at + 2, text.encode('>\n  <link name="é"/>\n</robot>'))])
    assert written == codecs.BOM_UTF16_LE + (
        '<?xml version="1.0" encoding="UTF-16"?>\r\n<robot>\r\n  <link name="é"/>\r\n</robot>\r\n'
    ).encode("utf-16-le")
    assert text.applied([]) is original


@pytest.mark.parametrize("pad", [0, 1])
@pytest.mark.parametrize("codec", ["utf-16-le", "utf-16-be", "utf-32-le"])
def test_a_wide_document_larger_than_a_piece_is_stored_back_whole(codec: str, pad: int) -> None:
    """Stored back a piece at a time: the characters of a text of nothing but two- and
    four-byte UTF-8 characters (one of the two paddings puts one across any given byte
    boundary), and the declaration's own encoding name, come back as they were."""
    declared = codec.replace("-le", "").replace("-be", "").upper()
    text = (f'<?xml version="1.0" encoding="{declared}"?>\n<robot><link name="'
            + "x" * pad + "é𝄞" * 200_000 + '"/></robot>\n')  # over 1 MiB as UTF-8
    mark = "\ufeff".encode(codec)
    original = mark + text.encode(codec)
    edited = EditedText(original)
    at = edited.data.index(b"</robot>")
    written = edited.applied([Edit.insertion(at, edited.encode('<link name="new"/>'))])
    assert written == mark + text.replace("</robot>", '<link name="new"/></robot>').encode(codec)


def test_new_text_takes_the_documents_line_ending_and_encoding() -> None:
    text = EditedText(b'<?xml version="1.0" encoding="ISO-8859-1"?>\r<robot/>\r')
    assert text.encode("<a>\u00e9\u20ac</a>\n") == b"<a>\xe9&#8364;</a>\r"
    assert EditedText(b"<robot/>").newline == "\n"
