"""A mimic joint of the URDF with a command interface in ``<ros2_control>``: refused from Jazzy on.

What it does: reports a ``<joint>`` of a ``<ros2_control>`` element (a child of ``<robot>``)
that has a ``<command_interface>``, whose URDF joint has a ``<mimic>``, and that does not say
``mimic="false"``. The severity follows the readers (``--ros-distro``, ``ros-distro``): an
**error** when only Jazzy or later reads the file, a **warning** when Humble may read it too,
nothing when only Humble does.

Why it matters: from ros2_control 4.13 (Jazzy, Kilted, Rolling; ros-controls/ros2_control#1553)
the parser takes mimic joints from the URDF and refuses a mimic joint that may be commanded: it
throws "Joint 'J' has mimic attribute not set to false: Activated mimic joints cannot have
command interfaces." and no hardware of the robot loads; the controller manager, or the
gazebo/gz ros2_control plugin, stops. Humble's parser reads no mimic information and accepts
the robot, so descriptions written for Humble (the ``<param name="mimic">`` idiom of gripper
descriptions) break when the robot moves to Jazzy.

Loader: ros2_control (ros-controls/ros2_control hardware_interface/src/component_parser.cpp
``parse_control_resources_from_urdf`` @53b9999).

Failing example::

    <robot name="gripper">
      <link name="palm"/>
      <link name="left"/>
      <link name="right"/>
      <joint name="left_finger" type="prismatic">
        <parent link="palm"/><child link="left"/><axis xyz="1 0 0"/>
        <limit lower="0" upper="0.04" effort="10" velocity="0.1"/>
      </joint>
      <joint name="right_finger" type="prismatic">
        <parent link="palm"/><child link="right"/><axis xyz="-1 0 0"/>
        <limit lower="0" upper="0.04" effort="10" velocity="0.1"/>
        <mimic joint="left_finger"/>
      </joint>
      <ros2_control name="gripper" type="system">
        <hardware><plugin>mock_components/GenericSystem</plugin></hardware>
        <joint name="left_finger"><command_interface name="position"/></joint>
        <joint name="right_finger"><command_interface name="position"/></joint>
      </ros2_control>
    </robot>

Expected finding: ``17:5 warning TX206 joint 'right_finger' mimics 'left_finger' in the URDF and
has a command interface here: ros2_control from Jazzy on refuses the robot ("Activated mimic
joints cannot have command interfaces") (Humble's parser reads no mimic information and accepts
it); drop its command interface or say mimic="false"``

Passing example::

    <robot name="gripper">
      <link name="palm"/>
      <link name="left"/>
      <link name="right"/>
      <joint name="left_finger" type="prismatic">
        <parent link="palm"/><child link="left"/><axis xyz="1 0 0"/>
        <limit lower="0" upper="0.04" effort="10" velocity="0.1"/>
      </joint>
      <joint name="right_finger" type="prismatic">
        <parent link="palm"/><child link="right"/><axis xyz="-1 0 0"/>
        <limit lower="0" upper="0.04" effort="10" velocity="0.1"/>
        <mimic joint="left_finger"/>
      </joint>
      <ros2_control name="gripper" type="system">
        <hardware><plugin>mock_components/GenericSystem</plugin></hardware>
        <joint name="left_finger"><command_interface name="position"/></joint>
        <joint name="right_finger"><state_interface name="position"/></joint>
      </ros2_control>
    </robot>

Fix: drop the ``<command_interface>`` of the mimic joint (its position follows its leader; the
mock and simulated systems propagate it), or say ``mimic="false"`` on the ``<ros2_control>``
joint if it really has its own actuator.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator

from txtool.lint.context import LintContext
from txtool.lint.problem import Problem
from txtool.lint.rule_helpers import whole_robot
from txtool.model.distro import Distro

CODE = "TX206"
NAME = "mimic-command-interface"
SEVERITY = "error"
FIXABLE = False


@whole_robot
def check(ctx: LintContext) -> Iterable[Problem]:
    if not ctx.hints.mimics or ctx.literal or not ctx.is_robot:
        return ()  # no <mimic> in the document, or one read as written (xacro not expanded)
    refusing = [d for d in ctx.readers.distros if d.ros2 and d is not Distro.HUMBLE]
    if not refusing:
        return ()  # only Humble (or no ROS 2 parser) reads this file
    accepting = Distro.HUMBLE in ctx.readers.distros
    return _refused(ctx, accepting)


def _refused(ctx: LintContext, accepting: bool) -> Iterator[Problem]:
    root = ctx.source.root
    for block in root.iterchildren("{*}ros2_control"):
        for joint in block.iterchildren("{*}joint"):
            name = (joint.get("name") or "").strip()
            info = ctx.joints.get(name)
            if info is None or info.mimic is None:
                continue
            if (joint.get("mimic") or "").strip().lower() == "false":
                continue
            if next(joint.iterchildren("{*}command_interface"), None) is None:
                continue
            humble = (" (Humble's parser reads no mimic information and accepts it)"
                      if accepting else "")
            yield ctx.problem(
                CODE, joint,
                f"joint '{name}' mimics '{info.mimic}' in the URDF and has a command interface "
                "here: ros2_control from Jazzy on refuses the robot (\"Activated mimic joints "
                f"cannot have command interfaces\"){humble}; drop its command interface or "
                "say mimic=\"false\"",
                loader_severity="warning" if accepting else None, refuses_whole=True)
