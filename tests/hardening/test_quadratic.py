"""A pull request cannot make a check take hours: work grows with the document, not its square.

Each test feeds the shape that made one step quadratic (thousands of suppression comments on a
single line, comments that never close, every finding of a minified document on its one line,
thousands of comments inside one transmission) and bounds the processor time of that step far
above what it takes now and far below what the quadratic step took (docs/security.md gives the
figures). Processor time, not wall time: a loaded machine slows neither bound.
"""

from __future__ import annotations

import re
import time
from collections.abc import Callable
from pathlib import Path

from click.testing import CliRunner

from tests.conftest import untraced
from txtool.cli import cli
from txtool.io.xmlio import Source, parse_bytes
from txtool.lint.engine import as_settings, finish
from txtool.lint.problem import Problem
from txtool.lint.suppress import parse


def cpu_seconds(work: Callable[[], object]) -> float:
    start = time.process_time()
    work()
    return time.process_time() - start


def test_thousands_of_suppressions_on_one_line():
    """12,000 ``disable-line`` comments and as many findings on one line: every finding is
    looked up, not checked against every directive (144 million checks before)."""
    count = 12000
    directive = b"<a/><!-- txtool: disable-line TX106 -->"
    data = b"<robot>" + directive * count + b"</robot>\n"
    problems = [Problem("robot.urdf", 1, 8 + len(directive) * i, "TX106", "zero reduction")
                for i in range(count)]

    def match() -> None:
        suppressions = parse(data)
        assert all(suppressions.suppressed(p) for p in problems)
        assert not list(suppressions.unused(frozenset({"TX106"})))
        assert len(suppressions.directives) == count
        assert {d.used == {"TX106"} for d in suppressions.directives} == {True}

    assert cpu_seconds(match) < 2.0  # 0.2 s now; 11 to 38 s when each finding met every directive


def test_suppression_comments_that_never_close():
    """2,000 ``<!-- txtool:`` openings with no ``-->``: the search for the end of each ran to
    the end of the document (18 s for 2,000)."""
    data = b"<robot>" + b"<!-- txtool: disable-line TX106 " * 2000
    assert cpu_seconds(lambda: parse(data)) < 1.0  # well under 0.01 s now


def test_the_end_columns_of_findings_on_one_line():
    """16,000 findings on the single 8 MB line of a minified document: the end of each is read
    in place (the rest of the line was copied for each, 64 GB in all)."""
    count = 16000
    element = b'<a name="x%d"/><!--' + b" " * 500 + b"-->"
    body = b"".join(element % i for i in range(count))
    data = b"<robot>" + body + b"</robot>\n"
    source = Source("robot.urdf", data, parse_bytes(data, "robot.urdf"))
    starts = [match.start() for match in re.finditer(rb"<a ", data)]
    problems = [Problem("robot.urdf", 1, start + 1, "TX106", "zero reduction")
                for start in starts]
    found: list[Problem] = []
    seconds = cpu_seconds(lambda: found.extend(finish(list(problems), source, as_settings(None))))
    assert [p.end_column - p.column for p in found] == [
        len(b'<a name="x%d"/>' % i) for i in range(count)]
    assert seconds < 2.0  # 0.15 s now; 11 s before


def test_thousands_of_comments_in_one_transmission(tmp_path: Path):
    """60,000 comments inside one transmission carried to the converted one: each was
    inserted at its index, which lxml reaches by walking the children before it."""
    notes = "".join(f"<!-- note {k} -->" for k in range(60000))
    robot = tmp_path / "robot.urdf"
    robot.write_text(
        '<robot name="r"><link name="b"/><transmission name="t">'
        f"<type>transmission_interface/SimpleTransmission</type>{notes}"
        '<joint name="j"><hardwareInterface>hardware_interface/EffortJointInterface'
        '</hardwareInterface></joint><actuator name="m"><mechanicalReduction>50'
        "</mechanicalReduction></actuator></transmission></robot>\n")
    results = []
    with untraced():  # the program's time, not coverage's tracer's (comments in a transmission
        seconds = cpu_seconds(lambda: results.append(  # are converted traced elsewhere)
            CliRunner().invoke(cli, ["convert", str(robot), "--to", "ros2-p2"])))
    assert results[0].exit_code == 0, results[0].output
    converted = results[0].stdout
    assert converted.index("<!-- note 0 -->") < converted.index("<!-- note 59999 -->")
    assert converted.count("<!-- note ") == 60000
    assert seconds < 3.0  # 0.4 s now; 14 s before
