"""The one thing a written document never keeps as it was read: an XML declaration that does
not start it.

Some published URDFs put a licence comment, a blank line or spaces before ``<?xml ...?>``
(one fuzzed file a processing instruction); strict parsers (expat, libxml2) refuse that.
txtool reads such a document (:func:`txtool.io.xmlio.parse_bytes`) but writes none: after
whitespace alone the whitespace goes (the declaration may name the encoding), after anything
else the declaration.
"""

from __future__ import annotations

import re

from txtool.transform.edits.core import Edit, EditedText

# An XML declaration after what may stand before the root element (whitespace, comments,
# processing instructions). Each of them matches in one way only (a comment ends at its first
# -->, a processing instruction at its first ?>), so that where no declaration follows, the
# match gives up in time linear in the run, not in one that doubles with each comment.
_LATE_DECLARATION = re.compile(
    rb"(\xef\xbb\xbf)?((?:[ \t\r\n]|<!--[^-]*(?:-(?!->)[^-]*)*-->"
    rb"|<\?(?!xml[ \t\r\n?])[^>]*\?>)*)"
    rb"(<\?xml[ \t\r\n][^>]*\?>[ \t]*(?:\r\n|\r|\n)?)")


def late_declaration(data: bytes) -> Edit | None:
    """The edit that puts the declaration of ``data`` (bytes a scanner reads: see
    :class:`~txtool.transform.edits.core.EditedText`) first or takes it out; None when it is
    first or there is none."""
    late = _LATE_DECLARATION.match(data)
    if late is None or not late.group(2):
        return None
    if not late.group(2).strip(b" \t\r\n"):
        return Edit.deletion(late.start(2), late.start(3))
    return Edit.deletion(late.start(3), late.end(3))


def without_late_declaration(data: bytes) -> bytes:
    """``data`` (a whole document, in any encoding) with its late declaration dealt with as
    :func:`late_declaration` says, by that one edit."""
    text = EditedText(data)
    late = late_declaration(text.data)
    return data if late is None else text.applied([late])
