"""ROS 1 robots converted to ROS 2, handed to ros2_control's own parser and loaders.

Every ROS 1 robot of ``fixtures/``, ``../shared/corpus`` and ``../shared/workspace`` (xacro
expanded), and generated variants (mimic, fixed, missing and duplicated joints, an existing
``<ros2_control>`` block, a macro called several times, coupled transmissions, offsets,
negative, huge and unreadable reductions, every hardware interface), is converted to
``ros2-p2`` and ``ros2-p1`` with the library's :func:`txtool.convert` (the command exits 1
exactly when it returns losses) and handed to ``parser17`` (Humble) and ``parser20`` (Jazzy
and later) in one call per build. Either

* the parser accepts the file, and each transmission ros_control loads from the original is
  built with the same reductions and offsets, bit for bit, bound to the same joints and
  actuators, and its joints get the command interfaces ros_control gives them; or
* the conversion has a loss naming the parser's reason (its rule code, and the joint the
  parser names).

What ros_control builds from the original is read here from its loaders' rules
(``../shared/reference/ros-control-transmissions.md``: ros-controls/ros_control
transmission_interface/src/simple_transmission_loader.cpp, differential_transmission_loader.cpp,
four_bar_linkage_transmission_loader.cpp, transmission_interface_loader.cpp and
ros_control_plugins.xml), its numbers by ``std::stod`` itself (the ``stod`` oracle).

``ros2-p1`` is Proposal 1, which ros2_control never adopted: the parser refuses every
``<role>`` element, and the conversion says so in one note. The P1 output is held to the rest
through its twin with each ``<role>`` element written as the attribute ros2_control reads.
"""

from __future__ import annotations

import re
import tempfile
from dataclasses import dataclass, field
from pathlib import Path

import pytest
from lxml import etree

import txtool
from tests.corpus import CORPUS, WORKSPACE
from tests.oracle.reference import oracle_dir, run_lines, run_parser
from txtool.io.load import load
from txtool.io.xmlio import InputError, XacroOptions, parse_bytes

FIXTURES = Path(__file__).resolve().parents[2] / "fixtures"
STANDARD = {
    "transmission_interface/SimpleTransmission": "simple",
    "transmission_interface/DifferentialTransmission": "coupled",
    "transmission_interface/FourBarLinkageTransmission": "coupled",
}
# ros_control_plugins.xml: the interfaces ros_control's loader knows (prefixed only), and the
# command interface each gives the joint (JointStateInterface: none).
KNOWN = {"JointStateInterface": None, "PositionJointInterface": "position",
         "VelocityJointInterface": "velocity", "EffortJointInterface": "effort",
         "BiDirectionalPositionJointInterface": "position",
         "BiDirectionalVelocityJointInterface": "velocity",
         "BiDirectionalEffortJointInterface": "effort"}
# The parser's words, and the rule whose finding names them.
REASONS = (
    (re.compile(r"Activated mimic joints cannot have command interfaces"), {"TX206"}),
    (re.compile(r"[Ff]ixed joint"), {"TX201"}),
    (re.compile(r"not found in URDF|does not exist in the URDF|[Jj]oint .* not .*URDF"),
     {"TX200"}),
    (re.compile(r"no attribute 'role'"), {"TX107", "TX303"}),
    (re.compile(r"Missing <plugin> tag"), {"TX101"}),
    (re.compile(r"There should be exactly one joint"), {"TX103"}),
)


# -- the robots ---------------------------------------------------------------------------------


def _is_ros1_robot(root: etree._Element) -> bool:
    if not isinstance(root.tag, str) or etree.QName(root).localname != "robot":
        return False
    tops = [c for c in root if isinstance(c.tag, str) and etree.QName(c).localname
            == "transmission"]
    return any(c.find("type") is not None for c in tops)


def _expanded(path: Path, packages: tuple[tuple[str, str], ...] = ()) -> bytes | None:
    try:
        source = load(str(path), xacro=XacroOptions(pkg_paths=packages), expand=True)
    except InputError:
        return None
    if not _is_ros1_robot(source.root):
        return None
    return etree.tostring(source.tree, xml_declaration=True, encoding="utf-8")


def real_robots() -> dict[str, bytes]:
    """The ROS 1 robots of the fixtures, the corpus and the workspace, expanded."""
    found: dict[str, bytes] = {}
    names = [*sorted(FIXTURES.glob("*.urdf")), *sorted((FIXTURES / "examples").glob("*.urdf"))]
    if CORPUS.is_dir():
        names += sorted(p for p in CORPUS.iterdir() if p.suffix in (".urdf", ".xacro", ".xml"))
    for path in names:
        data = _expanded(path)
        if data is not None:
            found[path.name] = data
    package = WORKSPACE / "src" / "rrbot_description"
    for path in sorted((package / "urdf").glob("rrbot.*")) if package.is_dir() else ():
        data = _expanded(path, (("rrbot_description", str(package)),))
        if data is not None:
            found[f"workspace/{path.name}"] = data
    return found


def _joint(name: str, kind: str = "revolute", extra: str = "", index: int = 0) -> str:
    limit = '<limit effort="1" velocity="1" lower="-1" upper="1"/>' if kind != "fixed" else ""
    return (f'<link name="l_{name}"/><joint name="{name}" type="{kind}"><parent link="base"/>'
            f'<child link="l_{name}"/><axis xyz="0 0 1"/>{limit}{extra}</joint>')


def _simple(name: str, joint: str, reduction: str = "50", interface: str =
            "hardware_interface/EffortJointInterface", offset: str | None = None) -> str:
    at = f"<offset>{offset}</offset>" if offset is not None else ""
    return (f'<transmission name="{name}"><type>transmission_interface/SimpleTransmission</type>'
            f'<joint name="{joint}"><hardwareInterface>{interface}</hardwareInterface>{at}'
            f'</joint><actuator name="{name}_m"><mechanicalReduction>{reduction}'
            '</mechanicalReduction></actuator></transmission>')


def _coupled(name: str, kind: str, joints: tuple[str, str], reductions: tuple[str, str],
             joint_reductions: tuple[str, str] = ("1", "1"), offsets: tuple[str, str] =
             ("0", "0"), interface: str = "hardware_interface/EffortJointInterface") -> str:
    body = "".join(
        f'<joint name="{j}"><role>joint{i + 1}</role><hardwareInterface>{interface}'
        f'</hardwareInterface><mechanicalReduction>{jr}</mechanicalReduction>'
        f'<offset>{o}</offset></joint>'
        for i, (j, jr, o) in enumerate(zip(joints, joint_reductions, offsets, strict=True)))
    body += "".join(
        f'<actuator name="{name}_m{i}"><role>actuator{i + 1}</role>'
        f'<mechanicalReduction>{r}</mechanicalReduction></actuator>'
        for i, r in enumerate(reductions))
    return (f'<transmission name="{name}"><type>transmission_interface/{kind}</type>{body}'
            '</transmission>')


def _robot(joints: str, rest: str) -> str:
    return f'<?xml version="1.0"?>\n<robot name="v"><link name="base"/>{joints}\n{rest}\n</robot>\n'


def variants() -> dict[str, str]:
    """Generated ROS 1 robots (text), each probing one way a conversion can be refused."""
    two = _joint("j1") + _joint("j2")
    out = {
        "mimic": _robot(_joint("j1") + _joint("j2", extra='<mimic joint="j1"/>'),
                        _simple("t1", "j1") + _simple("t2", "j2")),
        "fixed": _robot(_joint("j1") + _joint("jf", "fixed"),
                        _simple("t1", "j1") + _simple("tf", "jf")),
        "missing": _robot(_joint("j1"), _simple("t1", "j1") + _simple("tm", "nowhere")),
        "duplicated": _robot(_joint("j1"), _simple("t1", "j1") + _simple("t2", "j1")),
        "existing-same-joint": _robot(two, _simple("t1", "j1") + (
            '<ros2_control name="Hw" type="system"><hardware><plugin>mock_components/'
            'GenericSystem</plugin></hardware><joint name="j1"><command_interface name='
            '"effort"/><state_interface name="position"/></joint></ros2_control>')),
        "existing-other-joint": _robot(two, _simple("t1", "j1") + (
            '<ros2_control name="Hw" type="system"><hardware><plugin>mock_components/'
            'GenericSystem</plugin></hardware><joint name="j2"><command_interface name='
            '"effort"/><state_interface name="position"/></joint></ros2_control>')),
        "differential": _robot(two, _coupled("d", "DifferentialTransmission", ("j1", "j2"),
                                             ("30", "-40"), ("2", "0.5"), ("0.25", "-1e-3"))),
        "four-bar": _robot(two, _coupled("f", "FourBarLinkageTransmission", ("j1", "j2"),
                                         ("100", "1e3"), ("-3", "7.5"), (".5", "0"))),
        "coupled-roles-reversed": _robot(two, _coupled("d", "DifferentialTransmission",
                                                       ("j2", "j1"), ("10", "20"))),
        "coupled-unknown-joint": _robot(_joint("j1"), _coupled(
            "d", "DifferentialTransmission", ("j1", "gone"), ("10", "20"))),
        "simple-on-two-joints-coupled-fixed": _robot(_joint("j1") + _joint("jf", "fixed"),
                                                     _coupled("d", "DifferentialTransmission",
                                                              ("j1", "jf"), ("10", "20"))),
    }
    for number in ("-50", "1e308", "1.7976931348623157e308", "4.9e-324", "1e-310", "1e-400",
                   "1e400", "0.1", "50abc", " 7 ", "0x10", "inf", "nan", "fifty", "0", ""):
        out[f"reduction {number!r}"] = _robot(_joint("j1"), _simple("t", "j1", number))
    for number in ("0.1", "-2.5e-3", ".5", "1e-400", "x"):
        out[f"offset {number!r}"] = _robot(_joint("j1"), _simple("t", "j1", offset=number))
    for interface in (*(f"hardware_interface/{name}" for name in KNOWN), "EffortJointInterface",
                      "hardware_interface/PosVelJointInterface",
                      "hardware_interface/PosVelAccJointInterface",
                      "hardware_interface/ImuSensorInterface"):
        out[f"interface {interface}"] = _robot(_joint("j1"),
                                               _simple("t", "j1", interface=interface))
    out["every interface on one robot"] = _robot(
        "".join(_joint(f"j{i}") for i in range(len(KNOWN))),
        "".join(_simple(f"t{i}", f"j{i}", interface=f"hardware_interface/{name}")
                for i, name in enumerate(KNOWN)))
    return out


MACRO = """<?xml version="1.0"?>
<robot name="m" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="arm" params="prefix">
    <link name="${prefix}l"/>
    <joint name="${prefix}j" type="revolute"><parent link="base"/><child link="${prefix}l"/>
      <limit effort="1" velocity="1" lower="-1" upper="1"/></joint>
    <transmission name="${prefix}t">
      <type>transmission_interface/SimpleTransmission</type>
      <joint name="${prefix}j"><hardwareInterface>hardware_interface/PositionJointInterface</hardwareInterface></joint>
      <actuator name="${prefix}m"><mechanicalReduction>-12.5</mechanicalReduction></actuator>
    </transmission>
  </xacro:macro>
  <link name="base"/>
  <xacro:arm prefix="a_"/><xacro:arm prefix="b_"/><xacro:arm prefix="c_"/>
</robot>
"""


# -- what ros_control builds from the original --------------------------------------------------


@dataclass
class Built:
    """A transmission as ros_control loads it: per joint and actuator name its numbers, and
    per joint the command interfaces; ``refused`` why it does not load."""

    joints: dict[str, tuple[float, float]] = field(default_factory=dict)  # reduction, offset
    actuators: dict[str, float] = field(default_factory=dict)
    commands: dict[str, set[str]] = field(default_factory=dict)
    refused: str = ""


def _text(element: etree._Element | None) -> str | None:
    return None if element is None else (element.text or "")


def ros_control_builds(data: bytes) -> dict[str, Built]:
    """Each top-level transmission of a ROS 1 robot as ros_control's loaders build it."""
    root = parse_bytes(data, "original.urdf")
    wanted: list[str] = []
    plans = []
    for element in root.getroot().findall("transmission"):
        plans.append((element, len(wanted)))
        for member in (*element.findall("joint"), *element.findall("actuator")):
            wanted += [_text(member.find("mechanicalReduction")) or "",
                       _text(member.find("offset")) or ""]
    values = _stod(wanted)
    built = {e.get("name", ""): _built(e, values, at) for e, at in plans}
    # A robot's hardware has a handle only for the joints it simulates or drives: none for a
    # joint the URDF lacks, nor for a fixed one (gazebo_ros_control's DefaultRobotHWSim::initSim
    # skips a transmission whose joint is "not in the gazebo model", where fixed joints are
    # merged away), so ros_control binds no transmission on them.
    types = {j.get("name", ""): j.get("type") for j in root.getroot().findall("joint")}
    for (element, _), each in zip(plans, built.values(), strict=True):
        names = [j.get("name", "") for j in element.findall("joint")]
        if not each.refused and any(types.get(n, "fixed") == "fixed" for n in names):
            each.refused = "unbound joint"
    return built


def _stod(texts: list[str]) -> list[float | None]:
    if not texts:
        return []
    lines = run_lines("stod", [t.encode("utf-8").hex() for t in texts])
    return [float.fromhex(line.split()[1]) if line.startswith("OK") and "nan" not in line
            else (float("nan") if line.startswith("OK") else None) for line in lines]


def _built(element: etree._Element, values: list[float | None], at: int) -> Built:
    built = Built()
    kind = STANDARD.get((_text(element.find("type")) or "").strip())
    joints, actuators = element.findall("joint"), element.findall("actuator")
    if kind is None:
        built.refused = "type"
        return built
    wanted = 1 if kind == "simple" else 2
    if len(joints) != wanted or len(actuators) != wanted:
        built.refused = "counts"
        return built
    number = {id(m): (values[at + 2 * i], values[at + 2 * i + 1], m)
              for i, m in enumerate((*joints, *actuators))}
    for joint in joints:
        reduction, offset, member = number[id(joint)]
        has_reduction = member.find("mechanicalReduction") is not None
        has_offset = member.find("offset") is not None
        if (kind == "coupled" and has_reduction and reduction is None) or (
                has_offset and offset is None):
            built.refused = "joint number"
        built.joints[joint.get("name", "")] = (
            reduction if kind == "coupled" and has_reduction else 1.0,
            offset if has_offset else 0.0)
        built.commands[joint.get("name", "")] = _commands(joint)
    for actuator in actuators:
        reduction, _, member = number[id(actuator)]
        if reduction is None:  # required; std::stod threw (or no element)
            built.refused = "actuator reduction"
        built.actuators[actuator.get("name", "")] = reduction or 0.0
    # The transmission's constructor throws on a zero reduction ("Transmission reduction
    # ratios cannot be zero"; simple_transmission.h, differential_transmission.h,
    # four_bar_linkage_transmission.h)
    reductions = [*built.actuators.values()] + (
        [r for r, _ in built.joints.values()] if kind == "coupled" else [])
    if any(r == 0.0 for r in reductions):
        built.refused = "zero reduction"
    if kind == "coupled" and not _roles_valid(joints, actuators):
        built.refused = "roles"
    if any(not c and not _states(j) for c, j in zip(built.commands.values(), joints,
                                                     strict=True)):
        built.refused = "interfaces"
    if len({frozenset(_interfaces(j)) for j in joints}) > 1:
        built.refused = "different interfaces"
    if kind == "simple":  # the actuator's reduction is the transmission's (joint ignored)
        name = joints[0].get("name", "")
        built.joints[name] = (next(iter(built.actuators.values())), built.joints[name][1])
    return built


def _interfaces(joint: etree._Element) -> list[str]:
    return [(e.text or "").strip() for e in joint.findall("hardwareInterface")]


def _known(joint: etree._Element) -> list[str]:
    return [name.removeprefix("hardware_interface/") for name in _interfaces(joint)
            if name.startswith("hardware_interface/")
            and name.removeprefix("hardware_interface/") in KNOWN]


def _commands(joint: etree._Element) -> set[str]:
    return {KNOWN[name] for name in _known(joint) if KNOWN[name]}  # type: ignore[misc]


def _states(joint: etree._Element) -> bool:
    return bool(_known(joint))


def _roles_valid(joints: list[etree._Element], actuators: list[etree._Element]) -> bool:
    roles = [(_text(m.find("role")) or "") for m in joints]
    moles = [(_text(m.find("role")) or "") for m in actuators]
    return sorted(roles) == ["joint1", "joint2"] and sorted(moles) == ["actuator1", "actuator2"]


# -- the comparison -----------------------------------------------------------------------------


def as_read_by_ros2_control(p1: bytes) -> bytes:
    """A ros2-p1 document with each ``<role>`` element written as the ``role`` attribute."""
    tree = parse_bytes(p1, "p1.urdf")
    for role in list(tree.getroot().iter("role")):
        member = role.getparent()
        if member is not None and member.get("role") is None:
            member.set("role", (role.text or "").strip())
            member.remove(role)
    return etree.tostring(tree, xml_declaration=True, encoding="utf-8")


def _mimics(data: bytes) -> set[str]:
    root = parse_bytes(data, "original.urdf").getroot()
    return {j.get("name", "") for j in root.findall("joint") if j.find("mimic") is not None}


def verdict(name: str, original: bytes, said: tuple[list[str], list[str]], result: dict,
            built: dict[str, Built], before: dict) -> list[str]:
    """What is wrong with one conversion (its losses and notes) as ``result`` (the parser's)
    reads it, or nothing; ``before``: the parser's result for the original. A refusal the
    original had already (a ``<ros2_control>`` it brought) is the input's: the conversion says
    it without failing."""
    losses, notes = said
    if not result["accepted"]:
        if losses and _named(result["error"], losses):
            return []
        if not losses and before.get("error") == result["error"] and _named(
                result["error"], [n for n in notes if n.endswith("(the input has it already)")]):
            return []
        return [f"{name}: refused by the parser ({result['error']!r}) but "
                + (f"no loss names it: {losses}" if losses else "txtool exits 0")]
    if losses:
        return []
    wrong = []
    mimic = _mimics(original)
    seen = {t["name"]: t for hw in result["hardware"] for t in hw["transmissions"]}
    for tname, want in built.items():
        got = seen.get(tname)
        if want.refused == "unbound joint":  # not carried: the conversion says why
            if got is not None or not _named_unbound(tname, original, notes):
                wrong.append(f"{name}: {tname}: on a fixed or missing joint, carried or unsaid")
            continue
        if want.refused:
            continue  # ros_control does not load it: nothing to be equal to
        if got is None or not got.get("loader", {}).get("configured"):
            wrong.append(f"{name}: {tname}: ros_control loads it, ros2_control does not")
            continue
        wrong += _compare(f"{name}: {tname}", got, want, mimic)
    return wrong


def _named_unbound(transmission: str, original: bytes, notes: list[str]) -> bool:
    """Whether a note names the transmission with the parser's words for its joint."""
    words = ("Fixed joints do not make sense in ros2_control", "not found in URDF")
    return any(transmission in note and any(w in note for w in words) for note in notes)


def _compare(where: str, got: dict, want: Built, mimic: set[str]) -> list[str]:
    loader = got["loader"]
    joints = dict(zip(loader["joint_order"], zip(loader["joint_reduction"],
                                                  loader["joint_offset"], strict=True),
                      strict=True))
    wrong = []
    for joint, (reduction, offset) in want.joints.items():
        have = joints.get(joint)
        expect = (float.hex(reduction), float.hex(offset))
        if have is None or tuple(float.hex(float.fromhex(v)) for v in have) != expect:
            wrong.append(f"{where}: joint {joint}: ros_control {expect}, ros2_control {have}")
    if loader["actuator_reduction"]:
        actuators = dict(zip(loader["actuator_order"], loader["actuator_reduction"],
                             strict=True))
        for actuator, reduction in want.actuators.items():
            have = actuators.get(actuator)
            if have is None or float.fromhex(have).hex() != float.hex(reduction):
                wrong.append(f"{where}: actuator {actuator}: ros_control {reduction.hex()}, "
                             f"ros2_control {have}")
    commands = {m["name"]: set(m["command_interfaces"]) for m in got["joints"]}
    for joint, expect in want.commands.items():
        have = commands.get(joint, set())
        if have != expect and not (joint in mimic and not have):
            wrong.append(f"{where}: joint {joint}: ros_control commands {sorted(expect)}, "
                         f"ros2_control {sorted(have)}")
    return wrong


def _named(error: str, losses: list[str]) -> bool:
    """Whether a loss quotes the parser's words, or carries the rule for its reason and the
    joint it names."""
    if any(error in loss for loss in losses):
        return True
    codes = next((codes for pattern, codes in REASONS if pattern.search(error)), None)
    if codes is None:
        return False
    quoted = re.findall(r"'([^']+)'", error)
    return any(any(f": {code} " in loss for code in codes)
               and all(f"'{q}'" in loss for q in quoted[:1]) for loss in losses)


def _convert(text: str, target: str) -> tuple[bytes, list[str], list[str]]:
    done = txtool.convert(text, to=target)  # type: ignore[arg-type]
    return done.data, done.losses, done.notes


def _macro_robot() -> bytes:
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "arms.urdf.xacro"
        path.write_text(MACRO)
        data = _expanded(path)
    assert data is not None
    return data


def _all_inputs() -> dict[str, bytes]:
    inputs = {name: text.encode("utf-8") for name, text in variants().items()}
    inputs["macro called three times"] = _macro_robot()
    inputs.update(real_robots())
    return inputs


PROBE = (b'<ros2_control name="probe" type="system"><hardware><plugin>probe/Probe</plugin>'
         b'</hardware></ros2_control></robot>')


def urdf_robots(found: dict[str, bytes]) -> dict[str, bytes]:
    """Those of ``found`` that urdfdom reads as a robot: the parser, given each with a
    ``<ros2_control>`` block of no joint, does not throw "Failed to parse URDF file" (as it
    does for ros_control's transmission-only test robots, whatever their transmissions)."""
    names = list(found)
    probes = [found[name][:found[name].rindex(b"</robot>")] + PROBE for name in names]
    results = run_parser("parser20", probes)
    return {name: found[name] for name, result in zip(names, results, strict=True)
            if result.get("error") != "Failed to parse URDF file"}


@pytest.fixture(scope="module")
def inputs() -> dict[str, bytes]:
    oracle_dir()
    return urdf_robots(_all_inputs())


def test_the_robots_are_many(inputs: dict[str, bytes]) -> None:
    """The corpus and the workspace give robots (skipped without them), the variants more."""
    assert len(inputs) >= len(variants())
    if CORPUS.is_dir():
        assert sum(1 for name in inputs if name.endswith((".urdf", ".xacro", ".xml"))) >= 8


@pytest.mark.parametrize("target", ["ros2-p2", "ros2-p1"])
def test_converted_robots_are_accepted_or_refused_with_the_parsers_reason(
        inputs: dict[str, bytes], target: str) -> None:
    names = list(inputs)
    built = {name: ros_control_builds(inputs[name]) for name in names}
    converted = {name: _convert(inputs[name].decode("utf-8"), target) for name in names}
    documents = [converted[name][0] for name in names]
    if target == "ros2-p1":
        raw = run_parser("parser20", documents)
        for name, result in zip(names, raw, strict=True):
            if "<role>" in converted[name][0].decode("utf-8") and not converted[name][1]:
                assert not result["accepted"] and "no attribute 'role'" in result["error"]
                assert any("no attribute 'role'" in note for note in converted[name][2]), name
        documents = [as_read_by_ros2_control(data) for data in documents]
    wrong = []
    for program in ("parser17", "parser20"):
        results = run_parser(program, documents)
        originals = run_parser(program, [inputs[name] for name in names])
        for name, result, before in zip(names, results, originals, strict=True):
            wrong += [f"{program}: {w}" for w in verdict(
                name, inputs[name], converted[name][1:], result, built[name], before)]
    assert not wrong, "\n".join(wrong)


def test_both_outcomes_occur(inputs: dict[str, bytes]) -> None:
    """The variants reach both sides: files the parsers accept, and conversions refused."""
    outcomes = {bool(_convert(inputs[name].decode("utf-8"), "ros2-p2")[1])
                for name in ("mimic", "fixed", "differential", "coupled-roles-reversed")}
    assert outcomes == {True, False}
