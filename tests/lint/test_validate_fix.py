"""``txtool validate --fix`` and ``--diff``: migrate's fixes where a linter's users look for
them, the ``[*]`` marks and count of what they fix, and several reports from one run."""

from __future__ import annotations

import json
import os
import shutil
from pathlib import Path

import jsonschema
import pytest
from click.testing import CliRunner

from tests.corpus import corpus_file
from tests.lint.test_reporters import sarif_schema
from txtool.cli import cli
from txtool.reporters.fixes import Edit, edits_between, edits_for

LEGACY = """<robot name="r">
  <joint name="j" type="revolute"><limit effort="1" velocity="1" lower="-1" upper="1"/></joint>
  <joint name="k" type="revolute"><limit effort="1" velocity="1" lower="-1" upper="1"/></joint>
  <transmission name="t" type="transmission_interface/SimpleTransmission">
    <joint name="j"><hardwareInterface>EffortJointInterface</hardwareInterface></joint>
    <actuator name="m"><mechanicalReduction>50</mechanicalReduction></actuator>
  </transmission>
  <transmission name="t2">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="k"/>
    <actuator name="m2"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface><mechanicalReduction>50</mechanicalReduction></actuator>
  </transmission>
</robot>
"""
FIXED = """<robot name="r">
  <joint name="j" type="revolute"><limit effort="1" velocity="1" lower="-1" upper="1"/></joint>
  <joint name="k" type="revolute"><limit effort="1" velocity="1" lower="-1" upper="1"/></joint>
  <transmission name="t">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="j"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>
    <actuator name="m"><mechanicalReduction>50</mechanicalReduction></actuator>
  </transmission>
  <transmission name="t2">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="k">
      <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
    </joint>
    <actuator name="m2"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface><mechanicalReduction>50</mechanicalReduction></actuator>
  </transmission>
</robot>
"""
# Zero reduction: an error no fix touches.
UNFIXABLE = FIXED.replace("<mechanicalReduction>50<", "<mechanicalReduction>0<", 1)
OLD = 1_000_000_000  # an mtime long past, to see that a file was not rewritten


def run(*args: str, input: str | None = None) -> tuple[int, str, str]:
    result = CliRunner().invoke(cli, list(args), input=input)
    if result.exception and not isinstance(result.exception, SystemExit):
        raise result.exception
    return result.exit_code, result.stdout, result.stderr


@pytest.fixture
def robots(tmp_path, monkeypatch):
    """A folder with a robot --fix fixes and one whose only finding it cannot fix."""
    monkeypatch.chdir(tmp_path)
    monkeypatch.delenv("GITHUB_ACTIONS", raising=False)
    (tmp_path / "urdf").mkdir()
    for name, text in (("legacy.urdf", LEGACY), ("zero.urdf", UNFIXABLE)):
        (tmp_path / "urdf" / name).write_text(text)
        os.utime(tmp_path / "urdf" / name, (OLD, OLD))
    return tmp_path / "urdf"


def test_text_marks_the_fixable_findings_and_counts_them(robots):
    code, out, err = run("validate", "urdf/legacy.urdf")
    assert (code, err) == (1, "")
    marked = [line.split(": ", 2)[1] for line in out.splitlines()[:-1]]
    assert marked == ["warning TX302 [*] legacy-type-attribute", "warning TX300 [*] "
                      "unprefixed-interface", "error TX110 missing-interface",
                      "warning TX301 [*] interface-on-actuator"]
    assert out.splitlines()[-1] == (
        "Found 1 error, 3 warnings in 1 file; 3 fixable with `txtool validate --fix`.")
    code, out, _ = run("validate", "urdf/zero.urdf")
    assert code == 1 and "[*]" not in out and "fixable" not in out


def test_statistics_mark_the_rules_with_fixable_findings(robots):
    code, out, _ = run("validate", "--statistics", "urdf/legacy.urdf")
    assert (code, out) == (1, "1  TX110  error        missing-interface\n"
                              "1  TX300  warning  [*] unprefixed-interface\n"
                              "1  TX301  warning  [*] interface-on-actuator\n"
                              "1  TX302  warning  [*] legacy-type-attribute\n"
                              "Found 1 error, 3 warnings in 1 file; 3 fixable with "
                              "`txtool validate --fix`.\n")


def test_colored_text_marks_them_too(robots):
    code, out, _ = run("validate", "--color", "always", "urdf/legacy.urdf")
    assert code == 1 and out.count("[*]") == 3 and "\x1b[" in out


def test_diff_prints_what_fix_would_change_and_writes_nothing(robots):
    code, out, err = run("validate", "--diff", "urdf")
    assert code == 1
    assert out == run("migrate", "--diff", "urdf/legacy.urdf")[1]  # migrate's own diff
    assert out.startswith("--- a/urdf/legacy.urdf\n+++ b/urdf/legacy.urdf\n@@ ")
    assert "+    <type>transmission_interface/SimpleTransmission</type>\n" in out
    assert err.splitlines() == ["would change urdf/legacy.urdf (TX300 x1, TX301 x1, TX302 x1)",
                                "1 file(s) would be changed"]
    for path in robots.iterdir():
        assert path.stat().st_mtime == OLD
    assert (robots / "legacy.urdf").read_text() == LEGACY


def test_diff_of_a_walk_of_the_working_folder_names_files_without_dot(robots):
    code, out, err = run("validate", "--diff", ".")
    assert code == 1 and out.startswith("--- a/urdf/legacy.urdf\n+++ b/urdf/legacy.urdf\n")
    assert err.startswith("would change urdf/legacy.urdf ")
    code, _, err = run("validate", "--fix", ".")
    assert err == "txtool: fixed urdf/legacy.urdf (TX300 x1, TX301 x1, TX302 x1)\n"


def test_diff_wins_over_fix(robots):
    assert run("validate", "--fix", "--diff", "urdf") == run("validate", "--diff", "urdf")
    assert (robots / "legacy.urdf").read_text() == LEGACY


def test_diff_with_nothing_to_fix_exits_0(robots):
    assert run("validate", "--diff", "urdf/zero.urdf") == (0, "", "txtool: nothing to fix\n")


def test_fix_applies_migrates_fixes_then_reports_what_remains(robots):
    code, out, err = run("validate", "--fix", "urdf")
    assert (code, out) == (1, "urdf/zero.urdf:7:24: error TX106 zero-reduction: reduction of "
                              "actuator 'm' of transmission 't' is zero: ros_control refuses it "
                              "(\"Transmission reduction ratio cannot be zero\")\n"
                              "Found 1 error in 2 files.\n")
    assert err == "txtool: fixed urdf/legacy.urdf (TX300 x1, TX301 x1, TX302 x1)\n"
    assert (robots / "legacy.urdf").read_text() == FIXED
    assert (robots / "zero.urdf").stat().st_mtime == OLD  # not rewritten
    os.utime(robots / "legacy.urdf", (OLD, OLD))
    assert run("validate", "--fix", "urdf/legacy.urdf") == (0, "No problems in 1 file.\n", "")
    assert (robots / "legacy.urdf").stat().st_mtime == OLD  # a fixed point: nothing to write


def test_fix_that_cannot_write_fails_with_the_reason(robots):
    os.link(robots / "legacy.urdf", robots / "legacy-link.urdf")
    code, out, err = run("validate", "--fix", "urdf/legacy.urdf")
    assert code == 2 and out.count(" [*] ") == 3  # still there, still fixable
    assert err == ("txtool: urdf/legacy.urdf: has 2 hard links; replacing it would leave the "
                   "other names with the old text, so it is not written (copy the file to break "
                   "the link)\n")
    assert (robots / "legacy.urdf").read_text() == LEGACY


def test_fix_is_migrates_write(robots, tmp_path):
    """The bytes --fix writes are those migrate --write writes."""
    twin = tmp_path / "twin"
    twin.mkdir()
    (twin / "legacy.urdf").write_text(LEGACY)
    assert run("migrate", "--write", str(twin / "legacy.urdf"))[0] == 0
    assert run("validate", "--fix", "urdf/legacy.urdf")[0] == 0
    assert (robots / "legacy.urdf").read_bytes() == (twin / "legacy.urdf").read_bytes()


def test_fix_applies_only_the_selected_rules(robots):
    code, out, err = run("validate", "--fix", "--select", "TX302", "urdf/legacy.urdf")
    assert (code, out) == (0, "No problems in 1 file.\n")
    assert err == "txtool: fixed urdf/legacy.urdf (TX302 x1)\n"
    fixed = (robots / "legacy.urdf").read_text()
    assert "<type>transmission_interface/SimpleTransmission</type>" in fixed.split("t2")[0]
    assert "<hardwareInterface>EffortJointInterface<" in fixed  # TX300's, not selected


XACRO = """<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="iface" value="EffortJointInterface"/>
  <joint name="j" type="revolute"><limit effort="1" velocity="1" lower="-1" upper="1"/></joint>
  <transmission name="t">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="j"><hardwareInterface>${iface}</hardwareInterface></joint>
    <actuator name="m"><mechanicalReduction>50</mechanicalReduction></actuator>
  </transmission>
</robot>
"""


def test_a_finding_migrate_cannot_fix_as_written_is_not_marked(robots):
    """The expanded xacro lacks the prefix, but the file holds ${iface}: migrate (which never
    expands) has no name to prefix, so the finding is not fixable and --fix changes nothing."""
    (robots / "m.urdf.xacro").write_text(XACRO)
    code, out, _ = run("validate", "--format", "json", "urdf/m.urdf.xacro")
    assert code == 1
    assert [(p["code"], p["severity"], p["fixable"]) for p in json.loads(out)["problems"]] == [
        ("TX300", "error", False)]  # the refusal, said once (TX205's severity)
    code, out, err = run("validate", "--fix", "urdf/m.urdf.xacro")
    assert code == 1 and "[*]" not in out and "fixable" not in out and err == ""
    assert (robots / "m.urdf.xacro").read_text() == XACRO


def test_json_says_which_findings_are_fixable(robots):
    code, out, _ = run("validate", "--format", "json", "urdf/legacy.urdf")
    assert code == 1
    assert {p["code"]: p["fixable"] for p in json.loads(out)["problems"]} == {
        "TX302": True, "TX300": True, "TX110": False, "TX301": True}


@pytest.mark.parametrize(("args", "message"), [
    (["--fix", "-"], "--fix rewrites files in place; standard input ('-') cannot be fixed"),
    (["--diff", "-"], "--diff rewrites files in place; standard input ('-') cannot be fixed"),
    (["--diff", "--format", "json", "x.urdf"], "--diff prints a diff: it takes no --format"),
    (["--diff", "-q", "x.urdf"], "--diff prints a diff: it takes no --format"),
    (["--format", "text", "--format", "json", "x.urdf"], "give one, not 2"),
    (["--format", "json:a.json", "--format", "sarif:a.json", "x.urdf"],
     "two reports named the same file"),
    (["--format", "json:a.json", "-o", "./a.json", "x.urdf"], "two reports named the same file"),
    (["--format", "sarif:", "x.urdf"], "'sarif:': no file name after ':'"),
    (["--format", "xml:a.xml", "x.urdf"], "'xml' is not one of"),
    (["--format", "json", "--statistics", "x.urdf"], "go with --format text or concise, not json"),
])
def test_usage_errors(robots, args, message):
    code, out, err = run("validate", *args, input=LEGACY)
    assert (code, out) == (2, "") and message in err
    assert not list(Path().glob("a.*"))


def test_several_reports_from_one_run(robots):
    (robots.parent / "out").mkdir()
    code, out, err = run("validate", "--format", "json:out/report.json", "--format",
                         "sarif:out/my report.sarif", "-q", "urdf")
    assert (code, err) == (1, "")
    assert out.count("\n") == 5 and "Found" not in out  # text, -q, on stdout: the default
    report = json.loads((robots.parent / "out" / "report.json").read_text())
    log = json.loads((robots.parent / "out" / "my report.sarif").read_text())
    assert len(report["problems"]) == len(log["runs"][0]["results"]) == 5
    code, out, _ = run("validate", "--format", "github", "--format", "json:out/again.json",
                       "urdf")
    assert code == 1 and out.startswith("::")
    assert json.loads((robots.parent / "out" / "again.json").read_text()) == report


def test_a_report_that_cannot_be_written_fails_the_run_after_the_others(robots):
    (robots.parent / "taken").write_text("a file where the report's folder should be")
    code, out, err = run("validate", "--format", "sarif:taken/r.sarif", "--format",
                         "json:r.json", "urdf")
    assert code == 2
    assert out.splitlines()[-1].startswith("Found ")  # the text report is printed
    assert "taken/r.sarif" in err and "r.json" not in err
    assert json.loads((robots.parent / "r.json").read_text())["problems"]


def apply(text: str, replacements: list[dict]) -> str:
    """A SARIF fix's replacements applied to ``text`` (by their character spans)."""
    for change in sorted(replacements, key=lambda r: -r["deletedRegion"]["charOffset"]):
        region = change["deletedRegion"]
        start = region["charOffset"]
        text = text[:start] + change["insertedContent"]["text"] + text[start + region["charLength"]:]
    return text


def position(text: str, offset: int) -> tuple[int, int]:
    before = text[:offset]
    return before.count("\n") + 1, offset - (before.rfind("\n") + 1) + 1


def test_sarif_fixes_validate_and_give_what_fix_writes(robots):
    code, out, _ = run("validate", "--format", "sarif", "urdf")
    assert code == 1
    log = json.loads(out)
    jsonschema.Draft4Validator(sarif_schema()).validate(log)
    results = log["runs"][0]["results"]
    with_fixes = {r["ruleId"] for r in results if "fixes" in r}
    assert with_fixes == {"TX300", "TX301", "TX302"}
    replacements = {json.dumps(change, sort_keys=True): change
                    for r in results for fix in r.get("fixes", ())
                    for artifact in fix["artifactChanges"] for change in artifact["replacements"]}
    for change in replacements.values():
        region = change["deletedRegion"]
        assert position(LEGACY, region["charOffset"]) == (region["startLine"],
                                                          region["startColumn"])
        assert position(LEGACY, region["charOffset"] + region["charLength"]) == (
            region["endLine"], region["endColumn"])
    assert apply(LEGACY, list(replacements.values())) == FIXED
    tx301 = next(r for r in results if r["ruleId"] == "TX301")
    [change] = tx301["fixes"][0]["artifactChanges"][0]["replacements"]
    assert change["deletedRegion"]["startLine"] == 10  # its own lines, not the whole file


def test_edits_at_the_ends_of_a_file():
    assert edits_between("", "") == ()
    [insert] = edits_between("a\n", "a\nb")  # added after the last line
    assert insert == Edit((2, 1), (2, 1), 2, 0, "b", (1, 2))
    [tail] = edits_between("a\r\nb", "a\r\nc")  # a last line with no line ending
    assert tail == Edit((2, 1), (2, 2), 3, 1, "c", (2, 2))
    [gone] = edits_between("a\rb\rc\r", "a\rc\r")  # old Mac line endings
    assert gone == Edit((2, 1), (3, 1), 2, 2, "", (2, 2))
    [first] = edits_between("a\n", "z\na\n")
    assert first.lines == (1, 1) and first.touches(1, 1) and not first.touches(2, 3)


def test_edits_for_a_finding_away_from_every_change_are_all_of_them():
    edits = edits_between("a\nb\nc\nd\n", "A\nb\nc\nD\n")
    assert edits_for(edits, 1, 1) == edits[:1]
    assert edits_for(edits, 2, 3) == edits  # none touches lines 2-3


def test_fix_on_real_corpus_files(tmp_path, monkeypatch):
    """Copies of real robots with fixable findings: --fix writes migrate's result, and
    validating that finds nothing fixable left and nothing new."""
    monkeypatch.chdir(tmp_path)
    names = ["baxter__baxter.urdf", "husky__husky.urdf", "gazebo_ros_demos__rrbot_2013_hydro.xacro",
             "ros2_control_test_assets__minimal_robot_transmissions.urdf"]
    for name in names:
        shutil.copyfile(corpus_file(name), tmp_path / name)
    code, before, _ = run("validate", "--format", "json", *names)
    before_problems = json.loads(before)["problems"]
    fixable = [p for p in before_problems if p["fixable"]]
    assert {p["path"] for p in fixable} == set(names)
    twin = tmp_path / "twin"
    twin.mkdir()
    for name in names:
        shutil.copyfile(corpus_file(name), twin / name)
    assert run("migrate", "--write", *(str(twin / n) for n in names))[0] == 0
    code, _, err = run("validate", "--fix", *names)
    assert len(err.splitlines()) == len(names) and all(
        line.startswith("txtool: fixed ") for line in err.splitlines())
    for name in names:
        assert (tmp_path / name).read_bytes() == (twin / name).read_bytes()
        assert (tmp_path / name).read_bytes() != corpus_file(name).read_bytes()
    code, after, _ = run("validate", "--format", "json", *names)
    after_problems = json.loads(after)["problems"]
    assert not [p for p in after_problems if p["fixable"]]
    key = lambda p: (p["path"], p["code"], p["message"])  # noqa: E731
    assert {key(p) for p in after_problems} <= {key(p) for p in before_problems}


def test_diff_tells_a_configuration_note_once(robots):
    (robots.parent / ".git").mkdir()
    (robots / ".txtool.toml").write_text('ignore = ["ALL"]\n')
    code, out, err = run("validate", "--diff", "urdf/legacy.urdf")
    assert code == 1 and out.startswith("--- a/urdf/legacy.urdf")
    notes = [line for line in err.splitlines() if line.startswith("txtool: note: ")]
    assert len(notes) == 1 and "not read" in notes[0]
