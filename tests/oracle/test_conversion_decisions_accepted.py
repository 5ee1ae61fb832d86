"""What convert writes for a ROS 1 robot, ros2_control's compiled parser accepts.

Every ROS 1 robot of ``../shared/corpus``, ``../shared/workspace`` and ``fixtures/`` (a
``<robot>`` with links, so that urdfdom builds its model), and variants made to hit each
decision of docs/conversion.md ("What the target accepts": mimic, fixed and missing joints,
every hardware interface, an actuator's interface, an existing block), is converted to
ros2-p2 (what the parser reads) and handed to ``parser17`` (Humble) and ``parser20`` (Jazzy and later):
either the conversion reports a loss (the command exits 1, naming why), or both accept the
result. A file where nothing became ROS 2 (custom types only) has no ``<ros2_control>`` and
is not asked about.
"""

from __future__ import annotations

from functools import cache
from pathlib import Path

import pytest
from lxml import etree

from tests.corpus import CORPUS, ROOT, WORKSPACE
from tests.oracle.reference import oracle_dir, run_parser
from txtool.io.xmlio import InputError, Source, parse_bytes
from txtool.transform.convert import convert_source

# ros2_control's parser reads the role attribute (Proposal 2); Proposal 1's <role> elements are
# a proposal it does not read ("no attribute 'role' in 'joint' tag").
TARGETS = ("ros2-p2",)
PARSERS = ("parser17", "parser20")

LINKS = "".join(f'<link name="l{i}"/>' for i in range(10))


def _joint(name: str, kind: str = "revolute", child: int = 1, mimic: str = "") -> str:
    inner = (f'<parent link="l0"/><child link="l{child}"/><axis xyz="0 0 1"/>'
             '<limit lower="-1" upper="1" effort="10" velocity="1"/>')
    return f'<joint name="{name}" type="{kind}">{inner}{mimic}</joint>\n'


def _transmission(name: str, joint: str, interface: str = "EffortJointInterface",
                  actuator: str = "") -> str:
    named = f"<hardwareInterface>{interface}</hardwareInterface>" if interface else ""
    return (f'<transmission name="{name}"><type>transmission_interface/SimpleTransmission'
            f'</type><joint name="{joint}">{named}</joint><actuator name="{name}_m">{actuator}'
            "<mechanicalReduction>-3</mechanicalReduction></actuator></transmission>\n")


def _robot(*parts: str) -> bytes:
    """A robot urdfdom builds: each link a joint's child has none of the parts makes is
    fixed to the root."""
    body = "".join(parts)
    tree = "".join(f'<joint name="pad{i}" type="fixed"><parent link="l0"/>'
                   f'<child link="l{i}"/></joint>' for i in range(1, 10)
                   if f'<child link="l{i}"/>' not in body)
    return f'<robot name="variant">{LINKS}{tree}\n{body}</robot>\n'.encode()


INTERFACES = ("hardware_interface/PositionJointInterface", "VelocityJointInterface",
              "hardware_interface/EffortJointInterface", "EffortJointInterface",
              "hardware_interface/BiDirectionalPositionJointInterface",
              "hardware_interface/PosVelJointInterface",
              "hardware_interface/PosVelAccJointInterface",
              "hardware_interface/JointStateInterface")
BLOCK = ('<ros2_control name="hw" type="system"><hardware><plugin>my/Hw</plugin></hardware>'
         '<joint name="a"><command_interface name="effort"/><state_interface name="position"/>'
         "</joint></ros2_control>\n")

VARIANTS = {
    "mimic": _robot(_joint("a"), _joint("b", child=2, mimic='<mimic joint="a"/>'),
                    _transmission("ta", "a"), _transmission("tb", "b")),
    "mimic alone": _robot(_joint("a"), _joint("b", child=2, mimic='<mimic joint="a"/>'),
                          _transmission("tb", "b", "PositionJointInterface")),
    "fixed": _robot(_joint("a"), _joint("f", "fixed", 2), _transmission("ta", "a"),
                    _transmission("tf", "f")),
    "missing": _robot(_joint("a"), _transmission("ta", "a"), _transmission("tg", "ghost")),
    "only fixed": _robot(_joint("f", "fixed"), _joint("a", child=2), _transmission("tf", "f")),
    "interfaces": _robot(*(_joint(f"j{i}", child=i + 1) for i in range(len(INTERFACES))),
                         *(_transmission(f"t{i}", f"j{i}", name)
                           for i, name in enumerate(INTERFACES))),
    "actuator's interface": _robot(_joint("a"), _transmission(
        "ta", "a", "", "<hardwareInterface>EffortJointInterface</hardwareInterface>")),
    "existing block": _robot(_joint("a"), _joint("b", child=2), BLOCK,
                             _transmission("ta", "a"), _transmission("tb", "b")),
}


def _ros1_robot(data: bytes) -> bool:
    """A ROS 1 robot urdfdom builds: a <robot> with links and a top-level <transmission>
    that has a <type> child."""
    try:
        root = etree.fromstring(data)
    except etree.XMLSyntaxError:
        return False
    return (root.tag == "robot" and root.find("link") is not None
            and any(t.find("type") is not None for t in root.findall("transmission")))


@cache
def documents() -> dict[str, bytes]:
    """The ROS 1 robots to convert, by a label."""
    found = {f"variant: {name}": data for name, data in VARIANTS.items()}
    files = [*sorted(CORPUS.glob("*.urdf")), *sorted(WORKSPACE.rglob("*.xml")),
             *sorted((ROOT / "fixtures").glob("*.urdf"))]
    for path in files:
        data = Path(path).read_bytes()
        if _ros1_robot(data):
            found[path.name] = data
    return found


@cache
def verdicts(target: str) -> dict[str, tuple[list[str], list[dict]]]:
    """Each document's losses and, where it converts, what each parser build says."""
    oracle_dir()
    converted: dict[str, bytes] = {}
    losses: dict[str, list[str]] = {}
    for label, data in documents().items():
        try:
            result = convert_source(Source(label, data, parse_bytes(data, label)), target)
        except InputError as exc:  # not a conversion txtool makes: said as its reason
            losses[label] = [str(exc)]
            continue
        losses[label] = result.losses
        if not result.losses and b"<ros2_control" in result.data:
            converted[label] = result.data
    labels = list(converted)
    said = {parser: run_parser(parser, [converted[label] for label in labels])
            for parser in PARSERS}
    return {label: (losses[label], [said[parser][i] for parser in PARSERS])
            for i, label in enumerate(labels)} | {
        label: (lost, []) for label, lost in losses.items() if label not in converted}


@pytest.mark.parametrize("target", TARGETS)
def test_every_ros1_robot_converts_to_what_both_parsers_accept_or_says_why(target):
    if not CORPUS.is_dir():
        pytest.skip(f"corpus not found at {CORPUS}")
    refused = {label: [f"{parser}: {r['error']}" for parser, r in zip(PARSERS, results,
                                                                       strict=True)
                       if not r["accepted"]]
               for label, (_, results) in verdicts(target).items() if results}
    assert {label: errors for label, errors in refused.items() if errors} == {}


@pytest.mark.parametrize("target", TARGETS)
def test_each_decision_converts_without_loss(target):
    lost = {label: losses for label, (losses, _) in verdicts(target).items()
            if label.startswith("variant: ") and losses}
    assert lost == {}
    accepted = {label for label, (_, results) in verdicts(target).items()
                if results and all(r["accepted"] for r in results)}
    assert {f"variant: {name}" for name in VARIANTS} - {"variant: only fixed"} <= accepted


def test_the_real_robots_are_there_to_convert():
    if not CORPUS.is_dir():
        pytest.skip(f"corpus not found at {CORPUS}")
    converted = [label for label, (losses, results) in verdicts("ros2-p2").items()
                 if results and not label.startswith("variant: ")]
    assert len(converted) >= 10, converted
