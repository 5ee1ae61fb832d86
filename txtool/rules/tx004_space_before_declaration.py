"""Whitespace before the ``<?xml ...?>`` declaration: ROS loads it, strict XML tools do not.

What it does: reports blank lines or spaces before the document's ``<?xml ...?>``
declaration. txtool reads the document anyway (the declaration only carries the encoding).

Why it matters: the XML specification requires the declaration to be the very first thing in
the document. ROS loads such a file, but strict parsers refuse it: expat ("XML or text
declaration not at start of entity", used by xacro and Python's xml modules), libxml2 (lxml,
xmllint) and most editors' XML validation. A warning.

Loader: tinyxml2, which urdfdom and ros2_control's component parser use, skips leading
whitespace before the declaration (leethomason/tinyxml2 tinyxml2.cpp ``XMLDocument::Parse``
calls ``XMLUtil::SkipWhiteSpace`` first).

Failing example::

      <?xml version="1.0"?>
    <robot name="r">
      <transmission name="t">
        <type>transmission_interface/SimpleTransmission</type>
        <joint name="j">
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
        </joint>
        <actuator name="m"><mechanicalReduction>50</mechanicalReduction></actuator>
      </transmission>
    </robot>

Expected finding: ``1:3 warning TX004 whitespace before the XML declaration: tinyxml2 (urdfdom,
ros2_control) skips it and loads the file, but strict XML parsers (xacro's expat, libxml2)
reject it; remove it``

Passing example::

    <?xml version="1.0"?>
    <robot name="r">
      <transmission name="t">
        <type>transmission_interface/SimpleTransmission</type>
        <joint name="j">
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
        </joint>
        <actuator name="m"><mechanicalReduction>50</mechanicalReduction></actuator>
      </transmission>
    </robot>

Fix: delete the blank lines or spaces before ``<?xml``.
"""

from __future__ import annotations

from txtool.io.xmlio import LEADING_SPACE_DECLARATION
from txtool.lint.context import LintContext
from txtool.lint.problem import Problem
from txtool.lint.text import scanned_form

CODE = "TX004"
NAME = "space-before-declaration"
SEVERITY = "warning"
FIXABLE = False


def check(ctx: LintContext) -> list[Problem]:
    data = scanned_form(ctx.source.data)  # UTF-8, lines where libxml2 counts them
    match = LEADING_SPACE_DECLARATION.match(data)
    if match is None:
        return []
    index = match.end(1)
    line = data.count(b"\n", 0, index) + 1
    column = index - (data.rfind(b"\n", 0, index) + 1) + 1
    return [Problem(
        ctx.source.path,
        line,
        column,
        CODE,
        "whitespace before the XML declaration: tinyxml2 (urdfdom, ros2_control) skips it and "
        "loads the file, but strict XML parsers (xacro's expat, libxml2) reject it; remove it",
    )]
