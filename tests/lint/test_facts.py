"""The facts the rules read (txtool/lint/facts.py) say what the reader's model says.

The linter takes each transmission's dialect, type, kind and names from the XML and reads the
model only when a rule asks; these tests hold the two together on every corpus document (as
written) and on the shapes where the dialect or type is
decided by a detail: a role attribute, a ``<plugin>``, an enclosing ``<ros2_control>``, the
legacy ``type=`` attribute, blank and padded texts.
"""

from __future__ import annotations

import gc

import pytest

from tests.corpus import corpus_file, corpus_names
from txtool.dialects.read import read_transmission
from txtool.io.xmlio import Source, parse_bytes, read_bytes
from txtool.lint.config import Config, resolve
from txtool.lint.engine import context_for, lint_source
from txtool.lint.facts import Facts
from txtool.lint.problem import Problem
from txtool.lint.rule_helpers import loader_text, numbers_of

T = "transmission_interface/"
SHAPES = {
    "ros1 simple": f"""<robot name="r"><transmission name="t"><type>{T}SimpleTransmission</type>
        <joint name="j"><hardwareInterface> hardware_interface/EffortJointInterface
        </hardwareInterface><hardwareInterface/></joint>
        <actuator name="m"><mechanicalReduction>5</mechanicalReduction></actuator>
        </transmission></robot>""",
    "legacy attribute": """<robot name="r"><transmission name="t"
        type=" pr2_mechanism_model/SimpleTransmission "><joint name="j"/><actuator name="m"/>
        </transmission></robot>""",
    "attribute beside a blank type": """<robot name="r"><transmission type="SimpleTransmission">
        <type>  </type><joint name=""/></transmission></robot>""",
    "blank type, no attribute": """<robot name="r"><transmission name=" ">
        <type>
        </type><actuator/></transmission></robot>""",
    "role attribute outside ros2_control": f"""<robot name="r"><transmission name="t">
        <type>{T}DifferentialTransmission</type><joint name="a" role="joint1"/>
        <joint name="b"/><actuator name="m"/></transmission></robot>""",
    "plugin outside ros2_control": f"""<robot name="r"><transmission name="t">
        <plugin> {T}FourBarLinkageTransmission </plugin><type>{T}SimpleTransmission</type>
        <joint name="j"><role>joint1</role></joint></transmission></robot>""",
    "inside ros2_control": f"""<robot name="r"><ros2_control name="c" type="system">
        <joint name="j"><command_interface name="effort"/></joint>
        <transmission name="t"><type>{T}SimpleTransmission</type>
        <joint name="j" role="joint1"><mechanical_reduction>2</mechanical_reduction></joint>
        <actuator name="m" role="actuator1"/></transmission></ros2_control></robot>""",
    "namespaced": f"""<r:robot xmlns:r="urn:r" name="r"><r:transmission name="t">
        <r:type>{T}SimpleTransmission</r:type><r:joint name="j"/></r:transmission></r:robot>""",
}


def _check(source: Source) -> int:
    """Compare every transmission's facts with its model; the number compared."""
    ctx = context_for(source, resolve(None))
    for tx in ctx.facts:
        model = read_transmission(tx.element, None)
        assert (tx.ros1, tx.type, tx.kind, tx.name) == (
            model.dialect == "ros1", model.type, model.kind, model.name
        )
        assert [r.name for r in tx.joints] == [m.name for m in model.joints]
        assert [r.name for r in tx.actuators] == [m.name for m in model.actuators]
        assert tx.transmission == model  # the model read on first use is the reader's
        assert [r.member for r in tx.members] == [*model.joints, *model.actuators]
        if tx.ros1:
            assert [tuple(r.interfaces) for r in tx.members] == [
                m.interfaces for m in (*model.joints, *model.actuators)
            ]
    return len(ctx.facts)


@pytest.mark.parametrize("name", sorted(SHAPES))
def test_facts_match_the_model_on_each_shape(name: str) -> None:
    data = SHAPES[name].encode()
    assert _check(Source(path="shape.urdf", data=data, tree=parse_bytes(data, "shape.urdf")))


@pytest.mark.parametrize("name", corpus_names())
def test_facts_match_the_model_on_the_corpus(name: str) -> None:
    display, data = read_bytes(str(corpus_file(name)))
    assert _check(Source(path=display, data=data, tree=parse_bytes(data, display))) >= 0


def test_loader_text_without_cdata_reads_the_text_as_the_nodes_do() -> None:
    """A document with no CDATA section: an element without children has one text node."""
    root = parse_bytes(b"<a><n> 5 </n><n>\n</n><n/><n>5<!-- c -->0</n><n><!-- c -->5</n></a>",
                       "a.urdf").getroot()
    for element in root:
        assert loader_text(element, plain=True) == loader_text(element)


NUMBERS = b"""<robot name="r"><transmission name="t"><type>transmission_interface/SimpleTransmission
  </type><joint name="j"><offset> 0.5 </offset></joint><actuator name="m">
  <mechanicalReduction>${r}</mechanicalReduction></actuator></transmission>
  <transmission name="d"><type>transmission_interface/DifferentialTransmission</type>
  <joint name="a"><mechanicalReduction>
  </mechanicalReduction><offset>1<!-- c -->0</offset></joint><joint name="b"><offset/></joint>
  <actuator name="x"><mechanicalReduction><!-- c -->5</mechanicalReduction></actuator>
  <actuator name="y"><mechanicalReduction>1e999</mechanicalReduction></actuator></transmission>
  </robot>"""


@pytest.mark.parametrize("name", ["numbers", *corpus_names()])
def test_numbers_read_without_cdata_are_those_read_node_by_node(name: str) -> None:
    """Where the document holds no CDATA section, each number's text is read from the element
    directly; the numbers found and read are those of the node-by-node reading."""
    if name == "numbers":
        display, data = "numbers.urdf", NUMBERS
    else:
        display, data = read_bytes(str(corpus_file(name)))
    source = Source(path=display, data=data, tree=parse_bytes(data, display))
    ctx = context_for(source, resolve(None))
    for tx in ctx.facts:
        unsure = Facts(tx.found)  # plain=False: every text node read
        fields = ("element", "field", "noun", "member", "text", "unknown",
                  "unknown_written", "strict")
        assert [[getattr(n, f) for f in fields] for n in numbers_of(tx)] == [
            [getattr(n, f) for f in fields] for n in numbers_of(unsure)
        ]
        if tx.plain:
            assert all(n.single == (not len(n.element)) for n in numbers_of(tx))


@pytest.mark.parametrize("name", sorted(SHAPES))
def test_a_checked_document_is_freed_without_the_garbage_collector(name: str) -> None:
    """Facts and their transmission refer to each other; once the rules are done the linter
    drops the facts, so the document goes as soon as its findings are made (a cycle left
    behind would keep it, tree and all, until the collector's next pass)."""
    data = SHAPES[name].encode()
    settings = resolve(Config(select=["ALL"]))

    def lint() -> list[Problem]:
        return lint_source(Source(path="shape.urdf", data=data,
                                  tree=parse_bytes(data, "shape.urdf")), settings)

    lint()  # anything loaded or cached on first use stays
    gc.collect()
    gc.disable()
    try:
        lint()
        assert gc.collect() == 0
    finally:
        gc.enable()


@pytest.mark.parametrize(("xml", "found", "at_root"), [
    # all at the root: the root's own transmission children, in order
    ('<robot><transmission name="a"/><link name="l"/><transmission name="b"/></robot>',
     ["a", "b"], ["a", "b"]),
    # one in a macro: found, but not a child of the root
    ('<robot xmlns:xacro="x"><transmission name="a"/><xacro:macro name="m">'
     '<transmission name="b"/></xacro:macro></robot>', ["a", "b"], ["a"]),
    # one inside another: not a transmission of its own
    ('<robot><transmission name="a"><transmission name="n"/></transmission></robot>',
     ["a"], ["a"]),
    # a bare fragment: the root itself, which is no child of itself
    ('<transmission name="a"><transmission name="n"/></transmission>', ["a"], []),
    # a comment that holds one, a prefixed tag, a longer name, and none at the root
    ('<robot><transmission name="a"/><!-- <transmission name="c"/> -->'
     '<transmission name="b"/></robot>', ["a", "b"], ["a", "b"]),
    ('<robot xmlns:p="u"><transmission name="a"/><p:macro><p:transmission name="b"/>'
     '</p:macro></robot>', ["a", "b"], ["a"]),
    ('<robot><transmissions/><transmission name="a"/></robot>', ["a"], ["a"]),
    ('<robot><m><transmission name="a"/></m></robot>', ["a"], []),
    # several under one parent: inside a transmission (none of them), or not (each)
    ('<robot><transmission name="a"><m><transmission name="n"/><transmission name="o"/></m>'
     '</transmission><m><transmission name="b"/><transmission name="c"/></m></robot>',
     ["a", "b", "c"], ["a"]),
    ('<robot><ros2_control name="x"><transmission name="a"/><transmission name="b"/>'
     '</ros2_control></robot>', ["a", "b"], []),
])
@pytest.mark.parametrize("encoding", ["utf-8", "utf-16"])
def test_transmissions_found_and_those_at_the_root(xml, found, at_root, encoding):
    """The transmissions of a document, in order (not one nested in another), and which of
    them stand at its root."""
    from txtool.dialects.read import transmission_elements

    root = parse_bytes(xml.encode(encoding), "r.urdf").getroot()
    elements = transmission_elements(root)
    assert [e.get("name") for e in elements] == found
    assert [e.get("name") for e in elements if e.getparent() is root] == at_root
