"""Which joints a ``<ros2_control>`` may declare for a converted transmission, and how.

ros2_control's parser reads every joint of every ``<ros2_control>`` against the robot's URDF
(ros-controls/ros2_control hardware_interface/src/component_parser.cpp,
``parse_control_resources_from_urdf``) and refuses the whole robot, no hardware loading, for:

- a joint the URDF lacks: "Joint 'J' not found in URDF";
- a fixed joint: "Joint 'J' is of type 'fixed'. Fixed joints do not make sense in
  ros2_control.";
- a joint with a URDF ``<mimic>`` that has a command interface, unless it says
  ``mimic="false"``: "Joint 'J' has mimic attribute not set to false: Activated mimic joints
  cannot have command interfaces." (from Jazzy on; Humble's parser reads no mimic
  information and no ``mimic`` attribute, so the attribute changes nothing there).

ROS 1 could not bind a transmission on a fixed or missing joint either (gazebo_ros_control's
``DefaultRobotHWSim::initSim``: "not in the gazebo model"), so such a transmission is not
carried into a ``<ros2_control>``: it is left as written, and said. A transmission on a mimic
joint gave that joint a command handle under ros_control, which commanded it as any other
joint: its declaration keeps the command interfaces and says ``mimic="false"``, the one form
both parsers accept that commands the joint as ROS 1 did.

Only what the document shows is judged: a joint found in it (its name and type written
literally, outside any xacro conditional), and a joint missing only from a whole robot (a
``<robot>`` with URDF joints that neither declares the xacro namespace nor holds a xacro
element: a xacro file's joints may come from the files it includes or from its includer).
"""

from __future__ import annotations

from collections.abc import Iterable

from lxml import etree

from txtool.io.xmlio import local
from txtool.model.robot import children, joint_elements
from txtool.transform.placement.layout import namespace_of
from txtool.transform.placement.scope import XACRO, is_condition

FIXED = "Joint '{}' is of type 'fixed'. Fixed joints do not make sense in ros2_control."
MISSING = "Joint '{}' not found in URDF"


class RobotJoints:
    """The URDF joints of one document, read when first asked about."""

    def __init__(self, root: etree._Element) -> None:
        self.root = root
        self._elements: dict[str, etree._Element] | None = None
        self._whole: bool | None = None
        self._leaders: dict[str, str] | None = None

    @property
    def elements(self) -> dict[str, etree._Element]:
        if self._elements is None:
            robot = local(self.root) == "robot"
            self._elements = joint_elements(self.root) if robot else {}
        return self._elements

    def whole(self) -> bool:
        """Whether the document is a whole robot: a ``<robot>`` with joints and no xacro
        element (a joint it lacks is lacking from the robot)."""
        if self._whole is None:
            self._whole = bool(self.elements) and "xacro" not in self.root.nsmap and not any(
                uri in XACRO for uri in self.root.nsmap.values()) and not any(
                namespace_of(e) in XACRO or e.prefix == "xacro"
                for e in self.root.iter(etree.Element))
        return self._whole

    def _known(self, name: str) -> etree._Element | None:
        """The joint named ``name``, when the document says what it is for every argument."""
        element = self.elements.get(name)
        if element is None or _expression(element.get("type")) or any(
                map(is_condition, element.iterancestors())):
            return None
        return element

    def refusal(self, names: Iterable[str]) -> str | None:
        """What ros2_control says of the first of ``names`` it would refuse in a
        ``<ros2_control>`` (fixed, or not in the robot), or None."""
        for name in names:
            if _expression(name):
                continue
            element = self._known(name)
            if element is not None and element.get("type") == "fixed":
                return FIXED.format(name)
            if element is None and name not in self.elements and self.whole():
                return MISSING.format(name)
        return None

    def mimicked(self, name: str) -> str | None:
        """The joint ``name`` mimics in the URDF, or None."""
        if self._leaders is None:
            # Few joints mimic: their <mimic> elements are found in one walk of the document,
            # rather than looked for in every joint asked about.
            self._leaders = {}
            for mimic in self.root.iter("{*}mimic"):
                joint = mimic.getparent()
                named = joint.get("name") if joint is not None else None
                if named is not None and self.elements.get(named) is joint:
                    self._leaders.setdefault(named, mimic.get("joint") or "")
        leader = self._leaders.get(name)
        if leader is None or _expression(name) or self._known(name) is None:
            return None
        return leader


def _expression(text: str | None) -> bool:
    return text is not None and ("${" in text or "$(" in text)


def left_as_written(name: str, refusal: str) -> str:
    """The warning for a transmission not carried into a ``<ros2_control>``."""
    return (f"transmission '{name}': left as written, not carried into <ros2_control>: "
            f"ros2_control refuses a robot whose <ros2_control> declares its joint (\"{refusal}\""
            ", component_parser.cpp), and ros_control could not drive it either; correct the "
            "joint's name or type, or delete the transmission")


def not_mimicking(block: etree._Element, joints: RobotJoints) -> list[str]:
    """Say ``mimic="false"`` on each joint of ``block`` that has a URDF ``<mimic>`` and a
    command interface; the notes that say so."""
    notes = []
    for declaration in children(block, "joint"):
        name = declaration.get("name") or ""
        leader = joints.mimicked(name)
        if leader is None or not children(declaration, "command_interface"):
            continue
        declaration.set("mimic", "false")
        notes.append(
            f"joint '{name}' mimics '{leader}' in the URDF: declared with mimic=\"false\", so "
            "that ros2_control keeps its command interfaces as ros_control did (from Jazzy on "
            "the parser refuses an activated mimic joint with command interfaces: \"Activated "
            "mimic joints cannot have command interfaces\"); to have the hardware follow the "
            "mimic instead, drop the attribute and its command interfaces and declare the "
            f"joint '{leader}' in the same <ros2_control>")
    return notes
