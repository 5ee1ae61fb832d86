"""txtool in ``colcon test`` (docs/colcon.md): the JUnit report, and colcon itself running the
documented ament_python test and reading the documented ament_cmake test's result file."""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from click.testing import CliRunner
from lxml import etree

from txtool.cli import cli
from txtool.lint.problem import InputFailure, Problem
from txtool.reporters import Summary, render

ROOT = Path(__file__).resolve().parents[2]
COLCON = shutil.which("colcon", path=str(Path(sys.executable).parent)) or shutil.which("colcon")
needs_colcon = pytest.mark.skipif(COLCON is None, reason="colcon is not installed (extra 'test')")

ERROR = Problem("urdf/arm.urdf", 42, 7, "TX106", "reduction is zero", severity="error",
                name="zero-reduction")
WARNING = Problem("urdf/arm.urdf", 58, 7, "TX300", "no prefix", severity="warning",
                  name="unprefixed-interface")


def junit(problems, failures=(), failing=("error",)):
    summary = Summary.of(problems, 2, failures=failures, failing=failing)
    return etree.fromstring(render("junit", problems, summary).encode())


def cases(suite):
    return [(c.get("classname"), c.get("name"), [child.tag for child in c]) for c in suite]


def test_errors_fail_warnings_pass_with_their_line():
    suite = junit([ERROR, WARNING])
    assert (suite.get("tests"), suite.get("failures"), suite.get("errors")) == ("2", "1", "0")
    assert cases(suite) == [("txtool.urdf.arm_urdf", "TX106 zero-reduction 42:7", ["failure"]),
                            ("txtool.urdf.arm_urdf", "TX300 unprefixed-interface 58:7", ["system-out"])]
    assert suite[1][0].text == ("urdf/arm.urdf:58:7: warning TX300 unprefixed-interface: "
                                "no prefix")


def test_strict_fails_warnings_too_and_unreadable_files_are_errors():
    suite = junit([WARNING], [InputFailure("gone.urdf", "gone.urdf: no such file")],
                  failing=("error", "warning"))
    assert (suite.get("tests"), suite.get("failures"), suite.get("errors")) == ("2", "1", "1")
    assert cases(suite)[1] == ("txtool.gone_urdf", "read", ["error"])


def test_a_clean_run_is_one_passed_case():
    assert cases(junit([])) == [("txtool", "no problems", [])]


def test_control_characters_in_a_message_stay_valid_xml():
    odd = Problem("a\x1b.urdf", 1, 1, "TX100", "name '\x00\x07'", name="missing-name")
    suite = junit([odd])
    assert "\\x1b" in suite[0].get("classname") and "\\x07" in suite[0][0].text


def test_validate_writes_the_junit_file_and_exits_as_always(tmp_path):
    out = tmp_path / "txtool.xunit.xml"
    broken = str(ROOT / "fixtures" / "broken_robot.urdf")
    result = CliRunner().invoke(cli, ["validate", broken, "--format", "junit",
                                      "--output", str(out)])
    assert (result.exit_code, result.output) == (1, "")
    suite = etree.parse(str(out)).getroot()
    assert (suite.get("tests"), suite.get("failures")) == ("4", "4")
    assert [c.get("name").split()[0] for c in suite] == ["TX303", "TX105", "TX113", "TX200"]


def _package(root: Path, name: str, urdf: Path) -> Path:
    """An ament_python package holding ``urdf`` and the test file docs/colcon.md shows."""
    package = root / "src" / name
    (package / "urdf").mkdir(parents=True)
    (package / "test").mkdir()
    (package / "resource").mkdir()
    (package / "resource" / name).write_text("")
    (package / name).mkdir()
    (package / name / "__init__.py").write_text("")
    shutil.copy(urdf, package / "urdf" / "robot.urdf")
    (package / "package.xml").write_text(f"""<?xml version="1.0"?>
<package format="3">
  <name>{name}</name><version>0.0.1</version><description>d</description>
  <maintainer email="m@example.com">m</maintainer><license>Apache-2.0</license>
  <test_depend>python3-pytest</test_depend>
  <export><build_type>ament_python</build_type></export>
</package>
""")
    (package / "setup.py").write_text(f"""from setuptools import setup
setup(name={name!r}, version="0.0.1", packages=[{name!r}], extras_require={{"test": ["pytest"]}},
      data_files=[("share/ament_index/resource_index/packages", ["resource/{name}"]),
                  ("share/{name}", ["package.xml"])])
""")
    documented = (ROOT / "docs" / "colcon.md").read_text()
    test_file = re.search(r"```python\n# test/test_txtool.py\n(.*?)```", documented, re.S)
    (package / "test" / "test_txtool.py").write_text(test_file.group(1))
    return package


def _colcon(*args: str, cwd: Path) -> subprocess.CompletedProcess[str]:
    env = {k: v for k, v in os.environ.items() if not k.startswith(("TXTOOL_", "COLCON_"))}
    env["PATH"] = os.pathsep.join([str(Path(sys.executable).parent), env.get("PATH", "")])
    return subprocess.run([COLCON, *args], cwd=cwd, env=env, capture_output=True, text=True,
                          timeout=300)


@needs_colcon
def test_colcon_test_runs_the_documented_ament_python_test(tmp_path):
    _package(tmp_path, "good_description", ROOT / "fixtures" / "demo_robot.urdf")
    _package(tmp_path, "bad_description", ROOT / "fixtures" / "broken_robot.urdf")
    assert _colcon("build", cwd=tmp_path).returncode == 0
    _colcon("test", cwd=tmp_path)
    report = _colcon("test-result", "--verbose", cwd=tmp_path)
    assert report.returncode == 1
    assert "build/bad_description/pytest.xml: 1 test, 0 errors, 1 failure" in report.stdout
    assert "good_description" not in report.stdout  # it passed: --verbose lists failures only
    assert report.stdout.endswith("Summary: 2 tests, 0 errors, 1 failure, 0 skipped\n")
    assert "urdf/robot.urdf:37:9: error TX303 wrong-dialect-tag" in report.stdout


@needs_colcon
def test_colcon_test_result_reads_the_ament_cmake_result_file(tmp_path):
    results = tmp_path / "build" / "arm_description" / "test_results" / "arm_description"
    results.mkdir(parents=True)
    broken = str(ROOT / "fixtures" / "broken_robot.urdf")
    CliRunner().invoke(cli, ["validate", broken, "--format", "junit",
                             "--output", str(results / "txtool.xunit.xml")])
    report = _colcon("test-result", "--verbose", "--test-result-base", "build", cwd=tmp_path)
    assert report.returncode == 1
    assert "txtool.xunit.xml: 4 tests, 0 errors, 4 failures, 0 skipped" in report.stdout
    assert "TX113 unknown-standard-type 50:7" in report.stdout


def test_a_class_name_holds_no_dot_of_a_file_name_and_no_dot_folder():
    """JUnit readers take a class name's dots for packages: robot.urdf is no package."""
    walked = Problem("./urdf/robot.urdf.xacro", 3, 5, "TX106", "zero", name="zero-reduction")
    suite = junit([walked])
    assert cases(suite) == [("txtool.urdf.robot_urdf_xacro", "TX106 zero-reduction 3:5",
                             ["failure"])]
    assert suite[0][0].text == "urdf/robot.urdf.xacro:3:5: error TX106 zero-reduction: zero"
