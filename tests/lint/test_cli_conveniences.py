"""What users expect of a CLI: suggestions, colour switches, quiet/statistics/output-file, and
saying so when a named file holds nothing to check."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from click.testing import CliRunner

from tests.lint.conftest import BROKEN, CLEAN
from txtool.cli import cli

ESC = "\x1b["
FIXTURES = Path(__file__).resolve().parents[2] / "fixtures"


def invoke(*args: str, env: dict[str, str] | None = None) -> tuple[int, str, str]:
    result = CliRunner().invoke(cli, list(args), env=env)
    if result.exception and not isinstance(result.exception, SystemExit):
        raise result.exception
    return result.exit_code, result.stdout, result.stderr


@pytest.fixture
def broken(tmp_path) -> Path:
    path = tmp_path / "robot.urdf"
    path.write_text(BROKEN)
    return path


def test_a_mistyped_command_gets_a_suggestion():
    code, out, err = invoke("valdate", "x.urdf")
    assert (code, out) == (2, "")
    assert "No such command 'valdate'. Did you mean 'validate'?" in err


def test_an_unrelated_word_gets_no_suggestion():
    code, _, err = invoke("frobnicate")
    assert code == 2 and "No such command 'frobnicate'." in err and "Did you mean" not in err


@pytest.mark.parametrize("command", ["show", "roundtrip"])
def test_color_on_commands_that_colour(command):
    robot = str(FIXTURES / "demo_robot.urdf")
    code, out, _ = invoke(command, robot, "--color", "always")
    assert code == 0 and ESC in out
    code, out, _ = invoke(command, robot, "--color", "never", env={"FORCE_COLOR": "1"})
    assert code == 0 and ESC not in out
    code, out, _ = invoke(command, robot, env={"FORCE_COLOR": "1", "NO_COLOR": ""})
    assert code == 0 and ESC in out  # FORCE_COLOR colours a pipe
    code, out, _ = invoke(command, robot)
    assert code == 0 and ESC not in out  # a pipe, by default


def test_color_option_leaves_the_environment_as_it_was(monkeypatch):
    import os

    monkeypatch.delenv("FORCE_COLOR", raising=False)
    monkeypatch.setenv("NO_COLOR", "keep")
    monkeypatch.setenv("TERM", "xterm")
    for mode in ("always", "never"):
        invoke("show", str(FIXTURES / "demo_robot.urdf"), "--color", mode)
        assert os.environ.get("NO_COLOR") == "keep" and "FORCE_COLOR" not in os.environ
        assert os.environ["TERM"] == "xterm"


def test_validate_honours_force_color_and_no_color(broken):
    _, out, _ = invoke("validate", str(broken), env={"FORCE_COLOR": "1", "NO_COLOR": ""})
    assert ESC in out
    _, out, _ = invoke("validate", str(broken), env={"FORCE_COLOR": "1", "NO_COLOR": "1"})
    assert ESC not in out


def test_quiet_prints_the_findings_only(broken):
    code, out, err = invoke("validate", "-q", str(broken))
    assert (code, err) == (1, "")
    lines = out.splitlines()
    assert lines and all(line.startswith(f"{broken}:") for line in lines)
    code, out, _ = invoke("validate", "-q", str(broken).replace("robot", "x"))
    assert code == 2


def test_quiet_on_a_clean_file_prints_nothing(tmp_path):
    path = tmp_path / "clean.urdf"
    path.write_text(CLEAN)
    assert invoke("validate", "--quiet", str(path)) == (0, "", "")


def test_statistics_count_the_findings_per_rule(broken):
    code, out, _ = invoke("validate", "--statistics", str(broken))
    assert code == 1
    rows = out.splitlines()
    assert rows[-1].startswith("Found ")
    counted = {row.split()[1]: int(row.split()[0]) for row in rows[:-1]}
    _, listed, _ = invoke("validate", "-q", str(broken))
    codes = [line.split()[2] for line in listed.splitlines()]
    assert counted == {code: codes.count(code) for code in set(codes)}


def test_statistics_and_quiet_are_for_the_text_format(broken):
    code, out, err = invoke("validate", "--statistics", "--format", "json", str(broken))
    assert (code, out) == (2, "")
    assert "--quiet and --statistics go with --format text or concise, not json" in err


def test_output_file_receives_the_report(broken, tmp_path):
    target = tmp_path / "report.json"
    code, out, err = invoke("validate", "--format", "json", "-o", str(target), str(broken))
    assert (code, out, err) == (1, "", "")
    assert json.loads(target.read_text())["summary"]["errors"] >= 1
    code, out, _ = invoke("validate", "--output-file", str(tmp_path / "r.txt"), str(broken),
                          env={"NO_COLOR": "", "FORCE_COLOR": ""})
    assert (code, out) == (1, "")
    assert ESC not in (tmp_path / "r.txt").read_text()  # a file is not a terminal


def test_a_named_file_without_transmissions_says_so(tmp_path):
    path = tmp_path / "links.urdf"
    path.write_text('<robot name="r"><link name="base"/></robot>\n')
    code, out, _ = invoke("validate", str(path))
    assert code == 0
    assert out.splitlines() == [
        f"{path}:1:1: info TX006 no-transmission: no <transmission> in this file: "
        "nothing to check",
        "Found 1 info in 1 file."]


def test_a_folder_walk_does_not_report_fragments_without_transmissions(tmp_path):
    (tmp_path / "links.urdf").write_text('<robot name="r"><link name="base"/></robot>\n')
    (tmp_path / "robot.urdf").write_text(CLEAN)
    code, out, _ = invoke("validate", str(tmp_path))
    assert (code, out) == (0, "No problems in 2 files.\n")


def test_a_config_file_with_a_tool_txtool_table_is_explained(tmp_path, broken):
    config = tmp_path / "lint.toml"
    config.write_text('[tool.txtool]\nselect = ["TX1"]\n')
    code, out, err = invoke("validate", "--config", str(config), str(broken))
    assert (code, out) == (2, "")
    assert err == (f"txtool: {config}: key 'tool.txtool': this file takes txtool's keys at its "
                   "top level, as .txtool.toml does; [tool.txtool] is read only from a file "
                   "named pyproject.toml\n")


def test_every_help_page_carries_examples_that_use_real_options():
    import shlex

    from txtool.cli import COMMAND_MODULES, EXAMPLES

    assert set(EXAMPLES) == set(COMMAND_MODULES)
    for name in COMMAND_MODULES:
        code, out, _ = invoke(name, "--help")
        assert code == 0 and "Examples:\n" in out and f"  $ txtool {name}" in out, name
        command = cli.get_command(None, name)
        known = {opt for param in command.params for opt in (*param.opts, *param.secondary_opts)}
        for example in EXAMPLES[name]:
            words = shlex.split(example.split("  #")[0].split(" < ")[0])
            assert words[:2] == ["txtool", name], example
            unknown = [w for w in words if w.startswith("-") and w != "-" and w not in known]
            assert unknown == [], (example, unknown)


def test_convert_of_a_file_without_transmissions_says_so(tmp_path):
    path = tmp_path / "links.urdf"
    text = '<robot name="r"><link name="base"/></robot>\n'
    path.write_text(text)
    code, out, err = invoke("convert", str(path), "--to", "ros2-p2")
    assert (code, out) == (0, text)
    assert err == (f"txtool: {path}: 0 transmissions converted (the document has no "
                   "transmission)\n")
