"""A document of canonical ROS 1 SimpleTransmissions lets the per-transmission rules return at
once (txtool/lint/rule_helpers.py ``canonical``): the findings must be those the rules make when
they look at every transmission.

Each document is linted twice with every rule: as the linter runs, and with the document-level
answer forced to "not canonical" so that each rule walks its transmissions. The documents are
the corpus files, canonical arms, arms with one detail changed (each detail that the answer
rests on) and arms drawn from those details at random.
"""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from tests.corpus import corpus_file, corpus_names
from txtool.io.xmlio import Source, parse_bytes, read_bytes
from txtool.lint.config import Config, resolve
from txtool.lint.engine import context_for, finish, run_rules
from txtool.lint.problem import Problem
from txtool.lint.rule_helpers import all_canonical

EVERY_RULE = resolve(Config(select=["ALL"]))
SIMPLE = "transmission_interface/SimpleTransmission"
EFFORT = "hardware_interface/EffortJointInterface"


def _findings(source: Source, *, walk_all: bool) -> tuple[bool, list[Problem]]:
    """(whether the document read as canonical, its findings)."""
    ctx = context_for(source, EVERY_RULE)
    if walk_all:
        ctx.memo["canonical"] = False
    canonical = bool(ctx.found) and all_canonical(ctx)
    return canonical, finish(run_rules(ctx, EVERY_RULE), source, EVERY_RULE)


def _compare(data: bytes, path: str = "arm.urdf") -> bool:
    """Assert the two runs agree; whether the document read as canonical."""
    source = Source(path=path, data=data, tree=parse_bytes(data, path))
    canonical, fast = _findings(source, walk_all=False)
    again = Source(path=path, data=data, tree=parse_bytes(data, path))
    _, walked = _findings(again, walk_all=True)
    assert fast == walked
    return canonical


def transmission(
    *, name: str = "t", type_text: str = SIMPLE, type_attribute: str = "", joint: str = "j1",
    interfaces: tuple[str, ...] = (EFFORT,), actuator: str = "m1", reduction: str | None = "50",
    offset: str | None = None, extra: str = "", joint_extra: str = "", actuator_extra: str = "",
) -> str:
    hardware = "".join(f"<hardwareInterface>{text}</hardwareInterface>" for text in interfaces)
    reduction_element = (
        "" if reduction is None else f"<mechanicalReduction>{reduction}</mechanicalReduction>"
    )
    offset_element = "" if offset is None else f"<offset>{offset}</offset>"
    return (
        f'<transmission name="{name}"{type_attribute}><type>{type_text}</type>{extra}'
        f'<joint name="{joint}">{hardware}{offset_element}{joint_extra}</joint>'
        f'<actuator name="{actuator}">{reduction_element}{actuator_extra}</actuator>'
        "</transmission>"
    )


def arm(*transmissions: str, joints: str = "j1 j2") -> bytes:
    body = "".join(
        f'<joint name="{name}" type="revolute"><parent link="a"/><child link="b"/></joint>'
        for name in joints.split()
    )
    return f'<?xml version="1.0"?>\n<robot name="r">{body}\n{"".join(transmissions)}\n</robot>\n'.encode()


def test_a_canonical_arm_is_answered_for_the_whole_document() -> None:
    second = transmission(name="u", joint="j2", actuator="m2", offset=" 0.5 ")
    assert _compare(arm(transmission(), second))


# One detail away from canonical: each must be found by the rules that look at it.
CHANGED = {
    "blank name": {"name": " "},
    "blank joint name": {"joint": ""},
    "blank actuator name": {"actuator": " "},
    "differential": {"type_text": "transmission_interface/DifferentialTransmission"},
    "unknown type": {"type_text": "transmission_interface/SimpleTransmision"},
    "custom type": {"type_text": "my_pkg/Gearbox"},
    "legacy attribute too": {"type_attribute": f' type="{SIMPLE}"'},
    "no interface": {"interfaces": ()},
    "empty interface": {"interfaces": ("",)},
    "unprefixed interface": {"interfaces": ("EffortJointInterface",)},
    "unknown interface": {"interfaces": (EFFORT, "hardware_interface/EffortInterface")},
    "no reduction": {"reduction": None},
    "zero reduction": {"reduction": "0"},
    "subnormal reduction": {"reduction": "1e-310"},
    "hex reduction": {"reduction": "0x10"},
    "reduction with a unit": {"reduction": "50rad"},
    "split reduction": {"reduction": "5<!-- c -->0"},
    "blank reduction": {"reduction": " "},
    "xacro reduction": {"reduction": "${ratio}"},
    "infinite offset": {"offset": "1e999"},
    "split offset": {"offset": "<!-- c -->1"},
    "reduction on the joint": {"joint_extra": "<mechanicalReduction>2</mechanicalReduction>"},
    "offset on the actuator": {"actuator_extra": "<offset>1</offset>"},
    "reduction under the transmission": {"extra": "<mechanicalReduction>2</mechanicalReduction>"},
    "ros2 spelling": {"actuator_extra": "<mechanical_reduction>2</mechanical_reduction>"},
    "ros2 interface spelling": {"joint_extra": "<hardware_interface>x</hardware_interface>"},
    "second joint": {"extra": '<joint name="j2"/>'},
    "second actuator": {"extra": '<actuator name="m2"/>'},
    "role attribute": {"joint_extra": "", "extra": '<joint name="j2" role="joint1"/>'},
}


@pytest.mark.parametrize("change", sorted(CHANGED))
def test_one_changed_detail_is_checked_by_every_rule(change: str) -> None:
    changed = {"name": "u", "joint": "j2", **CHANGED[change]}
    assert not _compare(arm(transmission(), transmission(**changed)))  # type: ignore[arg-type]


# Details that change nothing a rule about one transmission looks at.
UNCHANGED = {
    "padded type": {"type_text": f" {SIMPLE}\n"},
    "interface on the actuator": {
        "actuator_extra": f"<hardwareInterface>{EFFORT}</hardwareInterface>"},
    "two registered interfaces": {
        "interfaces": (EFFORT, "hardware_interface/PositionJointInterface")},
    "padded offset": {"offset": "\t-1e-3 "},
}


@pytest.mark.parametrize("change", sorted(UNCHANGED))
def test_details_no_rule_reads_keep_the_answer(change: str) -> None:
    changed = {"name": "u", "joint": "j2", **UNCHANGED[change]}
    assert _compare(arm(transmission(), transmission(**changed)))  # type: ignore[arg-type]


@pytest.mark.parametrize("wrapper", [
    "<![CDATA[50]]>",  # a CDATA section anywhere: texts are read node by node
])
def test_cdata_in_the_document_turns_the_answer_off(wrapper: str) -> None:
    assert not _compare(arm(transmission(reduction=wrapper), transmission(name="u", joint="j2")))


def test_rules_about_the_whole_document_still_run() -> None:
    """Duplicate names, shared members, unknown joints: canonical transmissions, findings."""
    data = arm(transmission(name="t", joint="j1"), transmission(name="u", joint="j1", actuator="m2"),
               transmission(name="t", joint="j9", actuator="m3"))
    source = Source(path="arm.urdf", data=data, tree=parse_bytes(data, "arm.urdf"))
    canonical, problems = _findings(source, walk_all=False)
    assert canonical
    assert {p.code for p in problems} == {"TX108", "TX109", "TX200"}
    assert _compare(data) is True


NUMBERS = st.sampled_from(["50", " 2.5 ", "0", "-0.0", "1e-310", "1e999", "nan", "0x1p3", "+7",
                           "5 0", "${r}", "", "5<!--c-->", "<!--c-->5", ".5", "5."])
TEXTS = st.sampled_from([EFFORT, "hardware_interface/PositionJointInterface", "EffortJointInterface",
                         "", " ", "hardware_interface/Nope", "$(arg hw)"])


@st.composite
def drawn_transmissions(draw: st.DrawFn, index: int) -> str:
    return transmission(
        name=draw(st.sampled_from([f"t{index}", "", " ", "t0"])),
        type_text=draw(st.sampled_from([SIMPLE, SIMPLE, f"{SIMPLE} ", "",
                                        "transmission_interface/FourBarLinkageTransmission",
                                        "pr2_mechanism_model/SimpleTransmission"])),
        type_attribute=draw(st.sampled_from(["", "", ' type="x"'])),
        joint=draw(st.sampled_from([f"j{index}", "j1", "", "j9"])),
        interfaces=tuple(draw(st.lists(TEXTS, max_size=2))),
        actuator=draw(st.sampled_from([f"m{index}", "m1", ""])),
        reduction=draw(st.one_of(st.none(), NUMBERS)),
        offset=draw(st.one_of(st.none(), NUMBERS)),
        joint_extra=draw(st.sampled_from(["", "", "<mechanicalReduction>2</mechanicalReduction>",
                                          "<hardware_interface>x</hardware_interface>"])),
        actuator_extra=draw(st.sampled_from(["", "", "<offset>1</offset>",
                                             f"<hardwareInterface>{EFFORT}</hardwareInterface>"])),
    )


@settings(max_examples=150, deadline=None)
@given(st.lists(st.integers(1, 3), min_size=1, max_size=3).flatmap(
    lambda indexes: st.tuples(*(drawn_transmissions(i) for i in indexes))))
def test_drawn_arms_give_the_same_findings_either_way(transmissions: tuple[str, ...]) -> None:
    _compare(arm(*transmissions, joints="j1 j2 j3"))


@pytest.mark.parametrize("name", corpus_names())
def test_corpus_files_give_the_same_findings_either_way(name: str) -> None:
    display, data = read_bytes(str(corpus_file(name)))
    _compare(data, display)
