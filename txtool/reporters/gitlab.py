"""GitLab's code quality report: a JSON array, one object per finding.

GitLab shows it in merge requests (``artifacts: reports: codequality``). Its fields: a
``description``, the rule as ``check_name``, a ``fingerprint`` that stays the same when a
line added above moves the finding (see :func:`~txtool.reporters.fingerprints`), a
``severity`` of GitLab's scale and the ``location``, a path relative to the repository.
"""

from __future__ import annotations

import json
from collections.abc import Sequence

from txtool.lint.problem import Problem
from txtool.reporters import Summary, end_of, fingerprints
from txtool.reporters.github import annotation_path

# GitLab's scale is info, minor, major, critical, blocker; an error stops a loader.
SEVERITIES = {"error": "critical", "warning": "major", "info": "info"}


def render(problems: Sequence[Problem], summary: Summary, *, color: bool = False) -> str:
    issues = [_issue(problem, fingerprint)
              for problem, fingerprint in zip(problems, fingerprints(problems), strict=True)]
    return json.dumps(issues, indent=2, ensure_ascii=False) + "\n"


def _issue(problem: Problem, fingerprint: str) -> dict[str, object]:
    end_line, _ = end_of(problem)
    return {
        "description": f"{problem.code} {problem.message}",
        "check_name": problem.code,
        "fingerprint": fingerprint,
        "severity": SEVERITIES.get(problem.severity, "major"),
        "location": {
            "path": annotation_path(problem.path),
            "lines": {"begin": problem.line, "end": end_line},
        },
    }
