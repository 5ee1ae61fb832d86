"""A rule's documentation (its module docstring) as a terminal, Markdown and SARIF read it.

Docstrings are written in reStructuredText's small subset: ``literal``, ``:role:`target```
and ``Failing example::`` followed by an indented XML block.
"""

from __future__ import annotations

import re
from typing import Any

_ROLE = re.compile(r":(?:func|mod|class|meth|data|attr):`~?([^`]+)`")
_LITERAL = re.compile(r"``([^`]+)``")


def plain(doc: str) -> str:
    """For a terminal: no markup; ``x`` becomes x, ``Example::`` becomes ``Example:``."""
    text = _ROLE.sub(lambda m: m.group(1).rsplit(".", 1)[-1], doc)
    text = _LITERAL.sub(r"\1", text)
    return re.sub(r"(?m)::$", ":", text)


def markdown(rule: Any, *, heading: str = "**") -> str:
    """The docstring as Markdown: literals in backticks, examples as fenced XML."""
    title = f"{rule.code} {rule.name}"
    out = [f"# {title}" if heading == "#" else f"**{title}**", ""]
    fenced = False
    for line in _inline(rule.doc).splitlines():  # literals may span lines
        if fenced and line.strip() and not line.startswith("    "):
            while out[-1] == "":
                out.pop()
            out += ["```", ""]
            fenced = False
        if line.rstrip().endswith("::") and not fenced:
            out += [line.rstrip()[:-1], "", "```xml"]
            fenced = True
            continue
        out.append(line[4:] if fenced else line)
    if fenced:
        out.append("```")
    return "\n".join(out).replace("```xml\n\n", "```xml\n")


def _inline(text: str) -> str:
    text = _ROLE.sub(lambda m: f"`{m.group(1).rsplit('.', 1)[-1]}`", text)
    return _LITERAL.sub(r"`\1`", text)
