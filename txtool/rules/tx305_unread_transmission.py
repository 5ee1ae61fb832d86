"""A transmission that none of the file's readers reads.

What it does: reports, when the file's readers are known (``package.xml``, a ``<gazebo>``
plugin, ``--ros-distro`` or ``readers``/``ros-distro`` in the configuration; see "Readers" in the
loader documentation), a ``<transmission>`` standing where none of them looks: a top-level one
when only ROS 2 programs read the file, one inside ``<ros2_control>`` when only ROS 1 programs
do. It gets this one finding; its contents are not judged, since no loader ever sees them (a
missing reduction refuses nothing when nobody reads the transmission).

Why it matters: the transmission has no effect. ``info`` for a leftover: ROS 1 transmissions in
a ROS 2 robot (beside its ``<ros2_control>`` blocks or not), or ``<ros2_control>`` blocks in a
ROS 1 package. ``warning`` where the transmission looks meant to be read: a top-level
transmission written in a ROS 2 form (``<plugin>``, ``role`` attributes), which ros2_control
would read inside a ``<ros2_control>`` block. A ROS 2 Gazebo plugin in a robot without any
``<ros2_control>`` block is TX007's error.

Loader: ros_control's ``TransmissionParser::parse`` reads only the children of the root element
(ros-controls/ros_control transmission_interface/src/transmission_parser.cpp
``root->FirstChildElement("transmission")``), and gazebo_ros_control's RobotHWSim plugins take
what it parses. ros2_control's component parser reads only the ``<transmission>`` children of
``<ros2_control>`` (ros-controls/ros2_control hardware_interface/src/component_parser.cpp
``parse_resource_from_xml``), and gazebo_ros2_control, gz_ros2_control and mujoco_ros2_control
all parse the robot with it.

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
      <gazebo>
        <plugin filename="gz_ros2_control-system"
                name="gz_ros2_control::GazeboSimROS2ControlPlugin"/>
      </gazebo>
    </robot>

Expected finding: ``2:3 info TX305 ROS 1 transmission 'wheel_trans' stands outside every
<ros2_control> block, where none of this file's readers looks (gz_ros2_control, ros2_control:
<gazebo> plugin gz_ros2_control-system): nothing reads it; txtool migrate --write --to
ros2-p2 moves it into a <ros2_control> block``

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
      <gazebo>
        <plugin filename="gz_ros2_control-system"
                name="gz_ros2_control::GazeboSimROS2ControlPlugin"/>
      </gazebo>
    </robot>

Fix: move the transmission inside ``<ros2_control>`` (``txtool migrate --write --to
ros2-p2``), or delete it.
"""

from __future__ import annotations

import os
from collections.abc import Iterator

from txtool.lint.context import LintContext
from txtool.lint.facts import Facts
from txtool.lint.problem import Problem, Severity
from txtool.model.readers import Placement, placement_of

CODE = "TX305"
NAME = "unread-transmission"
SEVERITY = "info"
FIXABLE = False


def check(ctx: LintContext) -> Iterator[Problem]:
    unread = ctx.unread
    if not unread:
        return
    named = _readers(ctx)
    for tx in unread:
        element = tx.found.element
        if ctx.in_macro(element):  # a macro's transmission stands where its form belongs
            top = tx.ros1
            where = f"is written in the {'ROS 1' if top else 'ROS 2'} form in a macro"
        else:
            top = placement_of(element) is Placement.TOP_LEVEL
            where = ("stands outside every <ros2_control> block" if top
                     else "stands inside a <ros2_control> block")
        form = "ROS 1 " if tx.ros1 and not ctx.in_macro(element) else ""
        yield ctx.problem(
            CODE, tx.found.element,
            f"{form}{tx.label} {where}, where none of this file's readers looks ({named}): "
            f"nothing reads it; {_FIX[top]}",
            loader_severity=_severity(tx, top),
        )


# What moves the transmission where its readers look (or says there is nothing to move it with).
_FIX = {
    True: "txtool migrate --write --to ros2-p2 moves it into a <ros2_control> block",
    False: "move it to the top level in the ROS 1 form, or delete it",
}


def _readers(ctx: LintContext) -> str:
    """``ros2_control: package.xml: ament_cmake``; a configuration named by its file name alone
    (the folder is the user's own, and repeated on every finding it filled the line)."""
    found = ctx.readers
    if not found.readers:
        return "no reader known"
    reasons = "; ".join(dict.fromkeys(_short(why) for why in found.because))
    return f"{', '.join(found.names())}: {reasons}"


def _short(reason: str) -> str:
    return " ".join(os.path.basename(word) if os.path.isabs(word) else word
                    for word in reason.split(" "))


def _severity(tx: Facts, top: bool) -> Severity:
    """Warning where the transmission looks meant to be read (see the rule's documentation)."""
    return "warning" if top and not tx.ros1 else "info"
