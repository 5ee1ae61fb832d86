"""How a document's text is stored, and the forms the readers and writers work on.

The encoding comes from the byte-order mark, else from the zero bytes UTF-16 and UTF-32 put
around the first (ASCII) characters, else from the XML declaration; UTF-8 by default. Byte
scanners, the span index and the edits read UTF-16/32 documents in :func:`utf8_form`, and the
writers store what they produce back with :meth:`Encoding.from_utf8`.
"""

from __future__ import annotations

import codecs
import io
import re
from array import array
from collections.abc import Sequence
from functools import lru_cache
from typing import NamedTuple, overload

_MARKS = (  # UTF-32 first: its little-endian mark starts like UTF-16's
    (codecs.BOM_UTF32_LE, "utf-32-le"), (codecs.BOM_UTF32_BE, "utf-32-be"),
    (codecs.BOM_UTF8, "utf-8"), (codecs.BOM_UTF16_LE, "utf-16-le"),
    (codecs.BOM_UTF16_BE, "utf-16-be"),
)


# What from_utf8 stores at a time: at least _HEAD characters, whatever the text.
_PIECE = 1 << 20

# Encodings that store ASCII as ASCII, one byte each: a byte pattern finds every tag.
SCANNABLE = frozenset({"utf-8", "ascii", "iso8859-1", "cp1252"})


class Encoding(NamedTuple):
    """How a document's text is stored: the codec, the byte-order mark before the text (empty
    when there is none) and the name the XML declaration gives (None when it gives none)."""

    codec: str
    mark: bytes = b""
    declared: str | None = None

    @property
    def wide(self) -> bool:
        """UTF-16 or UTF-32: a line break or ``<`` is not one byte, so byte scanners cannot
        read it; see :func:`utf8_form`."""
        return self.codec.startswith(("utf-16", "utf-32"))

    def decode(self, data: bytes, errors: str = "strict") -> str:
        """The text of a document stored this way (its mark, if it has one, dropped)."""
        return data.removeprefix(self.mark).decode(self.codec, errors)

    def from_utf8(self, data: bytes) -> bytes:
        """A document in :func:`utf8_form` stored back this way: the mark, the declaration's
        own encoding name and the codec as before. Stored a piece at a time: the document is
        never held whole as text beside the bytes it becomes."""
        stored = io.BytesIO()
        stored.write(self.mark)
        decoder = codecs.getincrementaldecoder("utf-8")()
        view = memoryview(data)
        for start in range(0, len(data), _PIECE):
            text = decoder.decode(view[start:start + _PIECE], final=start + _PIECE >= len(data))
            if start == 0 and self.declared is not None:  # the first piece holds the head
                text = _renamed(text, self.declared)
            stored.write(text.encode(self.codec))
        return stored.getvalue()


# The XML declaration's encoding; looked for in the head of the document, as a declaration
# after a comment is read too (see xmlio._movable_declaration).
_DECLARED = re.compile(r"""<\?xml[^>]*?\sencoding\s*=\s*["']([A-Za-z0-9._-]+)["']""")
_HEAD = 4096


def detect_encoding(data: bytes) -> Encoding:
    """The encoding by the byte-order mark, else by the zero bytes of UTF-16/32 around the first
    (ASCII) characters (XML 1.0 appendix F), else the declaration's; UTF-8 by default."""
    return _encoding_of(data[:len(_MARKS[0][0]) + _HEAD])


@lru_cache(maxsize=4)
def _encoding_of(data: bytes) -> Encoding:
    """:func:`detect_encoding` of a document's head (all that it reads), kept for the last few
    documents: the parser, its checks and the scanners all ask about the same bytes. The head
    is the key, not the document: a cache must not hold a document once it is done with."""
    for mark, codec in _MARKS:
        if data.startswith(mark):
            return Encoding(codec, mark, _declared(data[len(mark):], codec))
    codec = _zero_pattern(data[:4])
    if codec is not None:
        return Encoding(codec, b"", _declared(data, codec))
    declared = _declared(data, "latin-1")
    try:
        codec = codecs.lookup(declared or "utf-8").name
    except LookupError:
        codec = "utf-8"  # libxml2 names the unknown encoding when it parses
    return Encoding("utf-8" if codec.startswith(("utf-16", "utf-32")) else codec, b"", declared)


def _zero_pattern(head: bytes) -> str | None:
    if len(head) < 4:
        return None
    if head[:3] == b"\0\0\0" and 0 < head[3] < 0x80:
        return "utf-32-be"
    if 0 < head[0] < 0x80 and head[1:4] == b"\0\0\0":
        return "utf-32-le"
    if head[0] == head[2] == 0 and 0 < head[1] < 0x80:
        return "utf-16-be"
    if 0 < head[0] < 0x80 and head[1] == head[3] == 0:
        return "utf-16-le"
    return None


def _declared(data: bytes, codec: str) -> str | None:
    match = _DECLARED.search(data[:_HEAD].decode(codec, errors="replace"))
    return match.group(1) if match else None


def _renamed(text: str, name: str) -> str:
    """``text`` with the encoding its XML declaration names replaced by ``name``."""
    match = _DECLARED.search(text, 0, _HEAD)
    if match is None:
        return text
    return text[:match.start(1)] + name + text[match.end(1):]


def utf8_form(data: bytes, errors: str = "strict") -> bytes:
    """A UTF-16 or UTF-32 document as UTF-8, its declaration naming UTF-8 (lines, columns and
    everything else as written); any other document as it is. Writers turn it back with
    :meth:`Encoding.from_utf8`. ``errors="replace"`` is for scanners that must read a document
    whose text cannot be decoded (its TX001 is being reported)."""
    encoding = detect_encoding(data)
    if not encoding.wide:
        return data
    text = encoding.decode(data, errors)
    return (_renamed(text, "UTF-8") if encoding.declared else text).encode("utf-8")


def parsing_form(data: bytes, errors: str = "strict") -> bytes:
    """What libxml2 and the byte scanners read: :func:`utf8_form`, with each bare CR made a LF.

    The XML parser turns every CR into a LF anyway (XML 1.0 section 2.11), but libxml2 counts
    no line at a bare CR: a file with CR line endings would be all line 1.
    """
    data = utf8_form(data, errors)
    if b"\r" in data and data.count(b"\r") != data.count(b"\r\n"):
        data = re.sub(rb"\r(?!\n)", b"\n", data)
    return data


def document_text(data: bytes) -> str:
    """The document as text, decoded as :func:`detect_encoding` says.

    For finding columns in the text as written; undecodable bytes become U+FFFD.
    """
    encoding = detect_encoding(data)
    return data.removeprefix(encoding.mark).decode(encoding.codec, errors="replace")


_LINE_END = re.compile(r"\r\n|\r|\n")


class Lines(Sequence[str]):
    """The lines of a document's text, without their line breaks: the text once and where
    each line starts, a line cut out only when asked for (a list of the lines would hold a
    string object for each, which for lines of a tag or two outweighs the text itself).

    Split where libxml2 counts lines (see :func:`parsing_form`), not at the other breaks
    ``str.splitlines`` knows (form feed, NEL, U+2028), which XML text may hold.
    """

    __slots__ = ("text", "_starts")

    def __init__(self, text: str) -> None:
        self.text = text
        starts = array("l", [0])
        starts.extend(match.end() for match in _LINE_END.finditer(text))
        self._starts = starts

    def __len__(self) -> int:
        return len(self._starts)

    @overload
    def __getitem__(self, index: int) -> str: ...
    @overload
    def __getitem__(self, index: slice) -> list[str]: ...
    def __getitem__(self, index: int | slice) -> str | list[str]:
        if isinstance(index, slice):
            return [self[each] for each in range(*index.indices(len(self)))]
        start, end = self.span(index)
        return self.text[start:end]

    def span(self, index: int) -> tuple[int, int]:
        """Where line ``index`` (0-based, as for ``[]``) starts and ends in :attr:`text`, its
        line break left out."""
        count = len(self._starts)
        if index < 0:
            index += count
        if not 0 <= index < count:
            raise IndexError("line index out of range")
        start = self._starts[index]
        if index + 1 == count:
            return start, len(self.text)
        end = self._starts[index + 1] - 1  # the last character of the break
        if end > start and self.text[end] == "\n" and self.text[end - 1] == "\r":
            end -= 1
        return start, end


@lru_cache(maxsize=2)
def text_lines(data: bytes) -> Lines:
    """The lines of a document as written (shared by everything that places findings in it)."""
    return Lines(document_text(data))


_FITTING = {  # the names (lower case, without - and _) a declaration may give each encoding
    "utf-8": ("utf8",),
    "utf-16-le": ("utf16", "utf16le", "ucs2", "iso10646ucs2"),
    "utf-16-be": ("utf16", "utf16be", "ucs2", "iso10646ucs2"),
    "utf-32-le": ("utf32", "utf32le", "ucs4", "iso10646ucs4"),
    "utf-32-be": ("utf32", "utf32be", "ucs4", "iso10646ucs4"),
}


def mislabelled(data: bytes) -> tuple[int, int, str] | None:
    """(line, column, reason) when the declaration names an encoding the bytes are not in:
    libxml2 would follow the mark without a word, or fail with a puzzling message."""
    encoding = detect_encoding(data)
    declared = encoding.declared
    if declared is None:
        return None
    said = re.sub(r"[-_]", "", declared.lower())
    if encoding.mark or encoding.wide:
        if said in _FITTING[encoding.codec]:
            return None
        how = "its byte-order mark" if encoding.mark else "the zero bytes around its first letters"
        actual = encoding.codec.upper().replace("-LE", "LE").replace("-BE", "BE")
        found = f"is written in {actual} (by {how})"
    elif said.startswith(("utf16", "utf32", "ucs2", "ucs4", "iso10646")):
        found = (f"is not written in {declared} (it has no byte-order mark and one byte per "
                 "ASCII character)")
    else:
        return None
    head = data.removeprefix(encoding.mark)[:_HEAD].decode(encoding.codec, errors="replace")
    start = _DECLARED.search(head).start(1)  # type: ignore[union-attr]
    before = re.split(r"\r\n|\r|\n", head[:start])
    return (len(before), len(before[-1]) + 1,
            f'the XML declaration says encoding="{declared}", but the document {found}; '
            f"correct the declaration or save the file as {declared}")
