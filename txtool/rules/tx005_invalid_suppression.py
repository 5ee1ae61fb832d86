"""A suppression comment that cannot work as written.

What it does: reports a ``<!-- txtool: ... -->`` comment whose directive is misspelt
(``disable-nextline``), that lists something other than rule codes before the ``;`` reason
(``TX10``, ``zero``), or names a code of no rule (``TX999``). Produced by the pipeline.

Why it matters: such a comment silences nothing, or less than its author meant, while looking
as if it did. No loader reads XML comments; severity ``warning``.

Loader: none reads the comment (tinyxml2 and lxml skip comments); the directives are txtool's
own, parsed in txtool/lint/suppress.py ``parse``.

Failing example::

    <robot name="r">
      <transmission name="t">
        <type>transmission_interface/SimpleTransmission</type>
        <joint name="j">
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
        </joint>
        <actuator name="m">
          <!-- txtool: disable-nextline TX106 -->
          <mechanicalReduction>0</mechanicalReduction>
        </actuator>
      </transmission>
    </robot>

Expected finding: ``8:7 warning TX005 unknown directive 'txtool: disable-nextline': did you mean
'disable-next-line'?``

Passing example::

    <robot name="r">
      <transmission name="t">
        <type>transmission_interface/SimpleTransmission</type>
        <joint name="j">
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
        </joint>
        <actuator name="m">
          <!-- txtool: disable-next-line TX106; zero on purpose in this test asset -->
          <mechanicalReduction>0</mechanicalReduction>
        </actuator>
      </transmission>
    </robot>

Fix: spell the directive ``disable-next-line``, ``disable-line`` or ``disable-file``, list
rule codes only (``txtool rules`` lists them), and put the reason after ``;``.
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
