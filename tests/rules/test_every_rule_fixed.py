"""Every fixable rule's fix, as a user runs it: two findings of the rule and an error of a rule
without a fix, in two files, fixed by one ``validate --fix`` run; ``--diff`` exits 1 while
there is something to fix and 0 once there is not; the fixed files validate clean of the
rule, and what the fix does not own keeps its bytes. The cases follow the registry: a rule
marked fixable without a case here fails the first test."""

from __future__ import annotations

import json

import pytest
from click.testing import CliRunner

from tests.rules.helpers import problems
from tests.rules.test_severities import OPTIONS, TABLE
from txtool.cli import cli
from txtool.rules import all_rules

FIXABLE = sorted(code for code, rule in all_rules().items() if rule.fixable)

HEAD = """<robot name="r">
  <joint name="a" type="revolute"><limit effort="1" velocity="1" lower="-1" upper="1"/></joint>
  <joint name="b" type="revolute"><limit effort="1" velocity="1" lower="-1" upper="1"/></joint>
  <joint name="c" type="revolute"><limit effort="1" velocity="1" lower="-1" upper="1"/></joint>
"""
SIMPLE = "<type>transmission_interface/SimpleTransmission</type>"
EFFORT = "<hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>"
# The finding no fix touches: a zero reduction (TX106, an error), in the last transmission.
ZERO = f"""  <transmission name="tc">
    {SIMPLE}
    <joint name="c">{EFFORT}</joint>
    <actuator name="mc"><mechanicalReduction>0</mechanicalReduction></actuator>
  </transmission>
</robot>
"""

# code: the transmissions on joints a and b, each with one finding of the rule (in two forms
# where the rule knows two)
CASES = {
    "TX300": f"""  <transmission name="ta">
    {SIMPLE}
    <joint name="a"><hardwareInterface>EffortJointInterface</hardwareInterface></joint>
    <actuator name="ma"><mechanicalReduction>50</mechanicalReduction></actuator>
  </transmission>
  <transmission name="tb">
    {SIMPLE}
    <joint name="b">
      {EFFORT}
      <hardwareInterface>PositionJointInterface</hardwareInterface>
    </joint>
    <actuator name="mb"><mechanicalReduction>50</mechanicalReduction></actuator>
  </transmission>
""",
    "TX301": f"""  <transmission name="ta">
    {SIMPLE}
    <joint name="a"/>
    <actuator name="ma">{EFFORT}<mechanicalReduction>50</mechanicalReduction></actuator>
  </transmission>
  <transmission name="tb">
    {SIMPLE}
    <joint name="b"></joint>
    <actuator name="mb">
      {EFFORT}
      <mechanicalReduction>50</mechanicalReduction>
    </actuator>
  </transmission>
""",
    # the legacy form (the attribute alone, the reduction under <transmission>) and the hybrid
    # one (the attribute beside a <type> element)
    "TX302": f"""  <transmission name="ta" type="SimpleTransmission">
    <joint name="a">{EFFORT}</joint>
    <actuator name="ma"/>
    <mechanicalReduction>50</mechanicalReduction>
  </transmission>
  <transmission name="tb" type="transmission_interface/SimpleTransmission">
    {SIMPLE}
    <joint name="b">{EFFORT}</joint>
    <actuator name="mb"><mechanicalReduction>50</mechanicalReduction></actuator>
  </transmission>
""",
}

# code: the rules that report the same mistakes beside it
COMPANIONS = {"TX301": ("TX110",)}  # the joint without an interface, as an error

# code: a finding of the rule that its fix declines by design, with the file's name
DECLINED = {
    # a transmission family with a loader of its own: no standard type to write
    "TX302": ("""<robot name="r">
  <joint name="a" type="revolute"><limit effort="1" velocity="1" lower="-1" upper="1"/></joint>
  <transmission name="ta" type="pr2_mechanism_model/SimpleTransmission">
    <joint name="a"/>
    <actuator name="ma"><mechanicalReduction>50</mechanicalReduction></actuator>
  </transmission>
</robot>
""", "r.urdf"),
    # the name comes from a xacro property: the file holds no name to prefix
    "TX300": (f"""<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="iface" value="PositionJointInterface"/>
  <joint name="a" type="revolute"><limit effort="1" velocity="1" lower="-1" upper="1"/></joint>
  <transmission name="ta">
    {SIMPLE}
    <joint name="a">{EFFORT}<hardwareInterface>${{iface}}</hardwareInterface></joint>
    <actuator name="ma"><mechanicalReduction>50</mechanicalReduction></actuator>
  </transmission>
</robot>
""", "r.urdf.xacro"),
}
FILES = ("a.urdf", "b.urdf")


def run(*args: str) -> tuple[int, str, str]:
    result = CliRunner().invoke(cli, list(args))
    if result.exception and not isinstance(result.exception, SystemExit):
        raise result.exception
    return result.exit_code, result.stdout, result.stderr


def findings(*paths: str) -> list[tuple[str, int, str, bool]]:
    code, out, _ = run("validate", "--format", "json", *paths)
    assert code in (0, 1), out
    return [(p["path"], p["line"], p["code"], p["fixable"]) for p in json.loads(out)["problems"]]


def test_every_fixable_rule_has_a_case_and_every_case_a_fixable_rule():
    assert sorted(CASES) == FIXABLE


@pytest.mark.parametrize("code", FIXABLE)
def test_two_findings_of_each_fixable_rule_in_two_files_are_fixed_in_one_run(
        code, tmp_path, monkeypatch):
    assert code in CASES, f"{code} is fixable: give it a case in CASES"
    document = HEAD + CASES[code] + ZERO
    monkeypatch.chdir(tmp_path)
    for name in FILES:
        (tmp_path / name).write_text(document)
    before = findings(*FILES)
    assert [(path, c, fixable) for path, _, c, fixable in before if c in (code, "TX106")] == [
        (path, c, c == code) for path in FILES for c in (code, code, "TX106")]
    # what else the same mistakes draw: not fixable itself, gone with the fix
    assert {(c, fixable) for _, _, c, fixable in before if c not in (code, "TX106")} == {
        (c, False) for c in COMPANIONS.get(code, ())}

    status, out, err = run("validate", *FILES)
    assert status == 1 and err == ""
    marked = [line.split(": ", 2)[1].split()[1] for line in out.splitlines()[:-1]
              if " [*] " in line]
    assert marked == [code] * 4
    assert out.splitlines()[-1].endswith("in 2 files; 4 fixable with `txtool validate --fix`.")

    status, out, err = run("validate", "--diff", *FILES)
    assert status == 1
    assert [line for line in out.splitlines() if line.startswith(("---", "+++"))] == [
        "--- a/a.urdf", "+++ b/a.urdf", "--- a/b.urdf", "+++ b/b.urdf"]
    assert err.splitlines() == [f"would change {name} ({code} x2)" for name in FILES] + [
        "2 file(s) would be changed"]
    assert all((tmp_path / name).read_text() == document for name in FILES)

    status, out, err = run("validate", "--fix", *FILES)
    assert err.splitlines() == [f"txtool: fixed {name} ({code} x2)" for name in FILES]
    assert status == 1  # the zero reduction is still there, and still an error
    assert [line.split(": ", 2)[1] for line in out.splitlines()[:-1]] == [
        "error TX106 zero-reduction"] * 2
    # (a fix that spreads an element over lines moves the later ones down)
    assert [(path, c, fixable) for path, _, c, fixable in findings(*FILES)] == [
        (path, "TX106", False) for path in FILES]
    for name in FILES:
        fixed = (tmp_path / name).read_text()
        assert fixed.startswith(HEAD) and fixed.endswith(ZERO)  # untouched around the fixes
        assert fixed != document
    assert run("validate", "--diff", *FILES) == (0, "", "txtool: nothing to fix\n")
    assert run("validate", "--fix", *FILES)[2] == ""  # a fixed point: nothing more to write


@pytest.mark.parametrize("code", sorted(DECLINED))
def test_a_finding_the_fix_declines_is_reported_as_not_fixable_and_left_as_written(
        code, tmp_path, monkeypatch):
    assert all_rules()[code].fixable
    document, name = DECLINED[code]
    monkeypatch.chdir(tmp_path)
    (tmp_path / name).write_text(document)
    assert [(c, fixable) for _, _, c, fixable in findings(name) if c == code] == [(code, False)]
    status, out, _ = run("validate", name)
    assert code in out and "[*]" not in out and "fixable" not in out
    status_diff, diff, err = run("validate", "--diff", name)
    assert (status_diff, diff) == (0, "") and "would change" not in err
    assert run("validate", "--fix", name) == (status, out, "")
    assert (tmp_path / name).read_text() == document


# Rows of the severity table whose findings stand in a robot file of their own.
XML_ROWS = sorted(code for code, (_, _, filename) in TABLE.items()
                  if filename not in ("controllers.yaml", "named.urdf"))


@pytest.mark.parametrize("code", XML_ROWS)
def test_each_rule_marks_its_findings_fixable_as_the_registry_says(code):
    """A rule without a fix never marks a finding fixable; the table's findings of a fixable
    rule are all ones its fix makes."""
    _, document, filename = TABLE[code]
    found = [p for p in problems("\n" + document, filename=filename, **OPTIONS.get(code, {}))
             if p.code == code]
    assert found, f"{code} did not fire on its table snippet"
    assert [p.fixable for p in found] == [all_rules()[code].fixable] * len(found)
