"""The file is not well-formed XML, so no ROS loader can read it.

What it does: reports where the XML parser stopped, when parsing fails (produced by the
pipeline; the rule itself checks nothing). A licence comment written before the
``<?xml ...?>`` declaration is reported too; txtool still reads the rest (it blanks the
declaration, keeping line numbers, since only the encoding matters). Whitespace alone before
the declaration is TX004's (a warning: tinyxml2 skips it).

Why it matters: no loader reads the file. ros_control answers "Can't parse transmissions.
Invalid robot description."; ros2_control's URDF parser throws; ``robot_state_publisher``
refuses the whole description. tinyxml2 (urdfdom, ros2_control, MuJoCo) refuses a declaration
that follows any other node (``XML_ERROR_PARSING_DECLARATION``), and so do xacro's expat and
libxml2.

Loader: tinyxml2, which urdfdom and ros2_control parse with (leethomason/tinyxml2
tinyxml2.cpp ``XMLNode::ParseDeep``); ros_control
(ros-controls/ros_control transmission_interface/src/transmission_parser.cpp
``TransmissionParser::parse``).

Failing example::

    <robot name="r">
      <transmission name="t">
    </robot>

Expected finding: ``3:9 error TX001 Opening and ending tag mismatch: transmission line 2 and
robot``

Passing example::

    <robot name="r">
      <transmission name="t">
        <type>transmission_interface/SimpleTransmission</type>
        <joint name="j">
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
        </joint>
        <actuator name="m"><mechanicalReduction>50</mechanicalReduction></actuator>
      </transmission>
    </robot>

Fix: close every element (an editor's XML validation shows where), and write the
declaration, if any, first in the file.
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
