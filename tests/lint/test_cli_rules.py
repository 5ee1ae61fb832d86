"""``txtool rules [CODE]``: the catalogue from the registry, one rule's documentation."""

from __future__ import annotations

import json
import re

import pytest
from click.testing import CliRunner

from txtool.cli import cli
from txtool.rules import RULE_MODULES, all_rules


def run(*args: str):
    result = CliRunner().invoke(cli, ["rules", *args])
    return result.exit_code, result.stdout, result.stderr


def test_catalogue_lists_every_registered_rule_once():
    code, out, err = run()
    lines = out.splitlines()
    assert (code, err) == (0, "")
    assert [line.split()[0] for line in lines] == list(all_rules())
    assert len(lines) == len(RULE_MODULES)
    tx105 = next(line for line in lines if line.startswith("TX105"))
    assert tx105.split()[1:3] == ["invalid-number", "error"]


def test_one_rule_prints_its_docstring_by_code_or_name():
    code, out, _ = run("tx106")
    assert code == 0
    assert out.startswith("TX106 zero-reduction (default severity: error)\n\n")
    assert "Failing example:\n" in out and "Passing example:\n" in out
    assert "``" not in out and "::\n" not in out  # no reStructuredText on screen
    assert "in ROS 1 0abc too (std::stod reads 0)" in out
    assert run("zero-reduction")[1] == out


@pytest.mark.parametrize("code", list(all_rules()))
def test_no_rule_shows_markup_on_screen(code):
    out = run(code)[1]
    assert "``" not in out and ":func:`" not in out and ":mod:`" not in out
    assert "::\n" not in out


def test_unknown_rule_is_exit_2():
    assert run("TX999") == (2, "", "txtool: no such rule: TX999 (see 'txtool rules')\n")


def test_json_catalogue():
    code, out, _ = run("--format", "json")
    rows = json.loads(out)
    assert code == 0 and [r["code"] for r in rows] == list(all_rules())
    assert {"code", "name", "severity", "fixable", "summary", "doc"} <= set(rows[0])


def test_every_rule_documents_itself_with_an_xml_example():
    for rule in all_rules().values():
        assert rule.summary, rule.code
        assert "::\n\n    <" in rule.doc, rule.code
        if rule.code.startswith(("TX0", "TX1")):
            assert re.search(r"^Failing example[^\n]*::$", rule.doc, re.M), rule.code
            assert re.search(r"^Passing example[^\n]*::$", rule.doc, re.M), rule.code
