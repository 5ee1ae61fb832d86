"""A suppression comment that cannot work as written.

A ``<!-- txtool: ... -->`` comment whose directive is misspelt (``disable-nextline``), that
lists something other than rule codes before the ``;`` reason (``TX10``, ``zero``), or names a
code of no rule (``TX999``) silences nothing, or less than its author meant, while looking as
if it did. Produced by the pipeline; severity ``warning``.

Failing example::

    <!-- txtool: disable-nextline TX106 -->
    <!-- txtool: disable-line TX999 -->

Passing example::

    <!-- txtool: disable-next-line TX106; zero on purpose -->
"""

from __future__ import annotations

from collections.abc import Iterator

from txtool.lint.context import LintContext
from txtool.lint.problem import Problem

CODE = "TX005"
NAME = "invalid-suppression"
SEVERITY = "warning"
FIXABLE = False


def check(ctx: LintContext) -> Iterator[Problem]:
    """Nothing to check per document: the pipeline reports invalid suppressions."""
    return iter(())
