"""The ``json`` report, as described by ``schemas/report.schema.json``.

The schema comes from the pydantic models in :mod:`txtool.reporters.report_schema`; the
report is plain ``json`` so that a run over many files does not load pydantic.
"""

from __future__ import annotations

import json
from collections.abc import Sequence
from typing import Any

from txtool.problem import Problem
from txtool.reporters import Summary, end_of


def report(problems: Sequence[Problem], summary: Summary) -> dict[str, Any]:
    """The report as JSON-ready data, keys in the schema's order."""
    rows = []
    for p in problems:
        end_line, end_column = end_of(p)
        rows.append({
            "path": p.path, "line": p.line, "column": p.column, "end_line": end_line,
            "end_column": end_column, "severity": p.severity, "code": p.code, "name": p.name,
            "message": p.message, "fixable": bool(p.fixable),
        })
    totals = {"files": summary.files, "errors": summary.errors, "warnings": summary.warnings,
              "infos": summary.infos}
    return {"problems": rows, "summary": totals}


def render(problems: Sequence[Problem], summary: Summary, *, color: bool = False) -> str:
    return json.dumps(report(problems, summary), indent=2, ensure_ascii=False) + "\n"
