"""A suppression comment that silences nothing.

What it does: reports a ``<!-- txtool: disable-next-line CODE -->`` (or ``disable-line`` /
``disable-file``) comment for each listed code that is enabled but silenced nothing; a
directive without codes is reported when it silenced nothing at all. Produced by the
pipeline.

Why it matters: a suppression that no longer matches a finding is noise that hides future
problems, like ruff's RUF100. No loader reads XML comments: severity ``info``, so it never
fails a run unless configured otherwise.

Loader: none reads the comment (tinyxml2 and lxml skip comments); the directives are txtool's
own, parsed in txtool/lint/suppress.py ``parse_directives``.

Failing example::

    <robot name="r">
      <transmission name="t">
        <type>transmission_interface/SimpleTransmission</type>
        <joint name="j">
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
        </joint>
        <actuator name="m">
          <!-- txtool: disable-next-line TX106 -->
          <mechanicalReduction>50</mechanicalReduction>
        </actuator>
      </transmission>
    </robot>

Expected finding: ``8:7 info TX003 suppression 'disable-next-line TX106' silences nothing:
remove it``

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

Fix: delete the comment, or the code it lists that no longer applies.
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
