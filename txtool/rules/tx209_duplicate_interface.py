"""An interface two ``<ros2_control>`` blocks both export: the resource manager keeps one.

What it does: reports a ``<joint>``, ``<sensor>`` or ``<gpio>`` of a ``<ros2_control>`` block
that declares a command (or state) interface whose full name (``NAME/INTERFACE``) an earlier
block of the robot already declares as a command (or state) interface, at the later member:
typically a joint named in two blocks, each with ``<command_interface name="position"/>``.
Names are compared as the parser reads them (stripped from Jazzy on, as written on Humble);
only where a ROS 2 program reads the document, after xacro expansion. A joint that two blocks
share with different interfaces (an actuator commanding it, a sensor reading its position,
as ros2_control's modular robot examples do) is not reported: nothing clashes.

Why it matters: the resource manager stores every exported interface under its full name,
one handle each. On Humble a second handle of that name is dropped without a word: the
controllers read and command the first block's, and the later block's hardware never sees
them. From Jazzy on the insertion throws "Tried to insert CommandInterface with already
existing key" (or StateInterface), which the resource manager logs: the later block's
state interface is left out, and its command interfaces from that one on are not imported.
Either way the robot does not run as written.

Loader: ros2_control's resource manager (ros-controls/ros2_control
hardware_interface/src/resource_manager.cpp ``import_state_interfaces``:413-426 and
``add_command_interfaces``:447-463, ``std::map::emplace``, on the humble branch @0941f73;
``insert_command_interface``:717-748 and ``add_state_interface``:951-963 @53b9999).

Failing example::

    <robot name="r">
      <link name="base"/><link name="arm"/>
      <joint name="shoulder" type="revolute">
        <parent link="base"/><child link="arm"/><axis xyz="0 0 1"/>
        <limit lower="-1" upper="1" effort="10" velocity="1"/>
      </joint>
      <ros2_control name="arm" type="system">
        <hardware><plugin>my_hardware/ArmSystem</plugin></hardware>
        <joint name="shoulder"><command_interface name="position"/></joint>
      </ros2_control>
      <ros2_control name="mock" type="system">
        <hardware><plugin>mock_components/GenericSystem</plugin></hardware>
        <joint name="shoulder"><command_interface name="position"/></joint>
      </ros2_control>
    </robot>

Expected finding: ``13:5 error TX209 joint 'shoulder' of <ros2_control> 'mock' exports command
interface 'shoulder/position', which <ros2_control> 'arm' (line 7) exports too: ros2_control's
resource manager keeps one handle per name (Humble drops this block's without a word; from
Jazzy on it logs "Tried to insert CommandInterface with already existing key"), so this
block's hardware never gets it``

Passing example::

    <robot name="r">
      <link name="base"/><link name="arm"/>
      <joint name="shoulder" type="revolute">
        <parent link="base"/><child link="arm"/><axis xyz="0 0 1"/>
        <limit lower="-1" upper="1" effort="10" velocity="1"/>
      </joint>
      <ros2_control name="motor" type="actuator">
        <hardware><plugin>my_hardware/Motor</plugin></hardware>
        <joint name="shoulder"><command_interface name="velocity"/></joint>
      </ros2_control>
      <ros2_control name="encoder" type="sensor">
        <hardware><plugin>my_hardware/Encoder</plugin></hardware>
        <joint name="shoulder"><state_interface name="position"/></joint>
      </ros2_control>
    </robot>

Fix: declare each joint (with its interfaces) in the one block whose hardware drives it, and
put its transmission there; a second block for the same joints (a mock beside the real
hardware) belongs in another description, chosen by a xacro argument.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator

from lxml import etree

from txtool.lint.context import LintContext
from txtool.lint.problem import Problem
from txtool.lint.rule_helpers import read_blocks, whole_robot
from txtool.model.robot import children

CODE = "TX209"
NAME = "duplicate-interface"
SEVERITY = "error"
FIXABLE = False

_MEMBERS = ("joint", "sensor", "gpio")
_KINDS = (("command_interface", "command"), ("state_interface", "state"))
_LOADER_WORDS = {"command": "CommandInterface", "state": "StateInterface"}


@whole_robot
def check(ctx: LintContext) -> Iterator[Problem]:
    blocks, read = read_blocks(ctx)
    owner: dict[tuple[str, str], etree._Element] = {}
    for block in blocks:
        mine: set[tuple[str, str]] = set()
        for member, tag in _members(block):
            yield from _clashes(ctx, block, member, tag, read, owner, mine)
        for key in mine:
            owner.setdefault(key, block)


def _members(block: etree._Element) -> Iterator[tuple[etree._Element, str]]:
    for child in block:
        if isinstance(child.tag, str) and etree.QName(child).localname in _MEMBERS:
            yield child, etree.QName(child).localname


def _clashes(ctx: LintContext, block: etree._Element, member: etree._Element, tag: str,
             read: Callable[[str], str], owner: dict[tuple[str, str], etree._Element],
             mine: set[tuple[str, str]]) -> Iterator[Problem]:
    written = member.get("name")
    if written is None:
        return
    name = read(written)
    clashing: list[tuple[str, str, etree._Element]] = []
    for element_tag, kind in _KINDS:
        for interface in children(member, element_tag):
            written_interface = interface.get("name")
            if written_interface is None:
                continue
            key = (kind, f"{name}/{read(written_interface)}")
            mine.add(key)
            earlier = owner.get(key)
            if earlier is not None:
                clashing.append((kind, key[1], earlier))
    if not clashing:
        return
    earlier = clashing[0][2]
    exports = " and ".join(f"{kind} interface '{full}'" for kind, full, _ in clashing)
    words = " / ".join(dict.fromkeys(_LOADER_WORDS[kind] for kind, _, _ in clashing))
    yield ctx.problem(
        CODE, member,
        f"{tag} '{name}' of <ros2_control> '{block.get('name', '')}' exports {exports}, which "
        f"<ros2_control> '{earlier.get('name', '')}' (line {ctx.position(earlier).line}) "
        "exports too: ros2_control's resource manager keeps one handle per name (Humble drops "
        f"this block's without a word; from Jazzy on it logs \"Tried to insert {words} with "
        f"already existing key\"), so this block's hardware never gets "
        f"{'it' if len(clashing) == 1 else 'them'}")
