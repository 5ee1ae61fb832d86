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
from tests.hardening.test_fuzz_regressions import arm_with_transmissions
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
def test_every_corpus_workspace_and_fixture_file(path: Path, tmp_path: Path,
                                                 monkeypatch: pytest.MonkeyPatch) -> None:
    from txtool.transform import convert

    document = convert._convert_document

    def near_enough(*args, near):
        assert near, "the index's siblings around a change were not enough"
        return document(*args, near=near)

    monkeypatch.setattr(convert, "_convert_document", near_enough)
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


def test_a_change_beside_a_child_the_index_passed_over_is_converted_again(monkeypatch) -> None:
    """The one switch of the index's shortcut: with no sibling around a transmission
    indexed, the placer's change needs one the index passed over, and the conversion runs
    again with every child of the root indexed, to the same bytes."""
    from txtool.transform import convert
    from txtool.transform.edits import conversion_edits

    data = (b'<robot name="r">\n  <link name="a"/>\n  <transmission name="t">\n'
            b"    <type>transmission_interface/SimpleTransmission</type>\n"
            b'    <joint name="j"><hardwareInterface>hardware_interface/EffortJointInterface'
            b"</hardwareInterface></joint>\n"
            b'    <actuator name="m"><mechanicalReduction>5</mechanicalReduction></actuator>\n'
            b'  </transmission>\n  <link name="b"/>\n  <transmission name="u">\n'
            b"    <type>transmission_interface/SimpleTransmission</type>\n"
            b'    <joint name="k"><hardwareInterface>hardware_interface/EffortJointInterface'
            b"</hardwareInterface></joint>\n"
            b'    <actuator name="n"><mechanicalReduction>5</mechanicalReduction></actuator>\n'
            b"  </transmission>\n</robot>\n")

    def converted():
        return convert_source(Source("r.urdf", data, parse_bytes(data, "r.urdf")), "ros2-p2")

    expected = converted()
    runs = []
    document = convert._convert_document

    def counted(*args, near):
        runs.append(near)
        return document(*args, near=near)

    monkeypatch.setattr(convert, "_convert_document", counted)
    monkeypatch.setattr(conversion_edits, "_AROUND", 0)
    again = converted()
    assert runs == [True, False]
    assert (again.data, again.edits) == (expected.data, expected.edits)
    _written(data, again.data, again.edits)


@pytest.mark.parametrize("kept", [
    "vendor_hw/StateInterface",  # a custom type: left as written
    " transmission_interface/SimpleTransmission <x/>",  # not plain text: taken for kept
])
def test_a_transmission_left_as_written_between_converted_ones_is_indexed(kept: str,
                                                                          monkeypatch) -> None:
    """The index skips the transmissions a conversion replaces whole (it writes over them);
    one it leaves as written (a custom type, franka_ros's state interface) is indexed as a
    kept neighbour, with no second pass."""
    from txtool.transform import convert

    def transmission(name: str, kind: str) -> str:
        return (f'  <transmission name="{name}"><type>{kind}</type><joint name="j{name}">'
                "<hardwareInterface>hardware_interface/EffortJointInterface"
                "</hardwareInterface></joint><actuator name=\"m{name}\">"
                "<mechanicalReduction>2</mechanicalReduction></actuator></transmission>\n")

    simple = "transmission_interface/SimpleTransmission"
    data = ('<robot name="r">\n  <link name="a"/>\n' + "".join(
        transmission(name, kind) for name, kind in (("t1", simple), ("t2", simple),
                                                    ("t3", kept), ("t4", simple)))
            + '  <link name="b"/>\n</robot>\n').encode()
    runs = []
    document = convert._convert_document
    monkeypatch.setattr(convert, "_convert_document",
                        lambda *args, near: runs.append(near) or document(*args, near=near))
    result = convert_source(Source("r.urdf", data, parse_bytes(data, "r.urdf")), "ros2-p2")
    assert runs == [True]
    assert result.converted == (3 if "<x/>" not in kept else 4)
    _written(data, result.data, result.edits)


ROBOT = (b'<robot name="r">\n  <link name="a"/>\n  <transmission name="t">\n'
         b"    <type>transmission_interface/SimpleTransmission</type>\n"
         b'    <joint name="j"><hardwareInterface>hardware_interface/EffortJointInterface'
         b"</hardwareInterface></joint>\n"
         b'    <actuator name="m"><mechanicalReduction>5</mechanicalReduction></actuator>\n'
         b"  </transmission>\n</robot>\n")


def _convert(data: bytes = ROBOT, target: str = "ros2-p2"):
    return convert_source(Source("r.urdf", data, parse_bytes(data, "r.urdf")), target)


@pytest.mark.parametrize("data", [ROBOT, arm_with_transmissions(40)], ids=["one", "block"])
@pytest.mark.parametrize(("patch", "reason"), [
    ("index", "r.urdf: cannot convert: the bytes do not read as parsed (refused)"),
    ("edits", "r.urdf: cannot convert: refused"),
    ("applied", "r.urdf: cannot convert: what the edits write does not read as the converted"
                " document"),
    ("unreadable", "r.urdf: cannot convert: what the edits write does not read back"),
])
def test_a_conversion_the_edits_cannot_write_is_refused_in_one_line(patch, reason, data,
                                                                     monkeypatch) -> None:
    """No other writer stands behind the edits: the conversion is refused, naming the
    file, and the library raises what the command line prints with exit 2; a document
    whose block is written as text ("block") is checked on the bytes written as well."""
    from txtool.transform.edits import conversion_edits
    from txtool.transform.edits.spans import SpanError
    from txtool.transform.edits.tree_edits import NotEditable

    def refuse(*_args, **_kwargs):
        raise (SpanError if patch == "index" else NotEditable)("refused")

    if patch == "index":
        monkeypatch.setattr(conversion_edits, "SpanIndex", refuse)
    elif patch == "edits":
        monkeypatch.setattr(conversion_edits.TreeChange, "edits", refuse)
    else:
        applied = conversion_edits.ConversionEdits.applied
        tail = b"<!-- x -->\n" if patch == "applied" else b"<"
        monkeypatch.setattr(conversion_edits.ConversionEdits, "applied",
                            lambda self, edits: applied(self, edits) + tail)
    with pytest.raises(InputError) as refused:
        _convert(data)
    assert str(refused.value).startswith(reason) and "\n" not in str(refused.value)


@pytest.mark.parametrize("newline", [b"\n", b"\r\n"])
@pytest.mark.parametrize("prolog", [False, True])
def test_the_check_reads_the_written_bytes_with_the_block_marker_back(newline, prolog,
                                                                       monkeypatch) -> None:
    """Where a block is written as text, the check parses the bytes written with the
    block's text taken out for its marker: exactly what the edits write with the marker
    unfilled, wherever edits before it moved it (transmissions cut before the block, a
    declaration and comment at the start)."""
    from txtool.transform import convert
    from txtool.transform.edits.core import EditedText

    data = arm_with_transmissions(40).replace(b"\n", newline)
    if prolog:
        data = b'<?xml version="1.0"?>' + newline + b"<!-- arm -->" + newline + data.replace(
            b'<transmission name="t3">', b'<link name="between"/><transmission name="t3">')
    checked = []
    check = convert.check_written

    def recorded(written, edits, path, expected):
        assert expected.marked is not None
        place, unfilled, token = expected.marked
        unfilled_edits = [*edits[:place], unfilled, *edits[place + 1:]]
        checked.append((conversion_edits._marked(written, edits, *expected.marked),
                        EditedText(data).applied(unfilled_edits), token))
        check(written, edits, path, expected)

    from txtool.transform.edits import conversion_edits

    monkeypatch.setattr(convert, "check_written", recorded)
    result = _convert(data)
    [(parsed, unfilled, token)] = checked
    assert parsed == unfilled and parsed.count(token) == 1 and token not in result.data
    assert len(parsed) < len(result.data) / 2  # the block's text is most of the document


def test_a_block_whose_marker_cannot_be_filled_in_is_parsed_into_the_tree(monkeypatch):
    from txtool.transform.edits import conversion_edits

    filled = []
    fill = conversion_edits._filled
    monkeypatch.setattr(conversion_edits, "_filled",
                        lambda *args: filled.append(1) or fill(*args))
    expected = _convert(arm_with_transmissions(40))
    assert filled  # the block was written as text, and filled in
    monkeypatch.setattr(conversion_edits, "_filled", lambda edits, marker, pieces: None)
    again = _convert(arm_with_transmissions(40))
    assert (again.data, again.losses, again.notes) == (
        expected.data, expected.losses, expected.notes)


@pytest.mark.parametrize(("where", "spoil"), [
    ("before the window", lambda data: data.replace(b'<joint name="j0"', b'<joint name="k0"')),
    ("in the window", lambda data: data.replace(b'<joint name="j39"', b'<joint name="k39"')),
    ("after the root", lambda data: data + b"<!-- x -->\n"),
])
def test_the_check_reads_from_the_window_and_holds_the_bytes_before_it_to_the_input(
        where, spoil, monkeypatch) -> None:
    """A robot whose joints come before its transmissions is read back from a few children
    before the first transmission on (the root's first child recorded), the bytes before it
    held to the input's as bytes; a byte of the written document changed before that child,
    after it, or after the root is refused as when the whole document is read."""
    from txtool.transform.edits import conversion_edits

    data = arm_with_transmissions(40)
    verdicts: list[bool] = []
    reads = conversion_edits._reads_as_window
    monkeypatch.setattr(conversion_edits, "_reads_as_window",
                        lambda *args: verdicts.append(verdict := reads(*args)) or verdict)
    result = _convert(data)
    assert verdicts == [True] and result.data.count(b"<transmission ") == 40
    applied = conversion_edits.ConversionEdits.applied
    monkeypatch.setattr(conversion_edits.ConversionEdits, "applied",
                        lambda self, edits: spoil(applied(self, edits)))
    verdicts.clear()
    with pytest.raises(InputError) as refused:
        _convert(data)
    assert verdicts == [False]
    assert str(refused.value).startswith("r.urdf: cannot convert: what the edits write does "
                                         "not read as the converted document")


def test_a_robot_all_ros1_of_standard_types_is_glanced_at_once_and_a_glance_wrong_is_run_again(
        monkeypatch) -> None:
    """Which transmissions a conversion replaces whole (the index skips them) is glanced
    at from the bytes for a robot all ROS 1 whose every ``<type>`` names a standard type,
    with no step for each; a custom type the glance cannot see (``<type >``) makes the
    conversion run again with every child of the root indexed, to the bytes a
    transmission-by-transmission glance gives in one run."""
    from txtool.transform import convert
    from txtool.transform.edits import conversion_edits

    data = arm_with_transmissions(12)
    standard = conversion_edits._standard
    monkeypatch.setattr(conversion_edits, "_standard", lambda element: pytest.fail("stepped"))
    assert _convert(data).converted == 12
    monkeypatch.setattr(conversion_edits, "_standard", standard)

    custom = data.replace(b"<type>transmission_interface/SimpleTransmission</type>"
                          b'<joint name="j5">', b'<type >vendor_hw/Custom</type><joint name="j5">')
    runs: list[bool] = []
    document = convert._convert_document
    monkeypatch.setattr(convert, "_convert_document",
                        lambda *args, near: runs.append(near) or document(*args, near=near))
    again = _convert(custom)
    assert runs == [True, False] and again.converted == 11
    monkeypatch.setattr(conversion_edits, "_types_standard", lambda data: False)
    runs.clear()
    stepped = _convert(custom)
    assert runs == [True]
    assert (again.data, again.edits, again.notes) == (stepped.data, stepped.edits, stepped.notes)
    _written(custom, again.data, again.edits)
