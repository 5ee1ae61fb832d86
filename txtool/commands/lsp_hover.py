"""The language server's hover: on a ``<transmission>``, what each loader reads of it, as
``txtool show --effective`` prints it (:mod:`txtool.views.effective`), with the file's readers.
"""

from __future__ import annotations

import re
from typing import TYPE_CHECKING

from txtool.commands.lsp_document import Options, load_buffer, root_of, settings_for
from txtool.io.xmlio import InputError, Source

if TYPE_CHECKING:
    from txtool.dialects.read import Found
    from txtool.lint.config import Settings

_COMMENT = re.compile(r"<!--.*?-->", re.DOTALL)
_START = re.compile(r"<(?:([\w.-]+):)?transmission(?=[\s/>])")


def offset_of(text: str, line: int, character: int) -> int:
    """The index in ``text`` of 0-based ``line`` and ``character`` (code points)."""
    lines = text.splitlines(keepends=True)
    return sum(len(each) for each in lines[:line]) + character


def transmission_at(text: str, offset: int) -> int | None:
    """The 1-based line on which the ``<transmission>`` element holding ``offset`` starts
    (None: the offset is in none). Commented-out text holds no element."""
    blanked = _COMMENT.sub(lambda m: re.sub(r"[^\n]", " ", m.group(0)), text)
    for start in _START.finditer(blanked):
        if start.start() > offset:
            return None
        end = _end_of_element(blanked, start)
        if offset < end:
            return blanked.count("\n", 0, start.start()) + 1
    return None


def _end_of_element(text: str, start: re.Match[str]) -> int:
    tag_end = text.find(">", start.end())
    if tag_end < 0:
        return len(text)
    if text[tag_end - 1] == "/":
        return tag_end + 1
    prefix = f"{start.group(1)}:" if start.group(1) else ""
    close = re.compile(rf"</{re.escape(prefix)}transmission\s*>").search(text, tag_end)
    return close.end() if close else len(text)


def hover_markdown(path: str, text: str, line: int, character: int,
                   workspace: list[str], options: Options) -> str | None:
    """The effective view of the transmission at 0-based ``line``/``character`` as Markdown;
    None when there is none there or the buffer cannot be read."""
    started = transmission_at(text, offset_of(text, line, character))
    if started is None:
        return None
    from txtool.dialects.read import read_source

    try:
        settings = settings_for(path, root_of(path, workspace), options)
        source = load_buffer(path, text, settings)
    except (InputError, OSError):  # the diagnostics say why
        return None
    found = read_source(source)
    if not found and source.source_tree is not None:  # a macro library: read as written
        source = Source(path=path, data=source.data, tree=source.source_tree)
        found = read_source(source)
    here = [f for f in found if f.transmission.location and
            f.transmission.location.line == started]
    if not here:
        return None
    return _effective(source, found, here, settings)


def _effective(source: Source, found: list[Found], here: list[Found],
               settings: Settings) -> str:
    """``show --effective`` of the transmissions ``here`` (of ``found``, all the file's)."""
    from txtool.lint.readers import assumption_of
    from txtool.views.effective import bindings_of, effective_text
    from txtool.views.readers_view import readers_text, unread_names

    assumption = assumption_of(source, settings.stated)
    unread = unread_names(assumption, [f.element for f in found])
    ros2 = [d for d in assumption.distros if d.ros2]
    bindings = bindings_of(here, ros2[0] if len(ros2) == 1 else None)
    shown = effective_text(source.path, [f.transmission for f in here], bindings, unread)
    shown = shown.split("\n", 1)[1]  # not the path: the editor shows the file
    return f"```text\n{shown}{readers_text(assumption, unread)}```"
