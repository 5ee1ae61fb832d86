"""migrate skips its fixes (and reads a conversion straight through) only where no fix could
find anything: the cheap tests say yes wherever a fix finds something."""

from __future__ import annotations

import copy
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from lxml import etree

from tests.corpus import corpus_file, corpus_names
from tests.hardening.fuzz_inputs import FuzzDocument, documents
from txtool.io.xmlio import InputError, parse_bytes
from txtool.lint.fixes import fix_tree, might_fix
from txtool.rules import Rule, all_rules
from txtool.transform.migrate import MigrateOptions, migrate_file

ROOT = Path(__file__).resolve().parents[2]
FIXTURES = ROOT / "fixtures"
FIXABLE = [rule for rule in all_rules().values() if rule.fixable]


def rules(*codes: str) -> list[Rule]:
    return [rule for rule in FIXABLE if rule.code in codes]


def root(text: str) -> etree._Element:
    return etree.fromstring(text.encode())


UNPREFIXED = """<robot><transmission name="t"><type>transmission_interface/SimpleTransmission</type>
  <joint name="j"><hardwareInterface>EffortJointInterface</hardwareInterface></joint>
  <actuator name="m"/></transmission></robot>"""
ON_ACTUATOR = """<robot><transmission name="t"><type>transmission_interface/SimpleTransmission</type>
  <joint name="j"/>
  <actuator name="m"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
  </actuator></transmission></robot>"""
TYPE_ATTRIBUTE = """<robot><transmission name="t" type="SimpleTransmission">
  <joint name="j"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
  </joint><actuator name="m"/></transmission></robot>"""
CLEAN = """<robot><transmission name="t"><type>transmission_interface/SimpleTransmission</type>
  <joint name="j"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
  </joint>
  <actuator name="m"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
  </actuator></transmission><joint name="j" type="continuous"/></robot>"""


@pytest.mark.parametrize(("text", "code"), [
    (UNPREFIXED, "TX300"), (ON_ACTUATOR, "TX301"), (TYPE_ATTRIBUTE, "TX302"),
])
def test_each_test_finds_what_its_fix_fixes_and_only_that(text: str, code: str) -> None:
    assert fix_tree(etree.ElementTree(root(text)), rules(code), text.encode()) == {code: 1}
    for rule in FIXABLE:
        assert might_fix(root(text), [rule]) == (rule.code == code)


def test_a_clean_document_needs_no_fix_and_an_unknown_rule_is_always_run() -> None:
    assert not might_fix(root(CLEAN), FIXABLE)
    assert not might_fix(root(CLEAN), [])
    unknown = FIXABLE[0]._replace(code="TX399")
    assert might_fix(root(CLEAN), [unknown])


def sample_paths() -> list[Path]:
    return sorted(p for p in FIXTURES.iterdir() if p.is_file())


def check_sound(data: bytes) -> None:
    """Where the tests say no, the fixes find nothing (and leave the tree alone)."""
    try:
        tree = parse_bytes(data, "doc")
    except InputError:
        return
    for selected in ([rule] for rule in FIXABLE):
        if might_fix(tree.getroot(), selected):
            continue
        before = etree.tostring(tree)
        fixed = copy.deepcopy(tree)
        assert fix_tree(fixed, selected, data) == {}, selected[0].code
        assert etree.tostring(fixed) == before


@pytest.mark.parametrize("name", corpus_names())
def test_no_fix_is_skipped_on_a_corpus_file(name: str) -> None:
    check_sound(corpus_file(name).read_bytes())


@pytest.mark.parametrize("path", sample_paths(), ids=lambda p: p.name)
def test_no_fix_is_skipped_on_a_fixture(path: Path) -> None:
    check_sound(path.read_bytes())


@settings(max_examples=150, deadline=None, suppress_health_check=list(HealthCheck))
@given(documents())
def test_no_fix_is_skipped_on_mutated_documents(document: FuzzDocument) -> None:
    check_sound(document.data)


def test_a_clean_document_is_not_rewritten(tmp_path: Path) -> None:
    path = tmp_path / "robot.urdf"
    path.write_bytes(CLEAN.replace("<robot>", "<robot>\n<!-- kept -->   ").encode())
    result = migrate_file(str(path), FIXABLE, MigrateOptions(mode="check"))
    assert result.data == result.original and not result.changed and not result.losses
    assert result.fixes == {}


@pytest.mark.parametrize(("text", "code"), [
    ("<r><transmission><joint name='j'><hardwareInterface>\u2003Effort<![CDATA[JointInterface]]>"
     "<x/></hardwareInterface></joint></transmission></r>", "TX300"),
    ("<r xmlns:n='urn:n'><n:transmission><joint name='j'><hardwareInterface> <!-- none -->"
     "</hardwareInterface></joint><n:actuator name='m'><n:hardwareInterface>"
     "<![CDATA[hardware_interface/EffortJointInterface]]></n:hardwareInterface></n:actuator>"
     "</n:transmission></r>", "TX301"),
    ("<r><n:transmission xmlns:n='urn:n' type='SimpleTransmission'><joint name='j'/>"
     "<actuator name='m'/></n:transmission></r>", "TX302"),
])
def test_text_split_by_cdata_children_or_namespaces_is_read_as_the_fixes_read_it(
        text: str, code: str) -> None:
    tree = etree.ElementTree(root(text))
    assert might_fix(tree.getroot(), rules(code))
    assert fix_tree(tree, rules(code), text.encode()) == {code: 1}
