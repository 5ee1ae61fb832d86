"""Run the lint pipeline on an inline XML snippet, the way ``txtool validate`` would.

``check(xml, **options)`` returns sorted ``(line, column, code, severity)`` tuples, so every
rule test pins the severity a finding is reported with. The snippet is
dedented and one leading newline is dropped, so line 1 is the first line after the opening
quotes. Options:

``select`` / ``ignore``
    rule codes or prefixes (``select=["TX105"]`` to look at one rule; default: every rule);
``severity``, ``rules``
    as in ``[tool.txtool]`` (``rules={"TX102": {"known-families": ["my_hw/"]}}``);
``filename``
    the name the snippet is written under (default ``robot.urdf``; a ``.xacro`` name is
    expanded by xacro, or linted literally when it is a macro library);
``xacro_args``, ``no_xacro``
    as the configuration keys ``xacro-args`` and ``no-xacro``.

``problems(xml, **options)`` returns the :class:`~txtool.lint.problem.Problem` values themselves,
for assertions on messages and severities.
"""

from __future__ import annotations

import tempfile
import textwrap
from pathlib import Path
from typing import Any

from txtool.io.xmlio import parse_bytes, serialize
from txtool.lint.config import Config, resolve
from txtool.lint.engine import lint_file
from txtool.lint.problem import Problem


def snippet(xml: str) -> str:
    text = textwrap.dedent(xml)
    return text[1:] if text.startswith("\n") else text


def problems(xml: str, *, filename: str = "robot.urdf", **options: Any) -> list[Problem]:
    config = Config.model_validate(options)
    with tempfile.TemporaryDirectory(prefix="txtool-test-") as folder:
        path = Path(folder) / filename
        path.write_text(snippet(xml), encoding="utf-8")
        settings = resolve(config, origin="test options", base=Path(folder))
        return lint_file(str(path), settings)


def check(xml: str, **options: Any) -> list[tuple[int, int, str, str]]:
    return sorted((p.line, p.column, p.code, p.severity) for p in problems(xml, **options))


def fixed(rule: Any, xml: str) -> tuple[str, int, int]:
    """The text after one run of ``rule.fix``, the fixes made, and the fixes a second run makes."""
    data = snippet(xml).encode()
    tree = parse_bytes(data, "robot.urdf")
    first = rule.fix(tree.getroot())
    text = serialize(tree, data).decode()
    return text, first, rule.fix(tree.getroot())
