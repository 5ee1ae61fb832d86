"""Small robots made for the fault matrix, each written as ROS 1 ``<transmission>`` elements and
as a ``<ros2_control>`` block with the same maths.

* ``chain``: four revolute joints in series, simple transmissions of reductions 1, 50, 160 and
  -7.5 (one reversed), one joint offset;
* ``differential``: a simple shoulder and a differential elbow/wrist (actuator reductions 30
  and 20, joint reductions 1 and 1.5, an elbow offset);
* ``four_bar``: the same arm with a four-bar linkage instead of the differential;
* ``counterbalanced``: a heavy shoulder whose gravity load is about 1.6 times its effort limit,
  so simulate assumes a counterbalance for it, and a light elbow.

:func:`derived` makes robots from a corpus robot: other reductions, two joints on a
differential, lower effort limits.
"""

from __future__ import annotations

from dataclasses import dataclass

from lxml import etree

from tests.simulate.robots import link
from txtool.io.xmlio import parse_bytes

EFFORT_ROS1 = "<hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>"


@dataclass(frozen=True)
class Joint:
    name: str
    axis: str  # "0 1 0"
    lower: float
    upper: float
    effort: float
    child: str  # link name
    origin: float  # x offset from the parent link's frame, m


@dataclass(frozen=True)
class Coupled:
    """A differential or four-bar on two joints (ROS 1 role order = XML order)."""

    name: str
    kind: str  # DifferentialTransmission | FourBarLinkageTransmission
    joints: tuple[str, str]
    actuators: tuple[str, str]
    actuator_reduction: tuple[float, float]
    joint_reduction: tuple[float, float]
    offset: tuple[float, float]


@dataclass(frozen=True)
class Generated:
    name: str
    links: tuple[str, ...]  # <link> elements
    joints: tuple[Joint, ...]
    simple: tuple[tuple[str, float, float], ...]  # (joint, reduction, offset)
    coupled: tuple[Coupled, ...] = ()

    def body(self) -> str:
        parents = ["base", *(j.child for j in self.joints)]
        joints = "".join(
            f'<joint name="{j.name}" type="revolute"><parent link="{parents[k]}"/>'
            f'<child link="{j.child}"/><origin xyz="{j.origin} 0 0"/><axis xyz="{j.axis}"/>'
            f'<limit lower="{j.lower}" upper="{j.upper}" effort="{j.effort}" velocity="3"/>'
            '<dynamics damping="0.02"/></joint>'
            for k, j in enumerate(self.joints))
        return '<link name="base"/>' + "".join(self.links) + joints

    def ros1(self) -> str:
        out = []
        for joint, n, offset in self.simple:
            out.append(
                f'<transmission name="t_{joint}"><type>transmission_interface/SimpleTransmission'
                f'</type><joint name="{joint}"><offset>{offset}</offset>{EFFORT_ROS1}</joint>'
                f'<actuator name="m_{joint}"><mechanicalReduction>{n}</mechanicalReduction>'
                "</actuator></transmission>")
        for c in self.coupled:
            joints = "".join(
                f'<joint name="{j}"><role>joint{k + 1}</role><offset>{c.offset[k]}</offset>'
                f"<mechanicalReduction>{c.joint_reduction[k]}</mechanicalReduction>"
                f"{EFFORT_ROS1}</joint>" for k, j in enumerate(c.joints))
            actuators = "".join(
                f'<actuator name="{a}"><role>actuator{k + 1}</role><mechanicalReduction>'
                f"{c.actuator_reduction[k]}</mechanicalReduction></actuator>"
                for k, a in enumerate(c.actuators))
            out.append(f'<transmission name="{c.name}"><type>transmission_interface/{c.kind}'
                       f"</type>{joints}{actuators}</transmission>")
        return f'<robot name="{self.name}">{self.body()}{"".join(out)}</robot>'

    def ros2(self) -> str:
        """The same maths for ros2_control: a simple transmission's reduction on its joint,
        coupled members in name order (ros2_control binds parameters in XML order to the
        members sorted by name)."""
        joints = "".join(
            f'<joint name="{j.name}"><command_interface name="effort"/>'
            '<state_interface name="position"/><state_interface name="velocity"/></joint>'
            for j in self.joints)
        out = []
        for joint, n, offset in self.simple:
            out.append(
                f'<transmission name="t_{joint}"><plugin>transmission_interface/'
                f'SimpleTransmission</plugin><actuator name="m_{joint}" role="actuator1"/>'
                f'<joint name="{joint}" role="joint1"><mechanical_reduction>{n}'
                f"</mechanical_reduction><offset>{offset}</offset></joint></transmission>")
        for c in self.coupled:
            assert list(c.joints) == sorted(c.joints) and list(c.actuators) == sorted(c.actuators)
            actuators = "".join(
                f'<actuator name="{a}" role="actuator{k + 1}"><mechanical_reduction>'
                f"{c.actuator_reduction[k]}</mechanical_reduction></actuator>"
                for k, a in enumerate(c.actuators))
            members = "".join(
                f'<joint name="{j}" role="joint{k + 1}"><mechanical_reduction>'
                f"{c.joint_reduction[k]}</mechanical_reduction><offset>{c.offset[k]}</offset>"
                "</joint>" for k, j in enumerate(c.joints))
            out.append(f'<transmission name="{c.name}"><plugin>transmission_interface/{c.kind}'
                       f"</plugin>{actuators}{members}</transmission>")
        block = (f'<ros2_control name="{self.name}" type="system"><hardware><plugin>'
                 f"mock_components/GenericSystem</plugin></hardware>{joints}{''.join(out)}"
                 "</ros2_control>")
        return f'<robot name="{self.name}">{self.body()}{block}</robot>'


def _arm(name: str, kind: str) -> Generated:
    return Generated(
        name=name,
        links=(link("l1", 1.0, 0.25, 0.02), link("l2", 0.8, 0.2, 0.01),
               link("l3", 0.3, 0.1, 0.002, "izz")),
        joints=(Joint("shoulder", "0 1 0", -1.5, 1.5, 40, "l1", 0.0),
                Joint("elbow", "0 1 0", -2, 2, 20, "l2", 0.5),
                Joint("wrist", "0 0 1", -1, 1, 10, "l3", 0.4)),
        simple=(("shoulder", 50, 0.0),),
        coupled=(Coupled("t_wrist", kind, ("elbow", "wrist"), ("m_left", "m_right"),
                         (30, 20), (1, 1.5), (0.1, 0.0)),),
    )


CHAIN = Generated(
    name="chain",
    links=(link("c1", 1.2, 0.2, 0.02, "izz"), link("c2", 1.0, 0.2, 0.015),
           link("c3", 0.6, 0.15, 0.006), link("c4", 0.2, 0.05, 0.001, "izz")),
    joints=(Joint("base_yaw", "0 0 1", -2, 2, 60, "c1", 0.0),
            Joint("shoulder", "0 1 0", -1.2, 1.2, 80, "c2", 0.1),
            Joint("elbow", "0 1 0", -1.5, 1.5, 40, "c3", 0.4),
            Joint("wrist", "0 0 1", -2.5, 2.5, 5, "c4", 0.3)),
    simple=(("base_yaw", 1, 0.0), ("shoulder", 50, 0.05), ("elbow", 160, 0.0),
            ("wrist", -7.5, 0.0)),
)

# 8 kg at 0.3 m needs up to 23.5 N·m against a 15 N·m limit: 1.57 times, so a counterbalance
# is assumed for the shoulder (simulate assumes none beyond 4 times).
COUNTERBALANCED = Generated(
    name="counterbalanced",
    links=(link("arm", 8.0, 0.3, 0.3), link("hand", 0.3, 0.1, 0.002)),
    joints=(Joint("shoulder", "0 1 0", -1.0, 1.0, 15, "arm", 0.0),
            Joint("elbow", "0 1 0", -1.5, 1.5, 10, "hand", 0.6)),
    simple=(("shoulder", 100, 0.0), ("elbow", 50, 0.0)),
)

DIFFERENTIAL = _arm("differential", "DifferentialTransmission")
FOUR_BAR = _arm("four_bar", "FourBarLinkageTransmission")


def derived(text: bytes, reductions: tuple[float, ...] = (), pair: tuple[str, str] | None = None,
            effort: dict[str, float] | None = None) -> bytes:
    """A robot made from another's URDF with ROS 1 simple transmissions: its reductions set in
    turn to ``reductions``, the transmissions of the two joints of ``pair`` replaced by one
    differential (their actuators and reductions, joint reductions 1; a ROS 1 four-bar would
    fail its own check, see docs/simulate.md), and the ``<limit effort>`` of the joints of
    ``effort`` set."""
    tree = parse_bytes(text, "robot")
    root = tree.getroot()
    simple = [t for t in root.findall("transmission") if "Simple" in (t.findtext("type") or "")]
    for k, t in enumerate(simple if reductions else []):
        value = t.find("actuator/mechanicalReduction")
        assert value is not None
        value.text = f"{reductions[k % len(reductions)]:g}"
    if pair is not None:
        owners = [next(t for t in simple if t.find("joint").get("name") == j) for j in pair]
        coupled = etree.Element("transmission", name=f"{pair[0]}_{pair[1]}_trans")
        etree.SubElement(coupled, "type").text = "transmission_interface/DifferentialTransmission"
        for k, t in enumerate(owners):
            joint = t.find("joint")
            role = etree.SubElement(joint, "role")
            role.text = f"joint{k + 1}"
            coupled.append(joint)
        for k, t in enumerate(owners):
            actuator = t.find("actuator")
            role = etree.SubElement(actuator, "role")
            role.text = f"actuator{k + 1}"
            coupled.append(actuator)
        owners[0].addprevious(coupled)
        for t in owners:
            root.remove(t)
    for joint in root.findall("joint"):
        if effort and joint.get("name") in effort:
            joint.find("limit").set("effort", f"{effort[joint.get('name')]:g}")
    return etree.tostring(tree, xml_declaration=True, encoding="utf-8")
