"""roundtrip cycles a transmission that repeats another under other names once, with the one
it repeats, and gives it the same rows with its name: the rows are those of cycling every
transmission in full, for real robots (which repeat their joints' transmissions), for
documents whose copies share names, joints, limits or comments, and for a first that loses
something (its followers are then cycled in full, as a detail names what was lost)."""

from __future__ import annotations

import copy
import json
import random
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from lxml import etree

from tests.corpus import corpus_file
from txtool.io.load import load
from txtool.model.robot import JointsOnDemand, joint_elements
from txtool.transform import roundtrip as module
from txtool.transform.repeats import cycled_document, plan_repeats
from txtool.transform.roundtrip import CycleRow, RoundTripReport, roundtrip
from txtool.views.report_json import roundtrip_json

SIMPLE = (
    '<transmission name="{t}"><type>transmission_interface/SimpleTransmission</type>'
    '<joint name="{j}"><hardwareInterface>hardware_interface/EffortJointInterface'
    '</hardwareInterface></joint><actuator name="{m}"><mechanicalReduction>{n}'
    "</mechanicalReduction></actuator></transmission>"
)
JOINT = ('<joint name="{j}" type="revolute"><parent link="base"/><child link="l_{j}"/>'
         '<limit lower="-1" upper="{upper}" effort="10" velocity="2"/></joint>')
# ros_control reads a differential's members by role; listed against their roles (joint2
# first), a round trip through ros2_control, which binds them by name, changes behaviour.
AGAINST_ROLES = (
    '<transmission name="{t}"><type>transmission_interface/DifferentialTransmission</type>'
    '<actuator name="{m}2"><role>actuator2</role><mechanicalReduction>10</mechanicalReduction>'
    '</actuator><actuator name="{m}1"><role>actuator1</role><mechanicalReduction>20'
    '</mechanicalReduction></actuator>'
    '<joint name="{j}2"><role>joint2</role><hardwareInterface>hardware_interface/'
    'EffortJointInterface</hardwareInterface></joint>'
    '<joint name="{j}1"><role>joint1</role><hardwareInterface>hardware_interface/'
    'EffortJointInterface</hardwareInterface></joint></transmission>'
)


def robot(*parts: str) -> str:
    return '<robot name="r"><link name="base"/>' + "".join(parts) + "</robot>"


def in_full(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(module, "plan_repeats", lambda source, joints: None)


def both(path: Path, monkeypatch: pytest.MonkeyPatch) -> tuple[RoundTripReport, RoundTripReport]:
    """The report with repeats cycled once, and with every transmission cycled in full."""
    short = roundtrip(load(str(path)), consume=True)
    with monkeypatch.context() as patch:
        in_full(patch)
        full = roundtrip(load(str(path)))
    return short, full


def followers(path: Path) -> int:
    source = load(str(path))
    plan = plan_repeats(source, JointsOnDemand(joint_elements(source.root)))
    return 0 if plan is None else len(plan.first_of)


def chain(count: int, transmission: str = SIMPLE, **change: str) -> str:
    joints = [JOINT.format(j=f"j{i}", upper=change.get(f"upper{i}", "1")) for i in range(count)]
    names = [{"t": f"t{i}", "j": f"j{i}", "m": f"m{i}", "n": "50"} for i in range(count)]
    for i, spec in enumerate(names):
        for key in ("t", "j", "m", "n"):
            spec[key] = change.get(f"{key}{i}", spec[key])
    return robot(*joints, *(transmission.format(**spec) for spec in names))


@pytest.mark.parametrize(("text", "expected_followers"), [
    (chain(5), 4),
    (chain(5, m3="m0"), 2),  # t0 and t3 share an actuator: both cycled in full
    (chain(5, j4="j1"), 2),  # t1 and t4 drive one joint
    (chain(5, upper2="2", upper4="-0.0"), 2),  # other limits: other equivalence samples
    (chain(5, n3="50.0", n4="-50"), 2),  # other reductions as written
    (chain(4, m2="actuator1"), 2),  # a name the conversions write themselves
    (chain(4, t3="t0"), 1),  # two transmissions of one name
    (chain(3, j2="missing"), 1),  # a joint the robot does not have
    (chain(4).replace("<actuator name=\"m2\">", "<!-- c --><actuator name=\"m2\">"), 2),
], ids=["alike", "shared-actuator", "shared-joint", "limits", "numbers", "literal-name",
        "same-name", "missing-joint", "comment"])
def test_rows_are_those_of_every_transmission_cycled_in_full(
        text: str, expected_followers: int, tmp_path: Path,
        monkeypatch: pytest.MonkeyPatch) -> None:
    path = tmp_path / "robot.urdf"
    path.write_text(text)
    assert followers(path) == expected_followers
    short, full = both(path, monkeypatch)
    assert short.rows and short.to_json() == full.to_json()


def test_followers_of_a_first_that_loses_something_are_cycled_in_full(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    path = tmp_path / "robot.urdf"
    joints = [JOINT.format(j=f"d{i}{k}", upper="1") for i in range(3) for k in (1, 2)]
    start, end = robot().split("</robot>")[0], "</robot>"
    simple = chain(4).removeprefix(start).removesuffix(end)  # alike: cycled once
    path.write_text(robot(*joints, *(AGAINST_ROLES.format(t=f"d{i}", j=f"d{i}", m=f"n{i}")
                                     for i in range(3)), simple))
    assert followers(path) == 2 + 3
    cycled = []
    cycle = module._report
    monkeypatch.setattr(module, "_report", lambda source, *a, **k: (
        cycled.append(sorted(t.get("name") for t in source.root.iter("transmission")))
        or cycle(source, *a, **k)))
    short, full = both(path, monkeypatch)
    assert short.to_json() == full.to_json() and not short.ok
    assert any(row.transmission == "d2" and row.details for row in short.rows)
    # The first document cycled held one of each; the second the differentials in full.
    assert cycled[:2] == [["d0", "t0"], ["d0", "d1", "d2", "t0"]]


DECLARED = ('<ros2_control name="s" type="system"><hardware><plugin>mock_components/'
            'GenericSystem</plugin></hardware><joint name="{j}"><command_interface name="effort"/>'
            "</joint></ros2_control></robot>")


@pytest.mark.parametrize("text", [
    chain(3).replace("</robot>", DECLARED.format(j="j1")),  # converting t1 moves it in there
    chain(3).replace("</robot>", "<!-- txtool-original eNqzKS --></robot>"),
    chain(3).replace(SIMPLE.format(t="t2", j="j2", m="m2", n="50"),
                     "<gazebo>" + SIMPLE.format(t="t2", j="j2", m="m2", n="50") + "</gazebo>"),
], ids=["declared-in-a-block", "carried-original", "nested"])
def test_a_transmission_whose_conversions_read_more_than_it_is_cycled_in_full(
        text: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    path = tmp_path / "robot.urdf"
    path.write_text(text)
    assert followers(path) == (0 if "txtool-original" in text else 1)  # t0 and t1 or t2
    short, full = both(path, monkeypatch)
    assert short.to_json() == full.to_json()


def converted(text: str, target: str, tmp_path: Path) -> str:
    from txtool.transform.convert import convert_source

    path = tmp_path / "ros1.urdf"
    path.write_text(text)
    return convert_source(load(str(path)), target).data.decode()


def swap_first_declarations(text: str) -> str:
    first = text.index('<joint name="j0">')
    second = text.index('<joint name="j1">')
    end = text.index("</joint>", second) + len("</joint>")
    block_j0, between, block_j1 = text[first:second], "", text[second:end]
    return text[:first] + block_j1 + between + block_j0 + text[end:]


@pytest.mark.parametrize(("target", "change", "expected_followers"), [
    ("ros2-p2", None, 5),
    ("ros2-p1", None, 5),
    ("ros2-p2", swap_first_declarations, 0),  # not as generated: the block is not recognised
    ("ros2-p2", lambda text: text.replace('<ros2_control name="r"', '<ros2_control name="t3"'),
     4),  # a block named like a transmission: t3 is no one's follower
    ("ros2-p2", lambda text: text.replace('<state_interface name="effort"/>\n  </joint>',
                                          '<state_interface name="temperature"/>\n  </joint>',
                                          1), 4),  # j0 declared otherwise: t0 alone
    ("ros2-p2", lambda text: text.replace(
        "</robot>", '<ros2_control name="o" type="system"><joint name="j4"/></ros2_control>'
        "</robot>"), 0),  # j4 declared twice: that block's transmissions are cycled in full
], ids=["p2", "p1", "declarations-reordered", "block-named-like-one", "declared-otherwise",
        "declared-twice"])
def test_transmissions_in_a_ros2_control_block(target, change, expected_followers,
                                               tmp_path: Path,
                                               monkeypatch: pytest.MonkeyPatch) -> None:
    text = converted(chain(6), target, tmp_path)
    path = tmp_path / "robot.urdf"
    path.write_text(change(text) if change else text)
    assert followers(path) == expected_followers
    short, full = both(path, monkeypatch)
    assert short.rows and short.to_json() == full.to_json()


def test_the_document_cycled_holds_one_transmission_of_each_shape(tmp_path: Path) -> None:
    path = tmp_path / "robot.urdf"
    path.write_text(chain(50, n7="3"))
    source = load(str(path))
    plan = plan_repeats(source, JointsOnDemand(joint_elements(source.root)))
    assert plan is not None
    cycled = cycled_document(source, plan)
    assert [t.get("name") for t in cycled.root] == ["t0", "t7"]  # no links, joints, followers


def repeated(root: etree._Element, rng: random.Random) -> etree._Element:
    """``root`` with some of its transmissions repeated under new names, each copy driving a
    copy of the original's joints; now and then a copy keeps one name of the original."""
    root = copy.deepcopy(root)
    joints = {j.get("name"): j for j in root if j.tag == "joint"}
    originals = [t for t in root if t.tag == "transmission"]
    for copy_number, original in enumerate(rng.sample(originals, min(4, len(originals)))):
        new = copy.deepcopy(original)
        renamed: dict[str, str] = {}
        keep = rng.random() < 0.25
        for node in new.iter():
            name = node.get("name") if isinstance(node.tag, str) else None
            if name is not None:
                fresh = name if keep else rng.choice(["z", "a", "_"]) + f"{copy_number}{name}"
                node.set("name", renamed.setdefault(name, fresh))
                keep = False
        for old, fresh in renamed.items():
            if old in joints and old != fresh:
                joint = copy.deepcopy(joints[old])
                joint.set("name", fresh)
                root.insert(rng.randrange(len(root) + 1), joint)
        root.insert(rng.randrange(len(root) + 1), new)
    return root


@pytest.mark.parametrize("name", [
    "universal_robot__ur5e.urdf", "baxter__baxter.urdf", "moveit_resources__pr2_robot.urdf",
    "shadow__shadowhand_motor.urdf", "nao_robot__naoV50.urdf",
    "ros_control__transmission_interface_loader_bidirectional_valid.urdf",
])
def test_real_robots_and_copies_of_their_transmissions(
        name: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    path = corpus_file(name)
    as_written = both(path, monkeypatch)
    assert as_written[0].to_json() == as_written[1].to_json()
    root = load(str(path)).root
    rng = random.Random(name)
    for number in range(2):
        copied = tmp_path / f"copied{number}.urdf"
        copied.write_bytes(etree.tostring(repeated(root, rng)))
        short, full = both(copied, monkeypatch)
        assert short.to_json() == full.to_json()


# -- the JSON text ---------------------------------------------------------------------------

NAMES = st.text(st.characters(exclude_categories=()), max_size=12)  # surrogates too
ROWS = st.builds(
    CycleRow, NAMES, st.sampled_from([("ros1", "ros2-p2", "ros1"),
                                       ("ros2-p1", "ros1", "ros2-p2", "ros2-p1")]),
    st.fixed_dictionaries({"reduction": st.booleans(), "offset": st.booleans()}),
    st.sampled_from(["yes", "no: it \"differs\"", "n/a: lost"]),
    st.lists(NAMES, max_size=2).map(tuple))


@settings(max_examples=200, deadline=None)
@given(path=NAMES, rows=st.lists(ROWS, max_size=6), skipped=st.lists(NAMES, max_size=3))
def test_the_json_text_is_json_dumps_of_the_report(path, rows, skipped) -> None:
    report = RoundTripReport(path, rows, skipped)
    assert roundtrip_json(report) == json.dumps(report.to_json(), indent=2)
