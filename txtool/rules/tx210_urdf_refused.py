"""A robot urdfdom refuses to build: no hardware of it loads, under ROS 1 or ROS 2.

What it does: reports, in a whole robot (a ``<robot>`` with links, as written without xacro or
after xacro expansion) that ros_control or ros2_control reads (it has transmissions or
``<ros2_control>`` blocks), what urdfdom's model builder refuses: a robot, link or joint without
a ``name``; two links or two joints of one name; a joint without a ``type``, or of a type URDF
does not know; a ``revolute`` or ``prismatic`` joint without ``<limit>``, or a ``<limit>``
without ``effort`` or ``velocity``; a joint without ``<parent link>`` or ``<child link>``, or
naming a link the robot does not have; and, when every joint holds, links that do not form one
tree (no link without a parent, or two of them). A xacro file read as written (its links may
come from its includes or its includer) is not judged, nor the expansion of one whose
``<robot>`` has no name (a fragment written to be included). urdfdom also refuses malformed numbers,
materials and geometry: those are not checked here.

Why it matters: ros2_control's parser builds the URDF model with urdfdom after reading the
``<ros2_control>`` blocks and throws "Failed to parse URDF file" when it fails: no hardware of
the robot loads. Every other reader of ``robot_description`` built on urdfdom refuses it too
(robot_state_publisher; Gazebo's URDF import, which then spawns no robot, under ROS 1 too).
The message gives urdfdom's own words (logged by ``parseURDF``).

Loader: ros/urdfdom urdf_parser/src/model.cpp ``parseURDF``, joint.cpp ``parseJoint``,
link.cpp ``parseLink`` @9a1f5b4 (the same checks in 3.0.1) and ros/urdfdom_headers
urdf_model/include/urdf_model/model.h ``initTree``/``initRoot``; ros-controls/ros2_control
hardware_interface/src/component_parser.cpp ``parse_control_resources_from_urdf`` @53b9999.

Failing example::

    <robot name="r">
      <link name="base"/><link name="arm"/>
      <joint name="shoulder" type="revolute">
        <parent link="torso"/><child link="arm"/><axis xyz="0 0 1"/>
        <limit lower="-1" upper="1" effort="10" velocity="1"/>
      </joint>
      <ros2_control name="robot" type="system">
        <hardware><plugin>mock_components/GenericSystem</plugin></hardware>
        <joint name="shoulder"><command_interface name="position"/></joint>
      </ros2_control>
    </robot>

Expected finding: ``4:5 error TX210 urdfdom refuses the robot ("Failed to build tree: parent
link [torso] of joint [shoulder] not found"): so do the readers of the robot built on it
(ros2_control throws "Failed to parse URDF file")``

Passing example::

    <robot name="r">
      <link name="base"/><link name="arm"/>
      <joint name="shoulder" type="revolute">
        <parent link="base"/><child link="arm"/><axis xyz="0 0 1"/>
        <limit lower="-1" upper="1" effort="10" velocity="1"/>
      </joint>
      <ros2_control name="robot" type="system">
        <hardware><plugin>mock_components/GenericSystem</plugin></hardware>
        <joint name="shoulder"><command_interface name="position"/></joint>
      </ros2_control>
    </robot>

Fix: declare the link (``<link name="torso"/>``), name the right one, or remove the joint;
give every link one parent joint but the root.
"""

from __future__ import annotations

from collections.abc import Iterator

from lxml import etree

from txtool.lint.context import LintContext
from txtool.lint.problem import Problem
from txtool.lint.rule_helpers import whole_robot

CODE = "TX210"
NAME = "urdf-refused"
SEVERITY = "error"
FIXABLE = False

# urdfdom joint.cpp parseJoint: the types it knows
_TYPES = frozenset({"planar", "floating", "revolute", "continuous", "prismatic", "fixed"})
_LIMITED = {"revolute": "REVOLUTE but it does not specify limits",
            "prismatic": "PRISMATIC without limits"}

Refusal = tuple[etree._Element, str]


@whole_robot
def check(ctx: LintContext) -> Iterator[Problem]:
    root = ctx.source.root
    if ctx.literal or _urdf(root) != "robot" or not (ctx.found or ctx.hints.components):
        return
    if ctx.source.expanded and root.get("name") is None:
        return  # a xacro fragment: written to be included, its links are its includer's
    links, joints = [], []
    for element in root:
        name = _urdf(element)
        if name == "link":
            links.append(element)
        elif name == "joint":
            joints.append(_Joint(element))
    if not links:
        return  # a fragment (urdfdom: "No link elements found in urdf file")
    refused = [*_robot(root), *_links(links), *_joints(joints)]
    if not refused:
        refused = _tree(links, joints)
    for element, words in refused:
        yield ctx.problem(
            CODE, element,
            f"urdfdom refuses the robot (\"{words}\"): so do the readers of the robot built on "
            "it (ros2_control throws \"Failed to parse URDF file\")", refuses_whole=True)


def _urdf(element: etree._Element) -> str | None:
    """The name urdfdom reads ``element`` as (None: a comment, or a prefixed name): tinyxml2
    compares the tag as written, so only a default namespace hides in a bare name."""
    tag = element.tag  # a function for comments and processing instructions
    if tag.__class__ is not str:
        return None
    if tag[0] != "{":
        return tag
    return tag.rpartition("}")[2] if element.prefix is None else None


class _Joint:
    """A ``<joint>`` and what urdfdom reads of the first of each of its children, found in
    one pass and kept as strings: a robot's joints are all held at once, their children are
    looked up again only for a refusal."""

    __slots__ = ("element", "limit", "parent", "child")

    def __init__(self, element: etree._Element) -> None:
        self.element = element
        # None: no <limit>; else the first of its attributes urdfdom requires that it lacks
        # ("" for none).
        self.limit: str | None = None
        # The link the first <parent> and <child> name ("" for none, or for no such child).
        self.parent = self.child = ""
        seen: set[str] = set()
        for child in element:
            name = _urdf(child)
            if name not in ("limit", "parent", "child") or name in seen:
                continue
            seen.add(name)
            if name == "limit":
                self.limit = next((key for key in ("effort", "velocity")
                                   if child.get(key) is None), "")
            elif name == "parent":
                self.parent = child.get("link") or ""
            else:
                self.child = child.get("link") or ""

    def part(self, name: str) -> etree._Element:
        """The first child urdfdom reads as ``name`` (the joint itself where it has none)."""
        return next((child for child in self.element if _urdf(child) == name), self.element)


def _robot(root: etree._Element) -> Iterator[Refusal]:
    if root.get("name") is None:
        yield root, "No name given for the robot."


def _links(links: list[etree._Element]) -> Iterator[Refusal]:
    seen: set[str] = set()
    for link in links:
        name = link.get("name")
        if name is None:
            yield link, "No name given for the link."
        elif name in seen:
            yield link, f"link '{name}' is not unique."
        seen.add(name or "")


def _joints(joints: list[_Joint]) -> Iterator[Refusal]:
    seen: set[str] = set()
    for read in joints:
        joint = read.element
        name = joint.get("name")
        if name is None:
            yield joint, "unnamed joint found"
            continue
        kind = joint.get("type")
        limit = read.limit
        if kind is None:
            yield joint, f"joint [{name}] has no type, check to see if it's a reference."
        elif kind not in _TYPES:
            yield joint, f"Joint [{name}] has no known type [{kind}]"
        elif limit is None and kind in _LIMITED:
            yield joint, f"Joint [{name}] is of type {_LIMITED[kind]}"
        elif limit:
            yield read.part("limit"), f"joint limit: no {limit}"
        elif name in seen:
            yield joint, f"joint '{name}' is not unique."
        seen.add(name)


def _tree(links: list[etree._Element], joints: list[_Joint]) -> list[Refusal]:
    """What ``initTree`` refuses, else what ``initRoot`` refuses, once every link and joint
    was read."""
    names = {link.get("name", "") for link in links}
    children: set[str] = set()
    refused: list[Refusal] = []
    for read in joints:
        joint = read.element
        name = joint.get("name", "")
        parent_name, child_name = read.parent, read.child
        if not parent_name or not child_name:
            refused.append((joint, f"Failed to build tree: Joint [{name}] is missing a parent "
                                   "and/or child link specification."))
        elif child_name not in names:
            refused.append((read.part("child"), f"Failed to build tree: child link "
                                                f"[{child_name}] of joint [{name}] not found"))
        elif parent_name not in names:
            refused.append((read.part("parent"), f"Failed to build tree: parent link "
                                                 f"[{parent_name}] of joint [{name}] not found"))
        else:
            children.add(child_name)
    return refused or _root(links, children)


def _root(links: list[etree._Element], children: set[str]) -> list[Refusal]:
    roots = sorted((link for link in links if link.get("name") not in children),
                   key=lambda link: link.get("name", ""))
    if not roots:
        return [(links[0], "Failed to find root link: No root link found. The robot xml is "
                           "not a valid tree.")]
    if len(roots) == 1:
        return []
    # initRoot walks the links in name order and names the first two without a parent
    first, second = roots[0].get("name"), roots[1].get("name")
    return [(roots[1], f"Failed to find root link: Two root links found: [{first}] and "
                       f"[{second}]")]
