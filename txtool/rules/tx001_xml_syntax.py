"""The file is not well-formed XML, so no ROS loader can read it.

Produced by the pipeline when parsing fails (the rule itself checks nothing): the position is
where the XML parser stopped. ros_control answers "Can't parse transmissions. Invalid robot
description."; ros2_control's URDF parser throws; ``robot_state_publisher`` refuses the whole
description. A licence comment written before the ``<?xml ...?>`` declaration is reported
too: tinyxml2 (urdfdom, ros2_control, MuJoCo) refuses a declaration that follows any other
node (``XMLNode::ParseDeep``: ``XML_ERROR_PARSING_DECLARATION``), and so do xacro's expat and
libxml2; txtool still reads the rest (it blanks the declaration, keeping line numbers, since
only the encoding matters). Whitespace alone before the declaration is TX004's (a warning:
tinyxml2 skips it).

Failing example::

    <robot name="r">
      <transmission name="t">
    </robot>

Passing example::

    <robot name="r">
      <transmission name="t"/>
    </robot>
"""

from __future__ import annotations

from collections.abc import Iterator

from txtool.lint.context import LintContext
from txtool.lint.problem import Problem

CODE = "TX001"
NAME = "xml-syntax"
SEVERITY = "error"
FIXABLE = False


def check(ctx: LintContext) -> Iterator[Problem]:
    """Nothing to check on a parsed document: the pipeline reports parse errors."""
    return iter(())
