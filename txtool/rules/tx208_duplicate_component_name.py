"""Two ``<ros2_control>`` blocks with one name: the resource manager loads no hardware.

What it does: reports a ``<ros2_control>`` element of the robot whose ``name`` an earlier one
already has, at the later one. Names are compared as the parser reads them: stripped of
surrounding spaces from Jazzy on, as written on Humble. Only where a ROS 2 program reads the
document, after xacro expansion (a macro called twice writes two blocks of one name).

Why it matters: ros2_control's resource manager keys each hardware component by its name.
On Humble it throws "Hardware name NAME is duplicated. Please provide a unique 'name' in the
URDF." while loading the robot description, and the controller manager (or the Gazebo plugin)
stops; from Jazzy on it logs that error, stops loading and clears every component already
loaded: no hardware of the robot runs. A conversion that adds a block beside an existing one
must give it a name of its own.

Loader: ros2_control's resource manager (ros-controls/ros2_control
hardware_interface/src/resource_manager.cpp ``ResourceStorage::check_for_duplicates``:479-487,
called by ``load_and_initialize_actuator``/``sensor``/``system``:495-540 on the humble branch
@0941f73; ``ResourceManager::load_and_initialize_components``:1557-1568 and :1612-1618
@53b9999).

Failing example::

    <robot name="r">
      <link name="base"/><link name="arm"/><link name="tool"/>
      <joint name="shoulder" type="revolute">
        <parent link="base"/><child link="arm"/><axis xyz="0 0 1"/>
        <limit lower="-1" upper="1" effort="10" velocity="1"/>
      </joint>
      <joint name="wrist" type="revolute">
        <parent link="arm"/><child link="tool"/><axis xyz="0 0 1"/>
        <limit lower="-1" upper="1" effort="10" velocity="1"/>
      </joint>
      <ros2_control name="robot" type="system">
        <hardware><plugin>mock_components/GenericSystem</plugin></hardware>
        <joint name="shoulder"><command_interface name="position"/></joint>
      </ros2_control>
      <ros2_control name="robot" type="system">
        <hardware><plugin>mock_components/GenericSystem</plugin></hardware>
        <joint name="wrist"><command_interface name="position"/></joint>
      </ros2_control>
    </robot>

Expected finding: ``15:3 error TX208 <ros2_control> name 'robot' is also the name of the block
at line 11: ros2_control's resource manager refuses it ("Hardware name robot is duplicated"):
Humble throws and the controller manager stops; from Jazzy on no hardware of the robot is
loaded``

Passing example::

    <robot name="r">
      <link name="base"/><link name="arm"/><link name="tool"/>
      <joint name="shoulder" type="revolute">
        <parent link="base"/><child link="arm"/><axis xyz="0 0 1"/>
        <limit lower="-1" upper="1" effort="10" velocity="1"/>
      </joint>
      <joint name="wrist" type="revolute">
        <parent link="arm"/><child link="tool"/><axis xyz="0 0 1"/>
        <limit lower="-1" upper="1" effort="10" velocity="1"/>
      </joint>
      <ros2_control name="arm" type="system">
        <hardware><plugin>mock_components/GenericSystem</plugin></hardware>
        <joint name="shoulder"><command_interface name="position"/></joint>
      </ros2_control>
      <ros2_control name="wrist" type="system">
        <hardware><plugin>mock_components/GenericSystem</plugin></hardware>
        <joint name="wrist"><command_interface name="position"/></joint>
      </ros2_control>
    </robot>

Fix: give each ``<ros2_control>`` block a name of its own (a macro called several times
takes a prefix for it), or declare the joints in one block.
"""

from __future__ import annotations

from collections.abc import Iterator

from lxml import etree

from txtool.lint.context import LintContext
from txtool.lint.problem import Problem
from txtool.lint.rule_helpers import read_blocks, whole_robot

CODE = "TX208"
NAME = "duplicate-component-name"
SEVERITY = "error"
FIXABLE = False


@whole_robot
def check(ctx: LintContext) -> Iterator[Problem]:
    blocks, read = read_blocks(ctx)
    first: dict[str, etree._Element] = {}
    for block in blocks:
        written = block.get("name")
        if written is None:
            continue  # the parser refuses a block without a name before this
        name = read(written)
        earlier = first.setdefault(name, block)
        if earlier is block:
            continue
        line = ctx.position(earlier).line
        yield ctx.problem(
            CODE, block,
            f"<ros2_control> name '{name}' is also the name of the block at line {line}: "
            f"ros2_control's resource manager refuses it (\"Hardware name {name} is "
            "duplicated\"): Humble throws and the controller manager stops; from Jazzy on no "
            "hardware of the robot is loaded", refuses_whole=True)
