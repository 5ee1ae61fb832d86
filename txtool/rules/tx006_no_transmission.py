"""A file named on the command line that holds no transmission.

What it does: reports a file named on the command line (``txtool validate links.urdf``) with
no ``<transmission>`` after xacro expansion, and none inside xacro macros either. Files met in
a folder walk are not reported: a walk meets many included fragments (materials, macros) that
rightly hold none. A named file whose root element is no robot description's (a launch file,
a ``package.xml``, an SDF world) is passed over before, quietly. Produced by the pipeline.

Why it matters: such a run checks nothing, and saying "no problems" would suggest the robot's
transmissions were checked. Nothing is wrong with the file for any loader: severity ``info``,
so it never fails a run.

Loader: none; txtool's pipeline decides it (txtool/lint/engine.py ``_no_transmission``).

Failing example::

    <robot name="r">
      <link name="base"/>
    </robot>

Expected finding: ``1:1 info TX006 no <transmission> in this file: nothing to check``

Passing example::

    <robot name="r">
      <link name="base"/>
      <transmission name="t">
        <type>transmission_interface/SimpleTransmission</type>
        <joint name="j">
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
        </joint>
        <actuator name="m"><mechanicalReduction>50</mechanicalReduction></actuator>
      </transmission>
    </robot>

Fix: name the file that holds the transmissions (the top xacro file, say), or leave the
finding: it only says that nothing was checked.
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
