"""``roundtrip`` prints its table without rich where the output is plain; rich's text is the
reference, character for character, and anything the plain writer cannot match goes to rich."""

from __future__ import annotations

import contextlib
import io
import string

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from rich.table import Table

from txtool.commands.roundtrip import _print_rich_table
from txtool.views.plain import plain_output, plain_table, roundtrip_text
from txtool.views.render import safe

ASCII = st.text(st.characters(min_codepoint=32, max_codepoint=126), max_size=40)
NAME = st.text(st.sampled_from(string.ascii_letters + string.digits + "  ._-/:'()=,"),
               max_size=30)
MARKS = st.sampled_from(["✓", "✗", "yes", "no", "n/a", "ros1 → ros2-p1 → ros1"])
CELL = st.one_of(NAME, MARKS, ASCII)
TEXT = st.one_of(NAME, ASCII)


def rich_text(title: str, columns: list[str], rows: list[list[str]], lines: list[str]) -> str:
    """What ``roundtrip`` printed through rich to a pipe (``views.render.console``)."""
    from rich.console import Console

    out = io.StringIO()
    console = Console(file=out, width=140, highlight=False)
    table = Table(title=safe(title), title_justify="left")
    for column in columns:
        table.add_column(safe(column))
    for row in rows:
        table.add_row(*(safe(cell) for cell in row))
    console.print(table)
    for line in lines:
        console.print(safe(line))
    return out.getvalue()


@settings(max_examples=300, deadline=None)
@given(
    title=TEXT,
    columns=st.lists(TEXT, min_size=1, max_size=8),
    data=st.data(),
    lines=st.lists(st.one_of(NAME, ASCII, st.lists(NAME.filter(bool), min_size=5, max_size=8)
                             .map(lambda words: " ".join(words * 20))), max_size=3),
)
def test_the_plain_table_is_rich_s_text_or_nothing(title, columns, data, lines):
    rows = data.draw(st.lists(st.lists(CELL, min_size=len(columns), max_size=len(columns)),
                              max_size=6))
    plain = plain_table(title, columns, rows, lines)
    if plain is not None:
        assert plain == rich_text(title, columns, rows, lines)


ARM = (
    '<robot name="r"><joint name="j" type="revolute"><parent link="a"/><child link="b"/>'
    '<limit lower="-1" upper="1" effort="5" velocity="2"/></joint>'
    '<transmission name="t"><type>transmission_interface/SimpleTransmission</type>'
    '<joint name="j"><hardwareInterface>hardware_interface/EffortJointInterface'
    '</hardwareInterface></joint><actuator name="m"><mechanicalReduction>50'
    "</mechanicalReduction></actuator></transmission></robot>"
)


def test_a_roundtrip_report_prints_as_rich_prints_it(run, tmp_path):
    arm = tmp_path / "arm.urdf"
    arm.write_text(ARM)
    from txtool.io.load import load
    from txtool.transform.roundtrip import roundtrip

    report = roundtrip(load(str(arm)))
    text = roundtrip_text(report)
    assert text is not None and "│ t            │ ros1 → ros2-p1 → ros1 " in text
    code, out, err = run("roundtrip", str(arm))
    assert (code, out, err) == (0, text, "")
    with_rich = io.StringIO()
    with contextlib.redirect_stdout(with_rich):
        _print_rich_table(report)
    assert text == with_rich.getvalue()


@pytest.mark.parametrize(("env", "plain"), [
    ({}, True),
    ({"FORCE_COLOR": "1"}, False),
    ({"FORCE_COLOR": ""}, True),
    ({"TTY_COMPATIBLE": "1"}, False),
    ({"TTY_COMPATIBLE": "0", "FORCE_COLOR": "1"}, True),
])
def test_colour_variables_send_the_table_to_rich(monkeypatch, env, plain):
    for name in ("FORCE_COLOR", "TTY_COMPATIBLE"):
        monkeypatch.delenv(name, raising=False)
    for name, value in env.items():
        monkeypatch.setenv(name, value)
    assert plain_output(io.StringIO()) is plain


def test_with_colour_the_lost_fields_stay_red(run, tmp_path):
    robot = tmp_path / "r.urdf"
    robot.write_text(
        '<robot name="r"><transmission name="t">'
        "<type>transmission_interface/FourBarLinkageTransmission</type>"
        '<joint name="a"><role>joint1</role><hardwareInterface>EffortJointInterface'
        '</hardwareInterface></joint><joint name="b"><role>joint2</role><hardwareInterface>'
        "EffortJointInterface</hardwareInterface></joint>"
        '<actuator name="m1"><role>actuator1</role><mechanicalReduction>2</mechanicalReduction>'
        '</actuator><actuator name="m2"><role>actuator2</role><mechanicalReduction>3'
        "</mechanicalReduction></actuator></transmission></robot>")
    code, out, _ = run("roundtrip", "--color", "always", str(robot))
    assert code == 1
    assert "\x1b[31mno\x1b[0m" in out


@pytest.mark.parametrize("size", [135, 136, 137, 139, 140, 141])
def test_at_the_edge_of_the_width_the_plain_text_is_rich_s_or_nothing(size):
    """136 characters fill a one-column table to 140; a line of 140 fits, 141 wraps."""
    cases = [("t", ["a"], [["x"]], ["y" * size]),
             ("t", ["a"], [["x"]], [" ".join(["ab"] * (size // 3)).ljust(size, "c")]),
             ("title", ["h"], [["z" * size]], []),
             ("T" * (size + 4), ["h"], [["z" * 136]], [])]
    for case in cases:
        plain = plain_table(*case)
        if plain is not None:
            assert plain == rich_text(*case)
    assert (plain_table(*cases[0]) is None) == (size > 140)
    assert (plain_table(*cases[2]) is None) == (size > 136)
