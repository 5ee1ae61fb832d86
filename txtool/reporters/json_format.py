"""The ``json`` report, as described by ``schemas/report.schema.json``.

The schema comes from the pydantic models in :mod:`txtool.reporters.report_schema`; the report
is written here without pydantic (loading it costs more than checking many files). The text
is what ``json.dumps(report(...), indent=2, ensure_ascii=False)`` writes, built row by row
with the C string encoder, which is several times faster for reports of thousands of problems;
a test holds both, and pydantic's models, to the same bytes.
"""

from __future__ import annotations

import json
from collections.abc import Sequence
from json.encoder import encode_basestring  # type: ignore[attr-defined]
from typing import Any

from txtool.io.printable import without_surrogates
from txtool.lint.problem import Problem
from txtool.reporters import Summary, end_of

_ROW = """    {
      "path": %s,
      "line": %d,
      "column": %d,
      "end_line": %d,
      "end_column": %d,
      "severity": %s,
      "code": %s,
      "name": %s,
      "message": %s,
      "fixable": %s,
      "related": %s
    }"""


def report(problems: Sequence[Problem], summary: Summary) -> dict[str, Any]:
    """The report as JSON-ready data, keys in the schema's order."""
    rows = []
    for p in problems:
        end_line, end_column = end_of(p)
        rows.append({
            "path": p.path, "line": p.line, "column": p.column, "end_line": end_line,
            "end_column": end_column, "severity": p.severity, "code": p.code, "name": p.name,
            "message": p.message, "fixable": bool(p.fixable), "related": _related(p),
        })
    unreadable = [{"path": f.path, "message": f.message} for f in summary.failures]
    return {"problems": rows, "unreadable": unreadable, "readers": _readers(summary),
            "summary": _totals(summary)}


def _related(problem: Problem) -> list[dict[str, object]]:
    return [{"path": note.path, "line": note.line, "column": note.column,
             "message": note.message} for note in problem.related]


def _related_text(problem: Problem) -> str:
    """:func:`_related` as ``json.dumps(..., indent=2)`` writes it inside a problem's row."""
    if not problem.related:
        return "[]"
    text = json.dumps(_related(problem), indent=2, ensure_ascii=False)
    return text.replace("\n", "\n" + " " * 6)


def _readers(summary: Summary) -> list[dict[str, object]]:
    return [file.as_json() for file in summary.readers]


def _totals(summary: Summary) -> dict[str, int]:
    return {"files": summary.files, "errors": summary.errors, "warnings": summary.warnings,
            "infos": summary.infos, "not_expanded": summary.not_expanded}


def render(problems: Sequence[Problem], summary: Summary, *, color: bool = False) -> str:
    """The report; a file name that is not UTF-8 keeps its bytes as ``\\udcNN`` escapes."""
    return without_surrogates(_render(problems, summary))


def _render(problems: Sequence[Problem], summary: Summary) -> str:
    whole = report((), summary)
    tail = {"unreadable": whole["unreadable"], "readers": whole["readers"],
            "summary": _totals(summary)}
    totals = json.dumps(tail, indent=2, ensure_ascii=False)[2:]  # '"unreadable": ...\n}'
    if not problems:
        return '{\n  "problems": [],\n' + totals + "\n"
    rows = []
    for p in problems:
        end_line, end_column = end_of(p)
        rows.append(_ROW % (
            encode_basestring(p.path), p.line, p.column, end_line, end_column,
            encode_basestring(p.severity), encode_basestring(p.code), encode_basestring(p.name),
            encode_basestring(p.message), "true" if p.fixable else "false", _related_text(p),
        ))
    return '{\n  "problems": [\n' + ",\n".join(rows) + "\n  ],\n" + totals + "\n"
