"""The one entry for every input: a file or standard input, parsed safely, xacro expanded.

:mod:`txtool.io.xmlio` reads and parses bytes; :mod:`txtool.io.xacro` expands xacro. This module
decides which applies, so neither of the two imports the other's caller.
"""

from __future__ import annotations

from txtool.io.xmlio import Source, XacroOptions, is_xacro, parse_bytes, read_bytes


def load(
    path: str,
    *,
    xacro: XacroOptions | None = None,
    stdin_name: str | None = None,
    expand: bool = True,
) -> Source:
    """Load one input; ``.xacro`` files are expanded in-process unless ``expand`` is False."""
    display, data = read_bytes(path, stdin_name=stdin_name)
    tree = parse_bytes(data, display)
    if not (expand and is_xacro(display) and path != "-"):
        return Source(path=display, data=data, tree=tree)
    from txtool.io.xacro import expand_xacro  # xacro is slow to import; only xacro needs it

    expanded = expand_xacro(path, display, xacro or XacroOptions())
    return Source(path=display, data=data, tree=expanded, expanded=True, source_tree=tree)
