"""Text from files made safe to print: names and paths cannot forge lines or drive a terminal.

A transmission name may hold a newline (``&#10;``) and a file name any byte but ``/``: printed
as they are, a newline starts what looks like another finding, and an escape sequence moves the
cursor, retitles the window or writes the clipboard. :func:`printable` writes every control
character as a Python-style escape (``\\n``, ``\\x1b``) and each byte of a file name that is
not UTF-8 (which Python holds as a lone surrogate) as ``\\xNN``.
"""

from __future__ import annotations

import re

_UNPRINTABLE = re.compile("[\x00-\x1f\x7f-\x9f\u2028\u2029\ud800-\udfff]")
_NAMED = {"\t": "\\t", "\n": "\\n", "\r": "\\r"}


def printable(text: str) -> str:
    """``text`` with control characters and undecodable bytes escaped (a backslash stays)."""
    if not _UNPRINTABLE.search(text):
        return text
    return _UNPRINTABLE.sub(_escape, text)


def _escape(match: re.Match[str]) -> str:
    char = match.group()
    code = ord(char)
    if char in _NAMED:
        return _NAMED[char]
    if 0xDC80 <= code <= 0xDCFF:  # os.fsdecode's stand-in for the byte code - 0xDC00
        return f"\\x{code - 0xDC00:02x}"
    return f"\\x{code:02x}" if code < 0x100 else f"\\u{code:04x}"


def without_surrogates(text: str) -> str:
    """For UTF-8 output (JSON): each lone surrogate as its ``\\udcNN`` escape, which Python's
    ``json`` reads back to the same string (``os.fsencode`` then gives the file's name)."""
    return re.sub("[\ud800-\udfff]", lambda m: f"\\u{ord(m.group()):04x}", text)
