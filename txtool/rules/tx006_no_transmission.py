"""A file named on the command line that holds no transmission.

``txtool validate robot.urdf`` on a file with no ``<transmission>`` (after xacro expansion,
and none inside xacro macros either) checks nothing; saying "no problems" would suggest the
robot's transmissions were checked. Reported only for files named on the command line: a folder
walk meets many included fragments (materials, macros) that rightly hold none. Produced by the
pipeline; severity ``info``, so it never fails a run.

Failing example::

    <!-- txtool validate links.urdf -->
    <robot name="r"><link name="base"/></robot>

Passing example::

    <!-- txtool validate robot.urdf -->
    <robot name="r">
      <transmission name="t">...</transmission>
    </robot>
"""

from __future__ import annotations

from collections.abc import Iterator

from txtool.lint.context import LintContext
from txtool.lint.problem import Problem

CODE = "TX006"
NAME = "no-transmission"
SEVERITY = "info"
FIXABLE = False


def check(ctx: LintContext) -> Iterator[Problem]:
    """Nothing to check per document: the pipeline reports files without transmissions."""
    return iter(())
