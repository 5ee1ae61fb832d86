"""``validate --strict``: warnings fail (exit 1) in every format and however files are shared."""

from __future__ import annotations

import json

import pytest

from tests.lint.conftest import CLEAN, WARNING_ONLY

WARNING = "warning TX102 unknown-type"


@pytest.fixture
def warned(tmp_path):
    path = tmp_path / "robot.urdf"
    path.write_text(WARNING_ONLY)
    return path


@pytest.mark.parametrize("output_format", ["text", "json", "github", "sarif"])
def test_strict_fails_on_a_warning_in_every_format(validate, warned, output_format):
    code, out, err = validate("--format", output_format, str(warned))
    assert (code, err) == (0, "")
    strict_code, strict_out, err = validate("--strict", "--format", output_format, str(warned))
    assert (strict_code, err) == (1, "")
    assert strict_out == out  # the report is the same; only the verdict changes
    assert "TX102" in out


def test_strict_json_report_lists_only_the_warning(validate, warned):
    code, out, _ = validate("--strict", "--format", "json", str(warned))
    assert code == 1
    assert [(p["code"], p["severity"]) for p in json.loads(out)["problems"]] == [
        ("TX102", "warning")]


def test_strict_fails_when_one_of_many_files_warns(validate, tmp_path, warned):
    for index in range(40):  # enough files to share them among processes
        (tmp_path / f"clean_{index:02d}.urdf").write_text(CLEAN)
    for jobs in ("1", "2"):
        code, out, _ = validate("--strict", "--jobs", jobs, str(tmp_path))
        assert code == 1, jobs
        assert out.count(WARNING) == 1 and "robot.urdf:" in out


def test_strict_with_exit_zero_still_exits_0(validate, warned):
    code, out, _ = validate("--strict", "--exit-zero", str(warned))
    assert code == 0 and WARNING in out


def test_strict_passes_a_clean_file(validate, tmp_path):
    path = tmp_path / "robot.urdf"
    path.write_text(CLEAN)
    assert validate("--strict", str(path)) == (0, "No problems in 1 file.\n", "")
