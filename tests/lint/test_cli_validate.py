"""``txtool validate`` as a user runs it: exit codes and output asserted together."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from tests.lint.conftest import BROKEN, CLEAN, WARNING_ONLY

TX106_LINE = (
    "robot.urdf:6:24: error TX106 zero-reduction: reduction of actuator 'm' of transmission "
    "'t' is zero: ros_control refuses it (\"Transmission reduction ratio cannot be zero\")"
)


def write(folder, name, text):
    path = folder / name
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text)
    return path


def test_findings_exit_1_with_text_lines_and_a_summary(validate, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    write(tmp_path, "robot.urdf", BROKEN)
    code, out, err = validate("robot.urdf")
    lines = out.splitlines()
    assert code == 1 and err == ""
    assert lines[0] == TX106_LINE
    assert lines[1].startswith("robot.urdf:9:5: warning TX102 unknown-type: ")
    assert lines[-1] == "Found 1 error, 1 warning in 1 file."


def test_clean_file_exits_0(validate, tmp_path):
    path = write(tmp_path, "robot.urdf", CLEAN)
    assert validate(str(path)) == (0, "No problems in 1 file.\n", "")


def test_warnings_fail_only_with_strict(validate, tmp_path):
    path = write(tmp_path, "robot.urdf", WARNING_ONLY)
    assert validate(str(path))[0] == 0
    code, out, _ = validate("--strict", str(path))
    assert code == 1 and "TX102" in out


def test_exit_zero(validate, tmp_path):
    path = write(tmp_path, "robot.urdf", BROKEN)
    code, out, _ = validate("--exit-zero", str(path))
    assert code == 0 and "TX106" in out


def test_infos_never_fail(validate, tmp_path):
    text = CLEAN.replace("<robot", "<!-- txtool: disable-file TX105 -->\n<robot")
    path = write(tmp_path, "robot.urdf", text)
    code, out, _ = validate("--strict", str(path))
    assert code == 0 and "info TX003 unused-suppression" in out


def test_select_and_ignore(validate, tmp_path):
    path = write(tmp_path, "robot.urdf", BROKEN)
    code, out, _ = validate("--select", "TX102", str(path))
    assert code == 0 and "TX102" in out and "TX106" not in out
    code, out, _ = validate("--ignore", "TX106,TX102", str(path))
    assert (code, out) == (0, "No problems in 1 file.\n")
    code, out, _ = validate("--select", "TX1", "--ignore", "TX102", str(path))
    assert code == 1 and "TX106" in out and "TX102" not in out


def test_unknown_code_is_a_usage_error(validate, tmp_path):
    path = write(tmp_path, "robot.urdf", CLEAN)
    assert validate("--select", "TX999", str(path)) == (
        2, "", "txtool: option '--select': unknown rule code 'TX999'\n"
    )


def test_missing_file_is_exit_2_and_other_files_are_still_checked(validate, tmp_path):
    path = write(tmp_path, "robot.urdf", BROKEN)
    code, out, err = validate(str(tmp_path / "nope.urdf"), str(path))
    assert code == 2
    assert err == f"txtool: {tmp_path / 'nope.urdf'}: no such file\n"
    assert "TX106" in out and out.endswith("in 1 file; 1 file could not be read.\n")


def test_bad_option_is_exit_2(validate, tmp_path):
    code, _, err = validate("--format", "yaml", str(tmp_path))
    assert code == 2 and "Invalid value for '--format'" in err


def test_malformed_xml_is_a_finding_not_a_crash(validate, tmp_path):
    path = write(tmp_path, "robot.urdf", "<robot>\n  <transmission>\n</robot>\n")
    code, out, err = validate(str(path))
    assert code == 1 and err == ""
    assert f"{path}:3:9: error TX001 xml-syntax: Opening and ending tag mismatch" in out


def test_directories_are_searched_for_robot_files(validate, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    write(tmp_path, "pkg/urdf/a.urdf", BROKEN)
    write(tmp_path, "pkg/urdf/b.urdf.xacro", CLEAN)
    write(tmp_path, "pkg/config/robot.xml", BROKEN)
    write(tmp_path, "pkg/config/other.xml", "<launch/>")
    write(tmp_path, "pkg/.hidden/c.urdf", BROKEN)
    write(tmp_path, "pkg/notes.txt", BROKEN)
    code, out, _ = validate("--format", "json", "pkg")
    report = json.loads(out)
    assert code == 1
    assert sorted({p["path"] for p in report["problems"]}) == [
        "pkg/config/robot.xml", "pkg/urdf/a.urdf"
    ]
    assert report["summary"] == {"files": 3, "errors": 2, "warnings": 2, "infos": 0,
                                 "not_expanded": 0}


def test_stdin_with_a_filename(validate, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    code, out, _ = validate("--stdin-filename", "robot.urdf", "-", input=BROKEN)
    assert code == 1 and out.splitlines()[0] == TX106_LINE


def test_stdin_xacro_is_checked_as_written(validate):
    xacro = BROKEN.replace(">0<", ">${r}<").replace("<robot", '<robot xmlns:xacro="x"')
    code, out, _ = validate("--stdin-filename", "r.urdf.xacro", "--select", "TX106", "-",
                            input=xacro)
    assert (code, out) == (0, "No problems in 1 file.\n")


def test_github_format_is_chosen_under_github_actions(validate, tmp_path, monkeypatch):
    path = write(tmp_path, "robot.urdf", BROKEN)
    monkeypatch.setenv("GITHUB_ACTIONS", "true")
    code, out, _ = validate("--select", "TX106", str(path))
    assert code == 1
    assert out.startswith(f"::error file={path},line=6,col=24,endLine=6,endColumn=45,"
                          "title=TX106 zero-reduction::reduction of actuator 'm'")


@pytest.mark.parametrize(
    ("args", "env", "colored"),
    [
        ((), {}, False),  # not a terminal
        (("--color", "always"), {}, True),
        (("--color", "always"), {"NO_COLOR": "1"}, True),
        (("--color", "never"), {}, False),
    ],
)
def test_color(validate, tmp_path, monkeypatch, args, env, colored):
    for key, value in env.items():
        monkeypatch.setenv(key, value)
    path = write(tmp_path, "robot.urdf", BROKEN)
    code, out, _ = validate(*args, str(path))
    assert code == 1 and ("\x1b[" in out) is colored
    assert "TX106" in out


def test_auto_color_honours_no_color(monkeypatch):
    from txtool.commands import validate as module

    monkeypatch.setattr("sys.stdout.isatty", lambda: True)
    monkeypatch.delenv("NO_COLOR", raising=False)
    monkeypatch.delenv("TERM", raising=False)
    assert module.use_color("auto") is True
    monkeypatch.setenv("NO_COLOR", "1")
    assert module.use_color("auto") is False


def test_a_folder_with_nothing_to_check_is_an_input_error_not_a_pass(validate, tmp_path):
    (tmp_path / "robot.urdf").mkdir()  # a folder named like a file
    write(tmp_path / "docs", "notes.txt", "no robot here")
    for folder in ("robot.urdf", "docs"):
        code, out, err = validate(str(tmp_path / folder))
        assert (code, out) == (2, "")
        assert err == (f"txtool: {tmp_path / folder}: no .urdf, .xacro or robot .xml file to "
                       "check in this folder (or its subfolders, leaving out ignored and "
                       "excluded ones)\n")


def test_tx305_names_the_configuration_by_its_file_name_and_offers_migrate(validate, tmp_path):
    """The configuration's folder was repeated on every finding, filling the line."""
    config = tmp_path / "settings" / "txtool.toml"
    config.parent.mkdir()
    config.write_text('ros-distro = "jazzy"\n')
    robot = tmp_path / "robot.urdf"
    robot.write_text(CLEAN)
    code, out, _ = validate("--config", str(config), str(robot))
    assert code == 0
    assert out == (
        f"{robot}:2:3: info TX305 unread-transmission: ROS 1 transmission 't' stands outside "
        "every <ros2_control> block, where none of this file's readers looks (ros2_control "
        "(jazzy): ros-distro jazzy in txtool.toml): nothing reads it; txtool migrate --write "
        "--to ros2-p2 moves it into a <ros2_control> block\nFound 1 info in 1 file.\n")


def test_a_walk_of_the_working_folder_names_files_without_dot_slash(validate, tmp_path,
                                                                     monkeypatch):
    (tmp_path / "urdf").mkdir()
    (tmp_path / "urdf" / "robot.urdf").write_text(BROKEN)
    monkeypatch.chdir(tmp_path)
    code, out, _ = validate("--format", "concise", ".")
    assert code == 1
    assert out.splitlines()[0] == ("urdf/robot.urdf:6:24: TX106 reduction of actuator 'm' of "
                                   "transmission 't' is zero")
    code, out, _ = validate("--format", "concise", "./urdf")  # a walk of any folder
    assert code == 1 and out.startswith("urdf/robot.urdf:6:24: TX106 ")


def test_a_report_into_a_folder_that_does_not_exist_makes_the_folder(validate, tmp_path,
                                                                     monkeypatch):
    """As the Action's ``sarif-file: out/txtool.sarif``; a file where a folder must be is
    one line and exit 2."""
    monkeypatch.chdir(tmp_path)
    Path("robot.urdf").write_text(BROKEN)
    code, out, err = validate("-o", "out/deep/report.sarif", "--format", "sarif",
                              "--format", "json:other/report.json", "robot.urdf")
    assert (code, out, err) == (1, "", "")
    assert json.loads(Path("out/deep/report.sarif").read_text())["version"] == "2.1.0"
    assert json.loads(Path("other/report.json").read_text())["summary"]["errors"] == 1
    Path("taken").write_text("a file")
    code, out, err = validate("-o", "taken/report.json", "--format", "json", "robot.urdf")
    assert code == 2 and out == ""
    assert err.startswith("txtool: taken/report.json: cannot write: ") and err.count("\n") == 1
