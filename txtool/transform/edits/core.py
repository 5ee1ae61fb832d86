"""A change to a document as edits: byte ranges of the original and what replaces them.

The model is that of ruff's fixes (``crates/ruff_diagnostics/src/edit.rs``, ``Edit``; applied
by ``crates/ruff_linter/src/fix/mod.rs``, ``apply_fixes``): whatever changes a document only
says which bytes go and what comes in their place, and :func:`apply_edits` is the one place
that makes the new bytes. Every byte outside an edit is copied from the original, so what a
change does not touch keeps its text by construction.

UTF-16 and UTF-32 documents are edited in their UTF-8 form (:class:`EditedText`), as the
scanners read them, and stored back as they were.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass

from txtool.io.encodings import Encoding, detect_encoding, utf8_form


@dataclass(frozen=True, order=True, slots=True)
class Edit:
    """Replace the bytes ``[start, end)`` of the original by ``content``: an insertion where
    ``start == end``, a deletion where ``content`` is empty."""

    start: int
    end: int
    content: bytes = b""

    def __post_init__(self) -> None:
        if not 0 <= self.start <= self.end:
            raise ValueError(f"not a byte range: [{self.start}, {self.end})")

    @classmethod
    def insertion(cls, at: int, content: bytes) -> Edit:
        return cls(at, at, content)

    @classmethod
    def deletion(cls, start: int, end: int) -> Edit:
        return cls(start, end)

    @classmethod
    def replacement(cls, start: int, end: int, content: bytes) -> Edit:
        return cls(start, end, content)


def apply_edits(original: bytes, edits: Iterable[Edit]) -> bytes:
    """``original`` with ``edits`` made, in one pass; every other byte is copied verbatim.

    The edits are taken in order of their ranges (insertions at the same offset in the order
    given); two that overlap, or one past the end of ``original``, are refused
    (:class:`ValueError`): which one would win is not for the applier to guess.
    """
    kept = memoryview(original)  # what is copied is copied once, into the result
    parts: list[bytes | memoryview] = []
    copied = 0
    for edit in _in_order(edits, len(original)):
        parts.append(kept[copied:edit.start])
        parts.append(edit.content)
        copied = edit.end
    parts.append(kept[copied:])
    return b"".join(parts)


def compose(first: Sequence[Edit], second: Sequence[Edit], original: bytes) -> list[Edit]:
    """One list of edits of ``original`` that makes what ``first`` and then ``second`` make.

    ``first`` edits ``original`` into ``middle = apply_edits(original, first)`` and ``second``
    edits ``middle``; applying the result to ``original`` gives ``apply_edits(middle, second)``.
    Edits that overlap or touch, in ``middle`` (an edit of ``second`` inside, across or next to
    what an edit of ``first`` put there, or two edits side by side), become one edit: its range
    the union of their ranges in ``original``, its content the final bytes for that range. So
    the result is in order, no two of its edits overlap or touch, and a byte that neither stage
    touched lies outside every one of them. Insertions at one offset keep the order given.
    Overlapping edits, or one past the end, are refused (:class:`ValueError`) as by
    :func:`apply_edits`. The work is in the edits and the bytes they cover, not the document.
    """
    images: list[tuple[int, int, Edit]] = []  # where each edit of first is in middle
    shift = 0  # len(middle) - len(original) so far
    for edit in _in_order(first, len(original)):
        images.append((edit.start + shift, edit.start + shift + len(edit.content), edit))
        shift += len(edit.content) - (edit.end - edit.start)
    later = _in_order(second, len(original) + shift)
    composed: list[Edit] = []
    i = j = shift = 0
    while i < len(images) or j < len(later):
        # A group opens at the first edit not taken yet and takes every edit that starts
        # before or where it ends; [start, end) is its range in middle.
        if j == len(later) or (i < len(images) and images[i][0] <= later[j].start):
            start = end = images[i][0]
        else:
            start = end = later[j].start
        origin = start - shift  # where it starts in original
        earlier: list[Edit] = []
        after: list[Edit] = []
        while True:
            if i < len(images) and images[i][0] <= end:
                edit = images[i][2]
                earlier.append(edit)
                end = max(end, images[i][1])
                shift += len(edit.content) - (edit.end - edit.start)
                i += 1
            elif j < len(later) and later[j].start <= end:
                after.append(later[j])
                end = max(end, later[j].end)
                j += 1
            else:
                break
        middle = apply_edits(original[origin:end - shift], [
            Edit(edit.start - origin, edit.end - origin, edit.content) for edit in earlier])
        content = apply_edits(middle, [
            Edit(edit.start - start, edit.end - start, edit.content) for edit in after])
        composed.append(Edit(origin, end - shift, content))
    return composed


def _in_order(edits: Iterable[Edit], length: int) -> list[Edit]:
    """``edits`` in the order :func:`apply_edits` takes them, refused as it refuses them."""
    ordered, end = sorted(edits, key=lambda edit: (edit.start, edit.end)), 0
    for edit in ordered:
        if edit.start < end:
            raise ValueError(f"edits overlap at byte {edit.start}")
        end = edit.end
    if end > length:
        raise ValueError(f"edit past the end of the document: byte {end}")
    return ordered


class EditedText:
    """The bytes a document's edits address, how new text is stored in them, and the document
    they make (in the encoding it was read in)."""

    def __init__(self, original: bytes) -> None:
        self.original = original
        self.stored: Encoding = detect_encoding(original)
        self.data = utf8_form(original)  # the original itself unless UTF-16 or UTF-32
        self.codec = "utf-8" if self.stored.wide else self.stored.codec
        self.newline = _newline(self.data)

    def encode(self, text: str) -> bytes:
        """``text`` (already escaped as markup) as bytes of this document: its line breaks
        those of the document, a character its encoding cannot store as a reference."""
        if self.newline != "\n":
            text = text.replace("\n", self.newline)
        return text.encode(self.codec, "xmlcharrefreplace")

    def applied(self, edits: Iterable[Edit]) -> bytes:
        """The document with ``edits`` made, stored as the original was."""
        edits = list(edits)
        if not edits:
            return self.original
        written = apply_edits(self.data, edits)
        return self.stored.from_utf8(written) if self.stored.wide else written


def _newline(data: bytes) -> str:
    """The line ending most lines end with (LF when there is no line break)."""
    if b"\r" not in data:
        return "\n"
    crlf = data.count(b"\r\n")
    cr, lf = data.count(b"\r") - crlf, data.count(b"\n") - crlf
    count, ending = max(((crlf, "\r\n"), (cr, "\r"), (lf, "\n")), key=lambda pair: pair[0])
    return ending if count else "\n"
