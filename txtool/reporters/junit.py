"""JUnit XML (the xunit files ament linters write and ``colcon test-result`` reads): one test
case per finding, failed where the finding fails the run (errors; warnings too with
``--strict``), passed with its message as output otherwise; a file that could not be read is
a test case in error; a run with nothing to say is one passed case, ``no problems``.
"""

from __future__ import annotations

from collections.abc import Sequence

from lxml import etree

from txtool.io.printable import printable
from txtool.lint.problem import Problem
from txtool.reporters import Summary

SUITE = "txtool"


def render(problems: Sequence[Problem], summary: Summary, *, color: bool = False) -> str:
    suite = etree.Element("testsuite", name=SUITE)
    failed = 0
    for problem in problems:
        case = _case(suite, problem.path, f"{problem.code} {problem.name} "
                                         f"{problem.line}:{problem.column}")
        path = problem.path.removeprefix("./")
        line = (f"{path}:{problem.line}:{problem.column}: {problem.severity} "
                f"{problem.code} {problem.name}: {problem.message}{problem.chain()}")
        if problem.severity in summary.failing:
            failed += 1
            failure = etree.SubElement(case, "failure", message=_text(problem.message),
                                       type=problem.severity)
            failure.text = _text(line)
        else:
            etree.SubElement(case, "system-out").text = _text(line)
    for failure in summary.failures:
        case = _case(suite, failure.path, "read")
        etree.SubElement(case, "error", message=_text(failure.message)).text = \
            _text(failure.message)
    if not problems and not summary.failures:
        _case(suite, "", "no problems")
    suite.set("tests", str(len(suite)))
    suite.set("failures", str(failed))
    suite.set("errors", str(len(summary.failures)))
    suite.set("skipped", "0")
    body = etree.tostring(suite, encoding="unicode", pretty_print=True)
    return '<?xml version="1.0" encoding="UTF-8"?>\n' + body


def _case(suite: etree._Element, path: str, name: str) -> etree._Element:
    return etree.SubElement(suite, "testcase", classname=_text(class_name(path)),
                            name=_text(name), time="0")


def class_name(path: str) -> str:
    """``urdf/robot.urdf`` as ``txtool.urdf.robot_urdf``: JUnit readers (Jenkins, GitLab,
    ``colcon test-result``) take the dots of a class name for packages, so the file's own dots
    become ``_`` and its folders the packages."""
    parts = [part for part in path.replace("\\", "/").split("/") if part not in ("", ".")]
    return ".".join([SUITE, *(part.replace(".", "_") for part in parts)])


def _text(value: str) -> str:
    """``value`` as XML may hold it: control characters and undecodable bytes escaped."""
    return printable(value)
