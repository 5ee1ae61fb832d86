"""migrate skips its fixes (and reads a conversion straight through) only where no fix could
find anything: the cheap tests say yes wherever a fix finds something."""

from __future__ import annotations

import contextlib
import copy
import tempfile
from collections import Counter
from pathlib import Path
from unittest import mock

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from lxml import etree

from tests.corpus import corpus_file, corpus_names
from tests.hardening.fuzz_inputs import FuzzDocument, documents
from txtool.io.xmlio import InputError, parse_bytes
from txtool.rules import Rule, all_rules
from txtool.transform import migrate
from txtool.transform.fixable import might_fix, might_fix_text, settled_text
from txtool.transform.migrate import MigrateOptions, fix_tree, migrate_file

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


@pytest.mark.parametrize("options", [
    MigrateOptions(mode="diff"), MigrateOptions(mode="diff", target="ros1"),
    MigrateOptions(mode="diff", target="ros2-p2"),
    MigrateOptions(mode="diff", target="ros2-p1", reversible=True),
], ids=["fixes", "ros1", "ros2-p2", "ros2-p1-reversible"])
@pytest.mark.parametrize("name", corpus_names())
def test_a_migration_gives_what_the_steps_give(name: str, options: MigrateOptions,
                                               monkeypatch: pytest.MonkeyPatch) -> None:
    """Fix, convert, parse, fix again, each stage as edits: what migrate does where it does
    not leave out the fixes that find nothing, nor read what the conversion wrote by its
    bytes alone."""
    path = str(corpus_file(name))
    try:
        result = migrate_file(path, FIXABLE, options)
    except InputError as error:
        result = error
    monkeypatch.setattr(migrate, "might_fix", lambda root, rules, data=None: True)
    monkeypatch.setattr(migrate, "might_fix_converted", lambda data, rules, target: True)
    try:
        steps = migrate_file(path, FIXABLE, options)
    except InputError as error:
        assert str(result) == str(error)
        return
    assert isinstance(result, migrate.FileResult)
    assert vars(result) == vars(steps)


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


def check_bytes_agree(data: bytes) -> None:
    """The bytes settle a rule only where the tree test says no: asking them first changes no
    answer."""
    try:
        tree = parse_bytes(data, "doc")
    except InputError:
        return
    for rule in FIXABLE:
        assert might_fix(tree.getroot(), [rule], data) == might_fix(tree.getroot(), [rule]), \
            rule.code


@pytest.mark.parametrize("name", corpus_names())
def test_the_bytes_agree_with_the_tree_on_a_corpus_file(name: str) -> None:
    check_bytes_agree(corpus_file(name).read_bytes())


@settings(max_examples=150, deadline=None, suppress_health_check=list(HealthCheck))
@given(documents())
def test_the_bytes_agree_with_the_tree_on_mutated_documents(document: FuzzDocument) -> None:
    check_bytes_agree(document.data)


JOINT_FIRST = CLEAN.replace("""
  <actuator name="m"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
  </actuator>""", '<actuator name="m"/>')


@pytest.mark.parametrize(("text", "settled"), [
    (JOINT_FIRST, {"TX300", "TX301", "TX302"}),
    (CLEAN, {"TX302"}),  # an actuator's interface: read in the tree
    (UNPREFIXED, {"TX302"}),
    (TYPE_ATTRIBUTE, {"TX300", "TX301"}),
    (ON_ACTUATOR, {"TX302"}),
    # A joint start tag in a comment is not the parent of what follows the comment.
    (JOINT_FIRST.replace('<actuator name="m"/>', '<actuator name="m"><!-- <joint name="x"> -->'
                         "<hardwareInterface>hardware_interface/EffortJointInterface"
                         "</hardwareInterface></actuator>"), {"TX302"}),
    (JOINT_FIRST.replace('<transmission name="t">', "<n:transmission xmlns:n='urn:n'\n"
                         "name='t' type='x'>").replace("</transmission>", "</n:transmission>"),
     {"TX300", "TX301"}),
    (JOINT_FIRST.replace("hardware_interface/Effort", "<![CDATA[hardware_interface/]]>Effort"),
     {"TX302"}),
    # Only the last transmission, at the end of the scan, has a type attribute.
    (JOINT_FIRST.replace("</robot>", '<transmission name="u" type="x"/></robot>'),
     {"TX300", "TX301"}),
])
def test_the_bytes_settle_only_what_they_can_tell(text: str, settled: set[str]) -> None:
    assert settled_text(text.encode(), FIXABLE) == settled
    assert settled_text(text.encode("utf-16"), FIXABLE) == set()  # not scanned
    assert might_fix_text(text.encode(), FIXABLE) == (settled != {"TX300", "TX301", "TX302"})


def steps_and_direct(path: str, options: MigrateOptions) -> tuple[object, object]:
    """migrate_file's result (or error) as it runs, and with every stage run and what the
    conversion wrote parsed (no shortcut taken)."""
    outcomes = []
    for forced in (False, True):
        with contextlib.ExitStack() as stack:
            if forced:
                stack.enter_context(mock.patch.object(
                    migrate, "might_fix", lambda root, rules, data=None: True))
                stack.enter_context(mock.patch.object(
                    migrate, "might_fix_converted", lambda data, rules, target: True))
            try:
                outcomes.append(vars(migrate_file(path, FIXABLE, options)))
            except InputError as error:
                outcomes.append(str(error))
    return outcomes[0], outcomes[1]


OPTIONS = [MigrateOptions(mode="diff", target=target, allow_lossy=lossy)
           for target in ("ros1", "ros2-p1", "ros2-p2") for lossy in (False, True)]


@settings(max_examples=120, deadline=None, suppress_health_check=list(HealthCheck))
@given(documents(), st.sampled_from(OPTIONS))
def test_a_mutated_document_migrates_as_the_steps_migrate_it(
        document: FuzzDocument, options: MigrateOptions) -> None:
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "robot.urdf"
        path.write_bytes(document.data)
        direct, steps = steps_and_direct(str(path), options)
    assert direct == steps


def robot(joints: int, pretty: bool) -> str:
    """A chain of joints, each driven by a ROS 1 transmission (as ``bench/bench_scale.py``)."""
    parts = ['<robot name="chain">', '<link name="l0"/>']
    parts += [f'<link name="l{i}"/><joint name="j{i}" type="revolute"><parent link="l{i - 1}"/>'
              f'<child link="l{i}"/></joint>' for i in range(1, joints + 1)]
    parts += [f'<transmission name="t{i}"><type>transmission_interface/SimpleTransmission'
              f'</type><joint name="j{i}"><hardwareInterface>hardware_interface/'
              f'EffortJointInterface</hardwareInterface></joint><actuator name="m{i}">'
              f'<mechanicalReduction>{10 + i}</mechanicalReduction></actuator></transmission>'
              for i in range(1, joints + 1)]
    text = "\n".join(parts) + "\n</robot>\n"
    return text.replace("><", ">\n<") if pretty else text


@pytest.mark.parametrize("pretty", [False, True], ids=["one-line", "pretty"])
@pytest.mark.parametrize("edit", [
    "", "<!-- c -->", "<role></role>", "<hardwareInterface>EffortJointInterface"
    "</hardwareInterface>"], ids=["plain", "comment", "empty-role", "unprefixed"])
def test_a_generated_robot_migrates_as_the_steps_migrate_it(tmp_path: Path, pretty: bool,
                                                            edit: str) -> None:
    text = robot(60, pretty).replace('<actuator name="m7">', f'<actuator name="m7">{edit}')
    path = tmp_path / "chain.urdf"
    path.write_text(text)
    for options in OPTIONS:
        direct, steps = steps_and_direct(str(path), options)
        assert direct == steps


def check_comment_texts(data: bytes) -> None:
    """The comments read from the bytes are those of the parse, or the bytes do not say."""
    try:
        tree = parse_bytes(data, "doc")
    except InputError:
        return
    texts = migrate._comment_texts(data)
    if texts is not None:
        assert Counter(texts) == Counter(migrate._comments(tree))
    if not migrate._may_declare(data):
        assert not migrate._comments(tree)


@pytest.mark.parametrize("name", corpus_names())
def test_comments_read_from_the_bytes_on_a_corpus_file(name: str) -> None:
    check_comment_texts(corpus_file(name).read_bytes())


@settings(max_examples=150, deadline=None, suppress_health_check=list(HealthCheck))
@given(documents())
def test_comments_read_from_the_bytes_on_mutated_documents(document: FuzzDocument) -> None:
    check_comment_texts(document.data)


@pytest.mark.parametrize(("text", "texts"), [
    (b"<!-- a --><r><!---->\r\n<!--b\r\nc\rd--></r>", [" a ", "", "b\nc\nd"]),
    (b'<?xml version="1.0"?>\n<r><!-- a --></r>', [" a "]),
    (b"<r><?pi <!-- no --> ?></r>", None),
    (b"<r><![CDATA[<!-- no -->]]></r>", None),
    ('<?xml version="1.0" encoding="ISO-8859-1"?><r><!-- \u00e9 --></r>'.encode("latin-1"), None),
])
def test_comments_from_the_bytes_or_none_where_they_cannot_tell(text: bytes,
                                                              texts: list[str] | None) -> None:
    assert migrate._comment_texts(text) == texts


def test_a_conversion_to_ros2_is_not_scanned_again_for_ros1_spellings() -> None:
    """What converting a document no fix finds anything in gives: to ROS 2 it needs no scan
    for the fixes of ROS 1 spellings; to ROS 1, or with any other fix, its bytes are read."""
    from txtool.transform.fixable import ROS1_ONLY, might_fix_converted

    assert {rule.code for rule in FIXABLE} == ROS1_ONLY  # every fix today: a new one must be placed in or out
    written = UNPREFIXED.encode()  # what the bytes would flag
    assert might_fix_text(written, FIXABLE)
    assert not might_fix_converted(written, FIXABLE, "ros2-p2")
    assert might_fix_converted(written, FIXABLE, "ros1")
    other = FIXABLE[0]._replace(code="TX399")
    assert might_fix_converted(written, [*FIXABLE, other], "ros2-p1")


@given(st.lists(st.sampled_from([b"<!--", b"-->", b"<!-->", b"<?", b"-", b">", b"a", b"\n"]),
                max_size=12).map(b"".join),
       st.sampled_from([b"<!--", b"-->", b"<!", b"<?", b"--"]), st.integers(0, 40))
def test_a_search_by_one_byte_finds_what_find_finds(data: bytes, needle: bytes, start: int
                                                    ) -> None:
    from txtool.io.byte_search import find_by

    for rare in range(len(needle)):
        assert find_by(data, needle, rare, start) == data.find(needle, start)
