"""The language server's handlers in this process: what a buffer gets published, which quick
fixes and hovers it gets, in the client's units, for the files ``txtool validate`` checks."""

from __future__ import annotations

from pathlib import Path

import pytest
from lsprotocol import types as lsp
from pygls.workspace import TextDocument

from tests.lsp.robots import ARM, ARM_XACRO, REDUCTION, REDUCTION_LINE
from tests.lsp.test_client import applied, edits_of
from txtool.commands.lsp_document import Options, problems_of
from txtool.commands.lsp_server import code_actions, diagnostics_of, hover_of
from txtool.io.xmlio import XacroOptions

OPTIONS = Options()


STALE_ROS1 = """<robot name="arm">
  <link name="base"/><link name="arm"/>
  <joint name="elbow" type="revolute"><parent link="base"/><child link="arm"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <ros2_control name="arm" type="system">
    <hardware><plugin>mock_components/GenericSystem</plugin></hardware>
    <joint name="elbow"><command_interface name="effort"/><state_interface name="position"/></joint>
  </ros2_control>
  <transmission name="elbow_trans">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="elbow"><hardwareInterface>EffortJointInterface</hardwareInterface></joint>
    <actuator name="elbow_motor"><mechanicalReduction>50</mechanicalReduction></actuator>
  </transmission>
</robot>
"""


def document(path: Path, text: str, version: int = 1) -> TextDocument:
    return TextDocument(path.as_uri(), text, version=version)


def codes(diagnostics: list[lsp.Diagnostic]) -> list[str]:
    return sorted(str(d.code) for d in diagnostics)


@pytest.fixture
def repo(tmp_path: Path) -> Path:
    (tmp_path / ".git").mkdir()
    return tmp_path


def test_what_validate_finds_in_the_saved_file_the_buffer_gets(repo: Path) -> None:
    from txtool.lint.api import LintOptions, lint_paths

    saved = repo / "arm.urdf"
    saved.write_text(ARM)
    found = diagnostics_of(document(saved, ARM), [str(repo)], OPTIONS)
    validated = lint_paths([str(saved)], LintOptions()).problems
    assert [(d.range.start.line + 1, d.range.start.character + 1, d.code) for d in found] == [
        (p.line, p.column, p.code) for p in validated]
    assert {d.severity for d in found} == {lsp.DiagnosticSeverity.Error}  # TX106, TX300


def test_the_buffer_is_checked_not_the_file_on_disk(repo: Path) -> None:
    saved = repo / "arm.urdf"
    saved.write_text(ARM)
    typed = ARM.replace(REDUCTION, REDUCTION.replace(">0<", ">50<"))
    assert "TX106" not in codes(diagnostics_of(document(saved, typed), [str(repo)], OPTIONS))
    unsaved = repo / "never_saved.urdf"  # a new file the editor has not written yet
    assert "TX106" in codes(diagnostics_of(document(unsaved, ARM), [str(repo)], OPTIONS))


@pytest.mark.parametrize("name, text, checked", [
    ("robot.xml", ARM, True),
    ("launch.xml", "<launch><node pkg='a' exec='b'/></launch>", False),
    ("package.xml", "<?xml version='1.0'?>\n<!-- c -->\n<package format='3'/>", False),
    ("notes.txt", ARM, False),
    ("macros.xacro", ARM, True),
])
def test_only_the_files_validate_checks_in_a_folder_get_diagnostics(
        repo: Path, name: str, text: str, checked: bool) -> None:
    found = diagnostics_of(document(repo / name, text), [str(repo)], OPTIONS)
    assert bool(found) is checked


def test_a_buffer_that_is_no_file_gets_nothing() -> None:
    untitled = TextDocument("untitled:Untitled-1", ARM, version=1)
    assert diagnostics_of(untitled, [], OPTIONS) == []
    assert code_actions(untitled, lsp.CodeActionContext(diagnostics=[]), [], OPTIONS) == []
    assert hover_of(untitled, lsp.Position(line=10, character=4), [], OPTIONS) is None


def test_malformed_xml_as_typed_is_tx001_where_it_breaks(repo: Path) -> None:
    broken = ARM.replace("</joint>\n    <actuator", "\n    <actuator", 1)
    found = diagnostics_of(document(repo / "arm.urdf", broken), [str(repo)], OPTIONS)
    assert codes(found) == ["TX001"]


def test_the_configuration_of_the_workspace_s_repository_counts(repo: Path) -> None:
    (repo / ".txtool.toml").write_text('ignore = ["TX106"]\n')
    (repo / "urdf").mkdir()
    found = diagnostics_of(document(repo / "urdf" / "arm.urdf", ARM), [str(repo)], OPTIONS)
    assert codes(found) == ["TX300"]
    # A configuration below the repository's root is passed over, as validate does.
    (repo / "urdf" / ".txtool.toml").write_text('ignore = ["TX2", "TX3"]\n')
    found = diagnostics_of(document(repo / "urdf" / "arm.urdf", ARM), [str(repo)], OPTIONS)
    assert codes(found) == ["TX300"]
    # --config names the file to use.
    named = Options(config=str(repo / "urdf" / ".txtool.toml"))
    found = diagnostics_of(document(repo / "urdf" / "arm.urdf", ARM), [str(repo)], named)
    assert codes(found) == ["TX106"]


def test_a_configuration_edited_since_the_last_check_counts_at_once(repo: Path) -> None:
    buffer = document(repo / "arm.urdf", ARM)
    assert "TX106" in codes(diagnostics_of(buffer, [str(repo)], OPTIONS))
    (repo / ".txtool.toml").write_text('ignore = ["TX106"]\n')
    assert "TX106" not in codes(diagnostics_of(buffer, [str(repo)], OPTIONS))


def test_a_bad_configuration_is_one_error_on_the_first_line(repo: Path) -> None:
    (repo / ".txtool.toml").write_text('select = ["XX"]\n')
    found = diagnostics_of(document(repo / "arm.urdf", ARM), [str(repo)], OPTIONS)
    assert len(found) == 1 and found[0].code is None
    assert found[0].range.start == lsp.Position(line=0, character=0)
    assert "unknown rule code" in found[0].message and ".txtool.toml" in found[0].message


def test_suppressions_and_unused_ones_are_as_validate_reports_them(repo: Path) -> None:
    silenced = ARM.replace(REDUCTION, "      <!-- txtool: disable-next-line TX106 TX999 -->\n"
                           + REDUCTION)
    found = diagnostics_of(document(repo / "arm.urdf", silenced), [str(repo)], OPTIONS)
    assert codes(found) == ["TX005", "TX300"]  # TX999 is no rule


def test_columns_are_counted_in_the_client_s_utf16_units(repo: Path) -> None:
    # An astral character takes two UTF-16 units before the element on its line.
    wide = ARM.replace(REDUCTION, "      <!--𝔸--><mechanicalReduction>0</mechanicalReduction>")
    found = diagnostics_of(document(repo / "arm.urdf", wide), [str(repo)], OPTIONS)
    zero = next(d for d in found if d.code == "TX106")
    start = len("      <!--𝔸-->") + 1
    assert zero.range.start == lsp.Position(line=REDUCTION_LINE, character=start)
    assert zero.range.end.character == start + len("<mechanicalReduction>")


def test_the_quick_fix_and_the_fix_all_remove_what_they_fix(repo: Path) -> None:
    buffer = document(repo / "arm.urdf", ARM)
    found = diagnostics_of(buffer, [str(repo)], OPTIONS)
    actions = code_actions(buffer, lsp.CodeActionContext(diagnostics=found), [str(repo)],
                           OPTIONS)
    assert [(a.title, a.kind) for a in actions] == [
        ("Fix TX300 unprefixed-interface", lsp.CodeActionKind.QuickFix),
        ("Fix all txtool fixable problems (TX300 x1)", "source.fixAll.txtool")]
    for action in actions:
        edits = edits_of(action)
        assert len(edits) == 1 and edits[0].range.start.line == 12  # one line changes
        fixed = document(repo / "arm.urdf", applied(ARM, edits), version=2)
        assert codes(diagnostics_of(fixed, [str(repo)], OPTIONS)) == ["TX106"]
    only_fix_all = lsp.CodeActionContext(diagnostics=[], only=[lsp.CodeActionKind.SourceFixAll])
    assert [a.kind for a in code_actions(buffer, only_fix_all, [str(repo)], OPTIONS)] == [
        "source.fixAll.txtool"]


def test_no_quick_fix_for_a_finding_not_fixable_or_not_txtool_s(repo: Path) -> None:
    buffer = document(repo / "arm.urdf", ARM)
    found = diagnostics_of(buffer, [str(repo)], OPTIONS)
    others = [d for d in found if d.code != "TX300"]
    foreign = lsp.Diagnostic(range=found[0].range, message="x", code="TX300", source="other")
    context = lsp.CodeActionContext(diagnostics=[*others, foreign],
                                    only=[lsp.CodeActionKind.QuickFix])
    assert code_actions(buffer, context, [str(repo)], OPTIONS) == []


def test_a_fix_the_configuration_turns_off_is_not_offered(repo: Path) -> None:
    (repo / ".txtool.toml").write_text('ignore = ["TX300"]\n')
    buffer = document(repo / "arm.urdf", ARM)
    assert code_actions(buffer, lsp.CodeActionContext(diagnostics=[]), [str(repo)], OPTIONS) == []


def test_fix_edits_keep_every_other_line_and_the_missing_last_newline(repo: Path) -> None:
    text = ARM.replace("  <link", "  <link", 1).rstrip("\n")  # no newline at the end
    text = text.replace('<robot name="arm">', '<robot name="arm"><!-- été -->')
    buffer = document(repo / "arm.urdf", text)
    actions = code_actions(buffer, lsp.CodeActionContext(diagnostics=[]), [str(repo)], OPTIONS)
    edits = edits_of(actions[0])  # type: ignore[union-attr,index]
    assert applied(text, edits) == text.replace(">PositionJointInterface<",
                                                ">hardware_interface/PositionJointInterface<")


def test_the_hover_anywhere_in_a_transmission_shows_what_each_loader_reads(repo: Path) -> None:
    buffer = document(repo / "arm.urdf", ARM.replace(">0<", ">50<"))
    lines = ARM.splitlines()
    inside = [(9, 2), (9, 20), (REDUCTION_LINE, 30), (17, 2), (17, len(lines[17]) - 1)]
    for line, character in inside:
        hover = hover_of(buffer, lsp.Position(line=line, character=character), [str(repo)],
                         OPTIONS)
        assert hover is not None, (line, character)
        shown = hover.contents.value  # type: ignore[union-attr]
        assert shown.startswith("```text\n1 transmission(s), as their loaders bind them")
        assert "shoulder_trans (line 10): SimpleTransmission" in shown
        assert "  read by ros_control\n" in shown
        assert "shoulder_motor" in shown and "Readers:" in shown and shown.endswith("```")
    for line, character in [(8, 3), (9, 1), (17, len(lines[17])), (18, 2)]:
        assert hover_of(buffer, lsp.Position(line=line, character=character), [str(repo)],
                        OPTIONS) is None, (line, character)


def test_the_hover_is_the_effective_view_of_show(repo: Path) -> None:
    from click.testing import CliRunner

    from txtool.cli import cli

    saved = repo / "arm.urdf"
    # a robot validate finds nothing in (show marks its findings; the editor shows them)
    saved.write_text(ARM.replace(">0<", ">50<").replace(
        ">PositionJointInterface<", ">hardware_interface/PositionJointInterface<"))
    shown = CliRunner().invoke(cli, ["show", "--effective", str(saved)]).stdout
    hover = hover_of(document(saved, saved.read_text()), lsp.Position(line=12, character=8),
                     [str(repo)], OPTIONS)
    assert hover is not None
    body = hover.contents.value.removeprefix("```text\n").removesuffix("```")  # type: ignore
    assert shown == f"{saved}\n{body}"


def test_no_hover_in_a_commented_out_transmission_or_a_malformed_buffer(repo: Path) -> None:
    commented = ARM.replace("  <transmission", "  <!-- <transmission name='old'/> -->\n"
                            "  <transmission")
    buffer = document(repo / "arm.urdf", commented)
    assert hover_of(buffer, lsp.Position(line=9, character=12), [str(repo)], OPTIONS) is None
    assert hover_of(buffer, lsp.Position(line=10, character=4), [str(repo)], OPTIONS) is not None
    broken = document(repo / "arm.urdf", ARM.replace("</robot>", ""))
    assert hover_of(broken, lsp.Position(line=10, character=4), [str(repo)], OPTIONS) is None


def test_the_hover_on_a_self_closing_or_prefixed_transmission(repo: Path) -> None:
    text = ('<robot name="r" xmlns:u="urn:u">\n  <transmission name="empty"/>\n'
            '  <link name="l"/>\n</robot>\n')
    buffer = document(repo / "r.urdf", text)
    assert hover_of(buffer, lsp.Position(line=1, character=5), [str(repo)], OPTIONS) is not None
    assert hover_of(buffer, lsp.Position(line=2, character=5), [str(repo)], OPTIONS) is None


def test_an_unsaved_xacro_buffer_is_expanded_from_its_folder(repo: Path) -> None:
    """Its includes are found beside the file; what the buffer says wins over the disk."""
    (repo / "ratio.xacro").write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro">'
        '<xacro:property name="ratio" value="0"/></robot>')
    text = ARM_XACRO.replace('<xacro:property name="ratio" value="0"/>',
                             '<xacro:include filename="ratio.xacro"/>')
    saved = repo / "arm.urdf.xacro"
    saved.write_text(ARM_XACRO.replace('value="0"', 'value="50"'))
    for options in (OPTIONS, Options(xacro=XacroOptions(trust=True))):
        found = diagnostics_of(document(saved, text), [str(repo)], options)
        assert codes(found) == ["TX106"]
        hover = hover_of(document(saved, text), lsp.Position(line=16, character=8), [str(repo)],
                         options)
        assert hover is not None and "not loaded: reduction ratio cannot be zero" in (
            hover.contents.value)  # type: ignore[union-attr]
    # With xacro off, the buffer is read as written: ${ratio} is not known.
    found = diagnostics_of(document(saved, text), [str(repo)], Options(no_xacro=True))
    assert "TX106" not in codes(found)


def test_a_xacro_macro_library_is_hovered_as_written(repo: Path) -> None:
    library = ('<robot xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
               '  <xacro:macro name="drive" params="j">\n'
               '    <transmission name="${j}_trans">\n'
               '      <type>transmission_interface/SimpleTransmission</type>\n'
               '      <joint name="${j}"><hardwareInterface>hardware_interface/'
               'EffortJointInterface</hardwareInterface></joint>\n'
               '      <actuator name="${j}_motor"><mechanicalReduction>10'
               '</mechanicalReduction></actuator>\n'
               '    </transmission>\n  </xacro:macro>\n</robot>\n')
    hover = hover_of(document(repo / "drive.xacro", library), lsp.Position(line=3, character=8),
                     [str(repo)], OPTIONS)
    assert hover is not None and "${j}_trans (line 3)" in hover.contents.value  # type: ignore


def test_a_refused_expansion_is_one_error_at_its_line(repo: Path) -> None:
    text = ARM_XACRO.replace('value="0"', 'value="${__import__(\'os\').getcwd()}"')
    found = diagnostics_of(document(repo / "arm.urdf.xacro", text), [str(repo)], OPTIONS)
    assert len(found) == 1 and found[0].severity == lsp.DiagnosticSeverity.Error
    assert found[0].range.start.line == 2 and "xacro" in found[0].message


def test_a_macro_s_transmission_is_hovered_as_each_call_produces_it(repo: Path) -> None:
    text = ('<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
            '  <xacro:macro name="drive" params="j ratio">\n'
            '    <transmission name="${j}_trans">\n'
            '      <type>transmission_interface/SimpleTransmission</type>\n'
            '      <joint name="${j}"><hardwareInterface>hardware_interface/'
            'EffortJointInterface</hardwareInterface></joint>\n'
            '      <actuator name="${j}_motor"><mechanicalReduction>${ratio}'
            '</mechanicalReduction></actuator>\n'
            '    </transmission>\n  </xacro:macro>\n'
            '  <link name="a"/><link name="b"/>\n'
            '  <joint name="one" type="revolute"><parent link="a"/><child link="b"/>'
            '<limit lower="-1" upper="1" effort="1" velocity="1"/></joint>\n'
            '  <xacro:drive j="one" ratio="10"/>\n  <xacro:drive j="two" ratio="0"/>\n'
            '</robot>\n')
    hover = hover_of(document(repo / "r.urdf.xacro", text), lsp.Position(line=4, character=8),
                     [str(repo)], OPTIONS)
    assert hover is not None
    shown = hover.contents.value  # type: ignore[union-attr]
    assert shown.startswith("```text\n2 transmission(s)")
    assert "one_trans (line 3)" in shown and "two_trans (line 3)" in shown
    assert "not loaded: reduction ratio cannot be zero" in shown


def test_a_suppressed_finding_is_not_fixed(repo: Path) -> None:
    interface = "      <hardwareInterface>PositionJointInterface</hardwareInterface>"
    silenced = ARM.replace(interface, "      <!-- txtool: disable-next-line TX300 -->\n"
                           + interface)
    buffer = document(repo / "arm.urdf", silenced)
    assert "TX300" not in codes(diagnostics_of(buffer, [str(repo)], OPTIONS))
    assert code_actions(buffer, lsp.CodeActionContext(diagnostics=[]), [str(repo)], OPTIONS) == []


def test_the_root_is_the_workspace_s_repository_else_the_file_s(tmp_path: Path) -> None:
    from txtool.commands.lsp_document import root_of

    (tmp_path / "ws" / ".git").mkdir(parents=True)
    (tmp_path / "ws" / "pkg" / "urdf").mkdir(parents=True)
    (tmp_path / "elsewhere").mkdir()
    robot = tmp_path / "ws" / "pkg" / "urdf" / "arm.urdf"
    inner = str(tmp_path / "ws" / "pkg")
    assert root_of(str(robot), [str(tmp_path / "elsewhere"), inner]) == str(tmp_path / "ws")
    assert root_of(str(robot), [str(tmp_path / "elsewhere")]) == str(tmp_path / "ws")
    loose = tmp_path / "elsewhere" / "arm.urdf"
    assert root_of(str(loose), [inner]) == str(tmp_path / "elsewhere")


def test_a_buffer_is_read_in_the_encoding_its_declaration_names(repo: Path) -> None:
    latin = ARM.replace('<?xml version="1.0"?>', '<?xml version="1.0" encoding="ISO-8859-1"?>')
    latin = latin.replace(REDUCTION, "      <!--é--><mechanicalReduction>0</mechanicalReduction>")
    found = diagnostics_of(document(repo / "arm.urdf", latin), [str(repo)], OPTIONS)
    zero = next(d for d in found if d.code == "TX106")
    assert zero.range.start.character == len("      <!--é-->")
    actions = code_actions(document(repo / "arm.urdf", latin),
                           lsp.CodeActionContext(diagnostics=[]), [str(repo)], OPTIONS)
    fixed = applied(latin, edits_of(actions[0]))  # type: ignore
    assert fixed == latin.replace(">PositionJointInterface<",
                                  ">hardware_interface/PositionJointInterface<")
    # An encoding that cannot hold the text, or that is no encoding: UTF-8.
    from txtool.commands.lsp_document import encode

    assert encode('<?xml version="1.0" encoding="ascii"?><r>é</r>')[1] == "utf-8"
    assert encode('<?xml version="1.0" encoding="no-such"?><r/>')[1] == "utf-8"


def test_a_stale_diagnostic_gets_no_fix_where_there_is_none(repo: Path) -> None:
    buffer = document(repo / "arm.urdf", ARM)
    stale = [d for d in diagnostics_of(buffer, [str(repo)], OPTIONS) if d.code == "TX300"]
    quick = lsp.CodeActionContext(diagnostics=stale, only=[lsp.CodeActionKind.QuickFix])
    fixed = document(repo / "arm.urdf", ARM.replace(">PositionJointInterface<",
                                                    ">hardware_interface/PositionJointInterface<"))
    assert code_actions(fixed, quick, [str(repo)], OPTIONS) == []  # fixed since
    broken = document(repo / "arm.urdf", ARM.replace("</robot>", ""))
    assert code_actions(broken, quick, [str(repo)], OPTIONS) == []  # not XML as it stands
    (repo / ".txtool.toml").write_text('ignore = ["TX300"]\n')
    assert code_actions(buffer, quick, [str(repo)], OPTIONS) == []  # turned off since


def test_line_edits_reach_the_end_of_a_document_with_or_without_its_last_newline() -> None:
    from txtool.commands.lsp_document import end_of, line_edits

    for before, after in [("a\nb", "a\nc"), ("a\nb\n", "a\nb\nc\n"), ("a", "a\nb"), ("", "x\n"),
                          ("a\r\nb\r\n", "a\r\nc\r\n")]:
        edits = [lsp.TextEdit(range=lsp.Range(start=lsp.Position(*end_of(before, e.start)),
                                              end=lsp.Position(*end_of(before, e.end))),
                              new_text=e.text) for e in line_edits(before, after)]
        assert applied(before, edits) == after, (before, after)


def test_the_hover_of_an_unexpanded_xacro_file_is_of_its_text(repo: Path) -> None:
    text = ARM_XACRO.replace('value="0"', 'value="$(arg ratio)"')  # no argument given
    hover = hover_of(document(repo / "arm.urdf.xacro", text), lsp.Position(line=16, character=8),
                     [str(repo)], OPTIONS)
    assert hover is not None and "shoulder_trans (line 11)" in hover.contents.value  # type: ignore


def test_no_hover_on_a_macro_no_call_produces(repo: Path) -> None:
    called = ARM_XACRO.replace('value="0"', 'value="10"')
    unused = ('  <xacro:macro name="unused">\n    <transmission name="never"/>\n'
              '  </xacro:macro>\n</robot>')
    text = called.replace("</robot>", unused)
    lines = text.splitlines()
    line = next(i for i, each in enumerate(lines) if 'name="never"' in each)
    buffer = document(repo / "arm.urdf.xacro", text)
    assert hover_of(buffer, lsp.Position(line=line, character=8), [str(repo)], OPTIONS) is None
    assert hover_of(buffer, lsp.Position(line=12, character=8), [str(repo)], OPTIONS) is not None


def test_a_start_tag_left_open_runs_to_the_end() -> None:
    from txtool.commands.lsp_hover import transmission_at

    text = '<robot>\n  <transmission name="t"'
    assert transmission_at(text, len(text) - 1) == 2
    assert transmission_at(text, 3) is None


def test_an_unsaved_xacro_buffer_counts_in_what_an_expansion_may_read(repo: Path,
                                                                     monkeypatch) -> None:
    from txtool.io import xacro as xacro_support

    monkeypatch.setattr(xacro_support, "MAX_READ", len(ARM_XACRO.encode()) - 1)
    found = diagnostics_of(document(repo / "arm.urdf.xacro", ARM_XACRO), [str(repo)], OPTIONS)
    failed = [d for d in found if d.code == "TX002"]
    assert len(failed) == 1 and "xacro would read more than" in failed[0].message
    monkeypatch.setattr(xacro_support, "MAX_READ", len(ARM_XACRO.encode()))
    found = diagnostics_of(document(repo / "arm.urdf.xacro", ARM_XACRO), [str(repo)], OPTIONS)
    assert codes(found) == ["TX106"]


def test_a_configuration_that_cannot_be_read_is_said_once_and_offers_nothing(
        repo: Path, monkeypatch) -> None:
    (repo / ".txtool.toml").write_text('select = ["XX"]\n')
    buffer = document(repo / "arm.urdf", ARM)
    context = lsp.CodeActionContext(diagnostics=[])
    assert code_actions(buffer, context, [str(repo)], OPTIONS) == []
    assert hover_of(buffer, lsp.Position(line=10, character=4), [str(repo)], OPTIONS) is None
    from txtool.commands import lsp_document

    def refused(*_: object) -> None:
        raise PermissionError(13, "Permission denied", str(repo / ".txtool.toml"))

    monkeypatch.setattr(lsp_document, "settings_for", refused)
    found = diagnostics_of(buffer, [str(repo)], OPTIONS)
    assert [d.message for d in found] == [f"{repo / '.txtool.toml'}: permission denied"]
    assert code_actions(buffer, context, [str(repo)], OPTIONS) == []


def test_fix_all_fixes_only_what_the_buffer_shows(repo: Path) -> None:
    """ROS 1 blocks in a file only ros2_control reads get a TX305 note, no TX300 finding: the
    fix-all action leaves them as they are (``migrate`` would still prefix them)."""
    (repo / "package.xml").write_text(
        '<package format="3"><name>arm</name><buildtool_depend>ament_cmake</buildtool_depend>'
        "<export><build_type>ament_cmake</build_type></export></package>")
    text = STALE_ROS1
    path = repo / "robot.urdf"
    path.write_text(text)
    buffer = TextDocument(path.as_uri(), text)
    found = problems_of(str(path), text, str(repo), OPTIONS)
    assert "TX305" in {p.code for p in found} and "TX300" not in {p.code for p in found}
    everything = lsp.CodeActionContext(diagnostics=[])
    assert code_actions(buffer, everything, [str(repo)], OPTIONS) == []


def test_a_finding_made_by_a_macro_call_carries_the_macro_as_related_information(
        repo: Path) -> None:
    """The diagnostic is on the call's argument; the macro's line is its related place."""
    text = ('<robot name="arm" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
            '  <xacro:macro name="tx" params="n r">\n'
            '    <transmission name="${n}_t">\n'
            '      <type>transmission_interface/SimpleTransmission</type>\n'
            '      <joint name="${n}"><hardwareInterface>hardware_interface/'
            'EffortJointInterface</hardwareInterface></joint>\n'
            '      <actuator name="${n}_m"><mechanicalReduction>${r}</mechanicalReduction>'
            '</actuator>\n'
            '    </transmission>\n'
            '  </xacro:macro>\n'
            '  <xacro:tx n="a" r="0"/>\n'
            '</robot>\n')
    found = [d for d in diagnostics_of(document(repo / "tx.urdf.xacro", text), [str(repo)],
                                       OPTIONS) if d.code == "TX106"]
    assert [(d.range.start.line, d.range.start.character) for d in found] == [(8, 18)]
    [related] = found[0].related_information
    assert related.location.uri == (repo / "tx.urdf.xacro").as_uri()
    assert related.location.range.start == lsp.Position(line=5, character=30)
    assert related.message == "in expansion of macro 'tx' defined at " + str(
        repo / "tx.urdf.xacro").rsplit("/", 1)[-1] + ":2"
