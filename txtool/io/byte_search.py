"""Searches of large documents' bytes for markup that stands in few places."""

from __future__ import annotations


def find_by(data: bytes, needle: bytes, rare: int, start: int = 0) -> int:
    """``data.find(needle, start)``, found by the byte of ``needle`` at index ``rare`` alone:
    one byte is sought with ``memchr``, on a large robot about ten times faster than a search
    for ``<!`` or ``-->`` (whose last bytes stand everywhere); each place it stands is
    checked. Choose a byte that few places hold: each one found costs a step in Python."""
    byte = needle[rare:rare + 1]
    at = data.find(byte, start + rare)
    while at >= 0:
        if data.startswith(needle, at - rare):
            return at - rare
        at = data.find(byte, at + 1)
    return -1
