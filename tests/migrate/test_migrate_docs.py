"""The examples of the documentation's migrate section are what txtool prints."""

from __future__ import annotations

import re
import shlex
from pathlib import Path

from tests.migrate.test_migrate_cli import ROBOT
from tests.migrate.test_migrate_xacro import CUSTOM, MACRO

DOC = Path(__file__).resolve().parents[2] / "docs" / "conversion.md"
# The xacro example is the test macro without its second interface and with a plain reduction.
ARM = (MACRO.replace(" iface:=EffortJointInterface", "")
       .replace("        <hardwareInterface>hardware_interface/${iface}</hardwareInterface>\n", "")
       .replace("${reduction * 2}", "${reduction}"))
FILES = {"robot.urdf": ROBOT, "arm.urdf.xacro": ARM, "panda.urdf": CUSTOM}


def _section() -> str:
    text = DOC.read_text()
    return text[text.index("## `txtool migrate"):text.index("## `txtool roundtrip")]


def _sessions() -> list[tuple[str, str]]:
    """(command, expected output) for every ``$ txtool ...`` line of the console blocks."""
    sessions = []
    for block in re.findall(r"```console\n(.*?)```", _section(), re.S):
        for part in re.split(r"^\$ ", block, flags=re.M)[1:]:
            command, _, output = part.partition("\n")
            sessions.append((command, output))
    return sessions


def test_the_examples_are_what_txtool_prints(run, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    for name, text in FILES.items():
        (tmp_path / name).write_text(text.lstrip("\n"))
    sessions = _sessions()
    assert len(sessions) == 5
    for command, expected in sessions:
        args = shlex.split(command)
        assert args[0] == "txtool"
        _, out, err = run(*args[1:])
        assert out + err == expected, command


def test_the_table_lists_every_fixable_rule():
    from txtool.rules import all_rules

    listed = re.findall(r"^\| (TX\d+) ", _section(), re.M)
    assert listed == sorted(code for code, rule in all_rules().items() if rule.fixable)
