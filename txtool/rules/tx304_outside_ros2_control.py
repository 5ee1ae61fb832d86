"""A transmission that ros2_control will never read.

What it does: reports, in a document that has ``<ros2_control>`` blocks, a transmission that is
not inside any of them: typically a top-level ROS 1 transmission left over from before a port.
In a xacro file read as written, transmissions inside a ``<xacro:macro>`` are not reported: the
macro may be instantiated inside a ``<ros2_control>`` block. This is the verdict where nothing
says which programs read the file (the ``<ros2_control>`` blocks alone do not rule ros_control
out); where the readers are known (``package.xml``, a ``<gazebo>`` plugin, ``--ros-distro``,
the configuration; see "Readers" in the loader documentation), a transmission none of them
reads is TX305's, one that only ROS 1 programs read (``--ros-distro noetic``) is not reported,
and one that a ROS 1 and a ROS 2 program read both is reported naming the ROS 2 readers and
why they were decided.

Why it matters: ros2_control reads transmissions only from the ``<transmission>`` children of a
``<ros2_control>`` element; a top-level one is ignored without a message. Its reduction and
offset therefore have no effect on the ROS 2 robot, although the file suggests they do.

Loader: ros2_control (ros-controls/ros2_control hardware_interface/src/component_parser.cpp
``parse_resource_from_xml``).

Failing example::

    <robot name="diffbot">
      <transmission name="wheel_trans">
        <type>transmission_interface/SimpleTransmission</type>
        <joint name="wheel">
          <hardwareInterface>hardware_interface/VelocityJointInterface</hardwareInterface>
        </joint>
        <actuator name="wheel_motor"><mechanicalReduction>50</mechanicalReduction></actuator>
      </transmission>
      <ros2_control name="DiffBot" type="system">
        <hardware><plugin>mock_components/GenericSystem</plugin></hardware>
        <joint name="wheel"><command_interface name="velocity"/></joint>
      </ros2_control>
    </robot>

Expected finding: ``2:3 warning TX304 ROS 1 transmission 'wheel_trans' stands outside every
<ros2_control> block of this document: ros2_control ignores it``

Passing example::

    <robot name="diffbot">
      <ros2_control name="DiffBot" type="system">
        <hardware><plugin>mock_components/GenericSystem</plugin></hardware>
        <joint name="wheel"><command_interface name="velocity"/></joint>
        <transmission name="wheel_trans">
          <plugin>transmission_interface/SimpleTransmission</plugin>
          <joint name="wheel" role="joint1">
            <mechanical_reduction>50</mechanical_reduction>
          </joint>
          <actuator name="wheel_motor" role="actuator1"/>
        </transmission>
      </ros2_control>
    </robot>

Fix: move it into the component that owns its joints (``txtool migrate --write --to ros2-p2``
converts it), or delete it if the ROS 1 description is no longer used.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator

from lxml import etree

from txtool.io.xmlio import local
from txtool.lint.context import LintContext
from txtool.lint.problem import Problem
from txtool.lint.rule_helpers import is_xacro, label
from txtool.model.readers import Assumption, Placement

CODE = "TX304"
NAME = "outside-ros2-control"
SEVERITY = "warning"
FIXABLE = False


def check(ctx: LintContext) -> Iterable[Problem]:
    if not ctx.hints.components:
        return ()  # no <ros2_control> in the document
    readers = ctx.readers
    if readers.decided and not readers.reads(Placement.IN_COMPONENT):
        return ()  # no ROS 2 program reads the file: its top-level transmissions are the read
    return _outside(ctx, _ignoring(readers))


def _ignoring(readers: Assumption) -> str:
    """Who ignores a top-level transmission: the decided ROS 2 readers, and why they are."""
    if not readers.decided:
        return "ros2_control"
    names = ", ".join(r.named() for r in readers.readers if r.reads is Placement.IN_COMPONENT)
    return f"{names} ({'; '.join(dict.fromkeys(readers.because))})"


def _outside(ctx: LintContext, ignoring: str) -> Iterator[Problem]:
    for tx in ctx.facts:
        found = tx.found
        if tx.component is not None or _in_macro(ctx, found.element):
            continue
        form = "ROS 1 " if tx.ros1 else ""
        yield ctx.problem(
            CODE,
            found.element,
            f"{form}{label(found)} stands outside every <ros2_control> block of this document: "
            f"{ignoring} ignores it",
        )


def _in_macro(ctx: LintContext, element: etree._Element) -> bool:
    """In a xacro file read as written, a macro body may be instantiated anywhere."""
    if not ctx.literal:
        return False
    parent = element.getparent()
    while parent is not None:
        if is_xacro(parent) and local(parent) == "macro":
            return True
        parent = parent.getparent()
    return False
