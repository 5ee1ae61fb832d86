"""Every document migrate or convert writes is its original with the edits made, and no byte
outside an edit differs: over every corpus, workspace and fixture file, to every target and
back, with --reversible, and over generated and fuzzed documents.

Before the line splice that conversions were written with was deleted, the two writers were
run side by side over the same documents (corpus, workspace, fixtures and about a thousand
fuzzed ones, every target, --reversible and --allow-lossy): the same bytes, but where the
splice rewrote bytes no change touched (the whitespace around the root, the quotes of a start
tag whose attribute changed), a ``--reversible`` original carried as lxml reserialized it
rather than as written, and an element emptied by ``migrate --to`` written ``<x/>`` where
``convert`` wrote ``<x></x>``; each is now what the edits write.
"""

from __future__ import annotations

import codecs
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from tests.corpus import CORPUS, WORKSPACE
from tests.hardening.fuzz_inputs import FIXTURES, documents
from txtool.io.xmlio import InputError, Source, parse_bytes
from txtool.rules import all_rules
from txtool.transform.convert import convert_source
from txtool.transform.edits.core import EditedText
from txtool.transform.migrate import MigrateOptions, migrate_file

FIXES = [rule for rule in all_rules().values() if rule.fixable]
OPTIONS = [MigrateOptions(), *(MigrateOptions(target=target, reversible=reversible,
                                              allow_lossy=True)
                               for target in ("ros1", "ros2-p1", "ros2-p2")
                               for reversible in (False, True))]


def _documents() -> list[Path]:
    found = sorted(p for p in FIXTURES.iterdir() if p.is_file())
    for folder in (CORPUS, WORKSPACE):
        if folder.is_dir():
            found += sorted(p for p in folder.rglob("*") if p.suffix in (".urdf", ".xacro", ".xml")
                            and p.name != "package.xml")
    return found


def _migrated(tmp_path: Path, data: bytes, suffix: str = ".urdf",
              options: MigrateOptions | None = None):
    path = tmp_path / f"robot{suffix}"
    path.write_bytes(data)
    return migrate_file(str(path), FIXES, options or MigrateOptions())


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


def _written(original: bytes, data: bytes, edits) -> None:
    """``data`` is ``original`` with ``edits`` made and parses; ``_edits_alone_changed``."""
    if data == original:
        return
    assert EditedText(original).applied(edits) == data
    parse_bytes(data, "written", limit=None)

    class Result:
        pass

    result = Result()
    result.data, result.edits = data, edits
    _edits_alone_changed(original, result)


def _every_way(original: bytes, tmp_path: Path, suffix: str = ".urdf") -> None:
    """migrate with every option set, then convert what it wrote back to ROS 1."""
    for options in OPTIONS:
        try:
            result = _migrated(tmp_path, original, suffix, options)
        except InputError:
            continue  # refused (the fixtures hold a broken robot): nothing written
        if result.refused:
            continue
        _written(original, result.data, result.edits)
        if options.target not in (None, "ros1") and result.data != original:
            back = convert_source(Source("back", result.data,
                                         parse_bytes(result.data, "back", limit=None)), "ros1")
            _written(result.data, back.data, back.edits)


@pytest.mark.parametrize("path", _documents(), ids=lambda p: p.name)
def test_every_corpus_workspace_and_fixture_file(path: Path, tmp_path: Path) -> None:
    _every_way(path.read_bytes(), tmp_path, "".join(path.suffixes[-2:]))


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


@settings(max_examples=40, deadline=None, suppress_health_check=[
    HealthCheck.function_scoped_fixture, HealthCheck.too_slow])
@given(original=fixable_documents())
def test_generated_documents_that_want_fixes(original: bytes, tmp_path: Path) -> None:
    assert _migrated(tmp_path, original).fixes
    _every_way(original, tmp_path)


@settings(max_examples=40, deadline=None, suppress_health_check=[
    HealthCheck.function_scoped_fixture, HealthCheck.too_slow, HealthCheck.data_too_large,
    HealthCheck.large_base_example])
@given(document=documents())
def test_fuzzed_documents(document, tmp_path: Path) -> None:
    _every_way(document.data, tmp_path, document.suffix)
