"""A suppression comment that silences nothing.

``<!-- txtool: disable-next-line TX105 -->`` (or ``disable-line`` / ``disable-file``) that no
longer matches a finding is noise that hides future problems, like ruff's RUF100. Reported
for each listed code that is enabled but silenced nothing (a directive without codes is
reported when it silenced nothing at all). Produced by the pipeline; severity ``info``, so it
never fails a run unless configured otherwise.

Failing example::

    <!-- txtool: disable-next-line TX106 -->
    <mechanicalReduction>50</mechanicalReduction>

Passing example::

    <!-- txtool: disable-next-line TX106 -->
    <mechanicalReduction>0</mechanicalReduction>
"""

from __future__ import annotations

from collections.abc import Iterator

from txtool.lint.context import LintContext
from txtool.lint.problem import Problem

CODE = "TX003"
NAME = "unused-suppression"
SEVERITY = "info"
FIXABLE = False


def check(ctx: LintContext) -> Iterator[Problem]:
    """Nothing to check per document: the pipeline reports unused suppressions."""
    return iter(())
