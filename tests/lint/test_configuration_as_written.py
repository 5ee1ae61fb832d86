"""Configuration values as users write them: a reader's name in any case and with spaces
around it, and per-file patterns, which match files by their path: standard input has none
unless --stdin-filename gives it one."""

from __future__ import annotations

from tests.lint.test_validate_fix import LEGACY

IGNORE_ALL = '[per-file-ignores]\n"*" = ["TX110", "TX300", "TX301", "TX302"]\n'


def test_a_reader_is_named_in_any_case(validate, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / ".txtool.toml").write_text('readers = [" ROS2_Control "]\n')
    (tmp_path / "r.urdf").write_text(LEGACY)
    code, out, err = validate("r.urdf")
    assert (code, err) == (0, "")
    assert out.splitlines()[0].startswith("r.urdf:4:3: info TX305 unread-transmission")


def test_per_file_patterns_reach_standard_input_only_by_the_name_it_is_given(
        validate, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / ".txtool.toml").write_text(IGNORE_ALL)
    code, out, _ = validate("-", input=LEGACY)
    assert code == 1 and out.splitlines()[-1].startswith("Found 1 error, 3 warnings in 1 file")
    assert validate("--stdin-filename", "r.urdf", "-", input=LEGACY)[:2] == (
        0, "No problems in 1 file.\n")
