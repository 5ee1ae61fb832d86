"""The document's bytes as the byte scanners read them, worked out once per document."""

from __future__ import annotations

from functools import lru_cache

from txtool.io.encodings import parsing_form


@lru_cache(maxsize=2)
def scanned_form(data: bytes) -> bytes:
    """:func:`~txtool.io.encodings.parsing_form` of ``data``, kept for the document being
    checked: the late-declaration check, TX004, suppressions and the CDATA test all read it."""
    return parsing_form(data)
