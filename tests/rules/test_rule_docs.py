"""Every rule's documentation has one layout, and its examples do what they say.

The layout (txtool/lint/ruledoc.py, docs/contributing.md): what it does, why it matters, the
loader and its source, a failing example with the finding ``txtool validate`` prints for it, a
passing example, the fix. Each example is a whole document, run through the whole pipeline as
``txtool validate`` runs it: the failing one must give the expected finding (line, column,
severity, code and message), the passing one no finding of the rule.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

import pytest

from txtool.lint.api import LintOptions, lint_paths
from txtool.lint.config import Config, resolve
from txtool.lint.engine import lint_file
from txtool.lint.ruledoc import Finding, expected_finding, layout_problems, sections
from txtool.rules import all_rules

ROOT = Path(__file__).resolve().parents[2]

RULES = sorted(all_rules())


@pytest.mark.parametrize("code", RULES)
def test_the_documentation_has_the_layout(code):
    assert layout_problems(code, all_rules()[code].doc) == []


PACKAGE = """<?xml version="1.0"?>
<package format="3">
  <name>example_description</name>
  <version>1.0.0</version>
  <description>example</description>
  <maintainer email="m@example.com">m</maintainer>
  <license>BSD</license>
  <buildtool_depend>{build}</buildtool_depend>
  <export><build_type>{build}</build_type></export>
</package>
"""


def findings(section, robot=None, launch=None) -> list[Finding]:
    """The findings of ``txtool validate FILE`` for an example (a file named on the command
    line), with the default configuration; a message names the example's other files from
    its folder. A heading ``(BUILD
    package, PATH)`` writes the example to PATH in a package whose package.xml builds with
    BUILD (``ament_cmake``, ``catkin``). With a ``robot`` section (a rule about controllers),
    the example is a controller file: ``txtool validate ROBOT --controllers EXAMPLE``; a
    ``launch`` section is written beside them."""
    with tempfile.TemporaryDirectory(prefix="txtool-rule-doc-") as folder:
        if launch is not None:
            (Path(folder) / launch.filename).parent.mkdir(parents=True, exist_ok=True)
            (Path(folder) / launch.filename).write_text(launch.text, encoding="utf-8")
        name = section.filename or "robot.urdf"
        if ", " in name:
            build, name = name.split(", ", 1)
            (Path(folder) / "package.xml").write_text(
                PACKAGE.format(build=build.removesuffix(" package")), encoding="utf-8")
        path = Path(folder) / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(section.text, encoding="utf-8")
        if robot is not None:
            robot_path = Path(folder) / (robot.filename or "robot.urdf")
            robot_path.parent.mkdir(parents=True, exist_ok=True)
            robot_path.write_text(robot.text, encoding="utf-8")
            found = lint_paths([str(robot_path)], LintOptions(controllers=(str(path),))).problems
        else:
            settings = resolve(Config.model_validate({}), origin="defaults", base=Path(folder))
            found = lint_file(str(path), settings, named=True)
    return [Finding(p.line, p.column, p.severity, p.code,
                    " ".join(p.message.replace(folder + os.sep, "").split())) for p in found]


@pytest.mark.parametrize("code", RULES)
def test_the_failing_example_gives_the_expected_finding_and_the_passing_example_none(code):
    by_label = {section.label: section for section in sections(all_rules()[code].doc)}
    expected = expected_finding(by_label["Expected finding"].text)
    robot, launch = by_label.get("Robot"), by_label.get("Launch")
    assert expected in findings(by_label["Failing example"], robot, launch)
    assert [f for f in findings(by_label["Passing example"], robot, launch)
            if f.code == code] == []


def test_the_layout_check_names_what_is_missing():
    doc = all_rules()["TX104"].doc
    assert layout_problems("TX104", doc) == []
    without_fix = doc[: doc.index("\nFix:")]
    assert layout_problems("TX104", without_fix) == [
        "sections ['What it does', 'Why it matters', 'Loader', 'Failing example', 'Expected "
        "finding', 'Passing example'], expected ['What it does', 'Why it matters', 'Loader', "
        "'Failing example', 'Expected finding', 'Passing example', 'Fix'] in that order, each "
        "once"]
    unsourced = doc.replace("simple_transmission_loader.cpp", "the loader").replace(
        "default_robot_hw_sim.cpp", "it").replace("franka_hw_sim.cpp", "it")
    assert layout_problems("TX104", unsourced) == [
        "'Loader' names no source file (repository path/file.cpp, with the line or function)"]
    assert layout_problems("TX106", doc) == ["'Expected finding' is a TX104, not a TX106"]


def test_the_layout_check_names_a_missing_summary_an_empty_section_and_a_bare_finding():
    doc = all_rules()["TX104"].doc
    body = doc[doc.index("What it does:"):]
    assert layout_problems("TX104", body)[0] == "no summary line first"
    empty_fix = doc[: doc.index("\nFix:")] + "\nFix:\n"
    assert layout_problems("TX104", empty_fix) == ["'Fix' is empty"]
    start = doc.index("Expected finding:")
    bare = doc[:start] + "Expected finding: TX104, somewhere.\n\n" + doc[
        doc.index("Passing example::"):]
    assert layout_problems("TX104", bare) == [
        "'Expected finding' gives no ``LINE:COLUMN severity CODE message``"]


def test_a_failing_example_that_does_not_fail_is_caught():
    doc = all_rules()["TX104"].doc
    section = next(s for s in sections(doc.replace('<actuator name="m"/>', '<actuator name="m">'
                   "<mechanicalReduction>5</mechanicalReduction></actuator>", 1))
                   if s.label == "Failing example")
    assert [f for f in findings(section) if f.code == "TX104"] == []


def test_the_new_rule_script_writes_a_registered_rule_in_the_layout(tmp_path):
    """``python docs/new_rule.py TX499 kebab-name``, in a copy of the package: a module in the
    layout, registered in code order, that the registry loads."""
    shutil.copytree(ROOT / "txtool", tmp_path / "txtool",
                    ignore=shutil.ignore_patterns("__pycache__"))
    (tmp_path / "docs").mkdir()
    shutil.copy(ROOT / "docs" / "new_rule.py", tmp_path / "docs")
    env = {**os.environ, "PYTHONPATH": str(tmp_path)}
    made = subprocess.run([sys.executable, "docs/new_rule.py", "TX499", "example-rule"],
                          cwd=tmp_path, env=env, capture_output=True, text=True, timeout=60)
    assert made.returncode == 0, made.stderr
    assert made.stdout == "wrote txtool/rules/tx499_example_rule.py (registered)\n"
    check = ("from txtool.rules import RULE_MODULES, all_rules\n"
             "from txtool.lint.ruledoc import layout_problems\n"
             "rule = all_rules()['TX499']\n"
             "print(rule.name, rule.severity, RULE_MODULES.index('tx499_example_rule')"
             " == RULE_MODULES.index('tx404_ros1_members_against_roles') + 1,"
             " layout_problems('TX499', rule.doc))\n")
    loaded = subprocess.run([sys.executable, "-c", check], cwd=tmp_path, env=env,
                            capture_output=True, text=True, timeout=60)
    assert loaded.stdout == "example-rule warning True []\n", loaded.stderr
    again = subprocess.run([sys.executable, "docs/new_rule.py", "TX499", "example-rule"],
                           cwd=tmp_path, env=env, capture_output=True, text=True, timeout=60)
    assert (again.returncode, again.stdout) == (2, "")
    assert again.stderr == "new_rule.py: txtool/rules/tx499_example_rule.py: exists already\n"
