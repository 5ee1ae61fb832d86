"""The document's bytes as the byte scanners read them, worked out once per document."""

from __future__ import annotations

from functools import lru_cache

from txtool.io.encodings import parsing_form


@lru_cache(maxsize=2)
def scanned_form(data: bytes) -> bytes:
    """:func:`~txtool.io.encodings.parsing_form` of ``data``, kept for the document being
    checked: the late-declaration check, TX004, suppressions and the CDATA test all read it.
    Text that cannot be decoded (a UTF-16 mark before an odd number of bytes) reads as U+FFFD
    here: the parser has already refused the document with its reason (TX001)."""
    return parsing_form(data, errors="replace")
