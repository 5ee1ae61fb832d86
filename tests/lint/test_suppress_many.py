"""Suppressions with several directives, many findings and several files: each directive
silences its own line and no other, wherever it stands among the others."""

from __future__ import annotations

import json

import pytest

from tests.rules.helpers import check

ZERO = (
    '  <transmission name="t{i:02d}"><type>transmission_interface/SimpleTransmission</type>'
    '<joint name="j{i:02d}"><hardwareInterface>hardware_interface/EffortJointInterface'
    '</hardwareInterface></joint><actuator name="m{i:02d}"><mechanicalReduction>0'
    "</mechanicalReduction></actuator></transmission>{same}\n"
)
ZERO_COLUMN = ZERO.format(i=0, same="").index("<mechanicalReduction>") + 1  # where TX106 points


def robot(*lines: str) -> str:
    return '<robot name="r">\n' + "".join(lines) + "</robot>\n"


def zero(i: int, same: str = "") -> str:
    return ZERO.format(i=i, same=same)


def tx106(*lines: int) -> list[tuple[int, int, str, str]]:
    return [(line, ZERO_COLUMN, "TX106", "error") for line in lines]


def test_each_of_several_next_line_directives_silences_only_its_own_next_line():
    text = robot(
        zero(1),                                                    # 2: reported
        "  <!-- txtool: disable-next-line TX106 -->\n",             # 3
        zero(2),                                                    # 4: silenced
        zero(3),                                                    # 5: reported
        "  <!-- txtool: disable-next-line TX106 -->\n",             # 6
        zero(4),                                                    # 7: silenced
        zero(5),                                                    # 8: reported
        "  <!-- txtool: disable-next-line TX106 -->\n",             # 9
        zero(6),                                                    # 10: silenced
    )
    assert check(text) == tx106(2, 5, 8)


def test_a_later_multiline_directive_targets_the_line_after_its_end():
    text = robot(
        "  <!-- txtool: disable-next-line\n",                       # 2
        "       TX106 -->\n",                                       # 3
        zero(1),                                                    # 4: silenced
        "  <!-- txtool: disable-next-line\n",                       # 5
        "       TX105\n",                                           # 6
        "       TX106; a reason\n",                                 # 7
        "       over several lines -->\n",                          # 8
        zero(2),                                                    # 9: silenced
        zero(3),                                                    # 10: reported
        "  <!-- txtool: disable-next-line TX106 -->\n",             # 11
        zero(4),                                                    # 12: silenced
    )
    # TX105 of the second directive silenced nothing: reported where that directive starts.
    assert check(text) == [(5, 3, "TX003", "info"), *tx106(10)]


def test_disable_line_directives_on_several_lines_each_silence_their_own_line():
    same = "<!-- txtool: disable-line TX106 -->"
    text = robot(zero(1), zero(2, same), zero(3), zero(4, same), zero(5, same), zero(6))
    assert check(text) == tx106(2, 4, 7)


def test_two_directives_on_one_line_and_one_on_the_next_keep_their_own_columns():
    # The second and third directives name codes with nothing to silence: each TX003 is
    # reported at its own comment, so a column counted from the wrong line start shows.
    text = robot(
        "  <!-- txtool: disable-next-line TX105 --> <!-- txtool: disable-next-line TX106 -->\n",
        zero(1),                                                    # 3: silenced
        "    <!-- txtool: disable-next-line TX104 -->\n",           # 4
        zero(2),                                                    # 5: reported
    )
    assert check(text) == [(2, 3, "TX003", "info"), (4, 5, "TX003", "info"), *tx106(5)]


def test_many_directives_and_findings_silence_exactly_the_marked_lines():
    lines, expected_lines = [], []
    line = 2
    for i in range(40):
        if i % 3 == 0:
            lines.append("  <!-- txtool: disable-next-line TX106 -->\n")
            line += 1
            lines.append(zero(i))
        elif i % 3 == 1:
            lines.append(zero(i, "<!-- txtool: disable-line TX106 -->"))
        else:
            lines.append(zero(i))
            expected_lines.append(line)
        line += 1
    assert check(robot(*lines)) == tx106(*expected_lines)


def test_a_file_directive_after_line_directives_still_silences_the_whole_file():
    text = robot(
        "  <!-- txtool: disable-next-line TX106 -->\n",
        zero(1),
        zero(2),
        "  <!-- txtool: disable-file TX106 -->\n",
        zero(3),
    )
    # The next-line directive's line is covered by the file directive too: both silenced it.
    assert check(text) == []


def test_a_directive_without_codes_among_coded_ones_silences_only_its_line():
    text = robot(
        "  <!-- txtool: disable-next-line TX105 -->\n",             # 2: unused
        zero(1),                                                    # 3: reported
        "  <!-- txtool: disable-next-line -->\n",                   # 4
        zero(2),                                                    # 5: silenced
        zero(3),                                                    # 6: reported
    )
    assert check(text) == [(2, 3, "TX003", "info"), *tx106(3, 6)]


@pytest.fixture
def two_files(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    # the same finding lines; directives on different lines in each file
    (tmp_path / "a.urdf").write_text(robot(
        "  <!-- txtool: disable-next-line TX106 -->\n", zero(1), zero(2)))
    (tmp_path / "b.urdf").write_text(robot(
        "  <!---->\n", zero(1), "  <!-- txtool: disable-next-line TX106 -->\n", zero(2)))
    return tmp_path


@pytest.mark.parametrize("jobs", ["1", "2"])
def test_each_file_keeps_its_own_directives(validate, two_files, jobs):
    code, out, _ = validate("--format", "json", "-j", jobs, "a.urdf", "b.urdf")
    found = sorted((p["path"], p["line"], p["code"]) for p in json.loads(out)["problems"])
    assert code == 1
    assert found == [("a.urdf", 4, "TX106"), ("b.urdf", 3, "TX106")]
