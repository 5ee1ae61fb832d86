"""migrate's fixes written as edits, against the line-splicing writer they replaced.

The line writer (kept here as the oracle, and still the writer of conversions) serialized the
fixed tree and spliced its changed lines into the original. The edits writer must give the
same bytes over every corpus file, the workspace, the fixtures and generated documents, except
where the line writer rewrote bytes that no fix changed; those differences are judged below,
each with the reason the edits are right:

- the whitespace between the nodes before or after the root (a blank line after a declaration,
  the spaces after the end tag of a fragment): a serialization has its own, and the line
  writer wrote it in the lines it took from the serialization;
- the quotes and spaces of a start tag one of whose attributes a fix dropped: the line writer
  wrote the whole line as serialized (``name='t' `` became ``name="t"``), the edits drop the
  attribute alone (tests/migrate/test_splice.py).

And every document a migration writes is the original with its edits made: no byte outside
an edit differs.
"""

from __future__ import annotations

import codecs
from bisect import bisect_right
from difflib import SequenceMatcher
from itertools import accumulate
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from lxml import etree

from tests.corpus import CORPUS, WORKSPACE
from tests.hardening.fuzz_inputs import FIXTURES, documents
from txtool.io.xmlio import InputError, parse_bytes, serialize
from txtool.rules import all_rules
from txtool.transform.edits import EditedText
from txtool.transform.migrate import MigrateOptions, fix_tree, migrate_file
from txtool.transform.splice import splice

FIXES = [rule for rule in all_rules().values() if rule.fixable]


def _line_writer(original: bytes) -> bytes:
    """The fixed document as the line writer wrote it."""
    tree = parse_bytes(original, "oracle")
    baseline = serialize(tree, original)
    fix_tree(tree, FIXES, original)
    return splice(original, baseline, serialize(tree, original))


def _documents() -> list[Path]:
    found = sorted(p for p in FIXTURES.iterdir() if p.is_file())
    for folder in (CORPUS, WORKSPACE):
        if folder.is_dir():
            found += sorted(p for p in folder.rglob("*") if p.suffix in (".urdf", ".xacro", ".xml")
                            and p.name != "package.xml")
    return found


def _migrated(tmp_path: Path, data: bytes, suffix: str = ".urdf"):
    path = tmp_path / f"robot{suffix}"
    path.write_bytes(data)
    return migrate_file(str(path), FIXES, MigrateOptions())


def _edits_alone_changed(original: bytes, result) -> None:
    """The result is the original with its edits made: walking the edits in order, every
    byte between them is the original's."""
    if result.data == original:
        return
    assert result.edits, "a changed document not written by edits"
    text = EditedText(original)
    written = EditedText(result.data).data  # in the form the edits address
    at = out = 0
    for edit in sorted(result.edits, key=lambda edit: (edit.start, edit.end)):
        assert written[out:out + edit.start - at] == text.data[at:edit.start]
        out += edit.start - at
        assert written[out:out + len(edit.content)] == edit.content
        out += len(edit.content)
        at = edit.end
    assert written[out:] == text.data[at:]


def _judged(original: bytes, oracle: bytes, result) -> None:
    """The edits give the oracle's bytes, or the same document with fewer bytes changed:
    each edit is on a line that the oracle wrote anew as well (or puts lines between two)."""
    if oracle == result.data:
        return
    assert _canonical(result.data) == _canonical(oracle)
    lines = EditedText(original).data.splitlines(keepends=True)
    matcher = SequenceMatcher(None, lines, EditedText(oracle).data.splitlines(keepends=True),
                              autojunk=False)
    kept = {i + k for i, _, size in matcher.get_matching_blocks() for k in range(size)}
    starts = list(accumulate((len(line) for line in lines), initial=0))
    for edit in result.edits:
        if edit.start == edit.end and edit.start in starts:
            continue  # new lines between two lines: neither is changed
        first = bisect_right(starts, edit.start) - 1
        last = bisect_right(starts, max(edit.end - 1, edit.start)) - 1
        assert not kept.intersection(range(first, last + 1)), (edit, lines[first:last + 1])


def _canonical(data: bytes) -> bytes:
    return etree.tostring(parse_bytes(data, "written", limit=None), method="c14n")


@pytest.mark.parametrize("path", _documents(), ids=lambda p: p.name)
def test_every_corpus_workspace_and_fixture_file(path: Path, tmp_path: Path) -> None:
    original = path.read_bytes()
    try:
        oracle = _line_writer(original)
    except InputError:
        return  # refused alike by both (the fixtures hold a broken robot)
    result = _migrated(tmp_path, original, "".join(path.suffixes[-2:]))
    assert result.data == oracle
    _edits_alone_changed(original, result)


LAYOUTS = st.sampled_from(["\n", "\r\n", "\r"])
ENCODINGS = st.sampled_from(["utf-8", "utf-8-sig", "latin-1", "utf-16", "utf-32"])


@st.composite
def fixable_documents(draw) -> bytes:
    """A robot whose ROS 1 transmissions each want some of the fixes, in every layout: line
    endings, encodings, quotes, comments, a xacro macro around them, members written empty."""
    quote = draw(st.sampled_from(['"', "'"]))
    q = lambda value: f"{quote}{value}{quote}"  # noqa: E731
    blocks = []
    for n in range(draw(st.integers(1, 4))):
        legacy = n == 0 or draw(st.booleans())  # one fix at least: TX302
        interface = draw(st.sampled_from(["EffortJointInterface", "hardware_interface/"
                                          "PositionJointInterface", None]))
        on_actuator = draw(st.booleans())
        head = f"<transmission name={q(f't{n}')}" + (
            f" type={q('transmission_interface/SimpleTransmission')}" if legacy else "") + ">"
        body = [] if legacy and draw(st.booleans()) else [
            "<type>transmission_interface/SimpleTransmission</type>"]
        held = f"<hardwareInterface>{interface}</hardwareInterface>" if interface else ""
        joint = (f"<joint name={q(f'j{n}')}/>" if on_actuator or not held
                 else f"<joint name={q(f'j{n}')}>{held}</joint>")
        reduction = "<mechanicalReduction>2</mechanicalReduction>"
        actuator = f"<actuator name={q(f'm{n}')}>{held if on_actuator else ''}</actuator>"
        if draw(st.booleans()):
            body.append("<!-- kept -->")
        body += [joint, actuator] if draw(st.booleans()) else [actuator, joint]
        if legacy:
            body.append(reduction)
        inner = "\n    ".join(body) if draw(st.booleans()) else "".join(body)
        blocks.append(f"{head}\n    {inner}\n  </transmission>")
    content = "\n  ".join(blocks)
    if draw(st.booleans()):
        content = f'<xacro:macro name="arm" params="">\n  {content}\n  </xacro:macro>'
    text = (f"<?xml version='1.0' encoding='ENC'?>\n<!-- a licence -->\n"
            f'<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n  <link name="é"/>\n'
            f"  {content}\n</robot>\n")
    encoding = draw(ENCODINGS)
    declared = {"utf-8-sig": "UTF-8", "latin-1": "ISO-8859-1"}.get(encoding, encoding.upper())
    text = text.replace("ENC", declared).replace("\n", draw(LAYOUTS))
    data = text.encode(encoding)
    if encoding in ("utf-16", "utf-32") and draw(st.booleans()):
        data = data.removeprefix(codecs.BOM_UTF16_LE if encoding == "utf-16"
                                 else codecs.BOM_UTF32_LE)  # encoding told by the zero bytes
    return data


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(original=fixable_documents())
def test_generated_documents_that_want_fixes(original: bytes, tmp_path: Path) -> None:
    result = _migrated(tmp_path, original)
    assert result.fixes
    _judged(original, _line_writer(original), result)
    _edits_alone_changed(original, result)


@settings(max_examples=60, deadline=None, suppress_health_check=[
    HealthCheck.function_scoped_fixture, HealthCheck.too_slow, HealthCheck.data_too_large,
    HealthCheck.large_base_example])
@given(document=documents())
def test_fuzzed_documents(document, tmp_path: Path) -> None:
    try:
        oracle = _line_writer(document.data)
        result = _migrated(tmp_path, document.data, document.suffix)
    except InputError:
        return  # not a document either writer writes
    _judged(document.data, oracle, result)
    _edits_alone_changed(document.data, result)
