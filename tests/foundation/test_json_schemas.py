"""Every ``--format json`` holds to its schema under ``schemas/``, on real robots.

Each schema is generated from pydantic models (regenerate with ``python -m
txtool.commands.json_schemas``, ``python -m txtool.reporters.report_schema > ...`` and ``txtool
schema -o ...``); the checked-in files must be what they generate, and what each command prints
for the corpus must validate against both the file and the models.
"""

from __future__ import annotations

import json
from pathlib import Path

import jsonschema
import pytest
from click.testing import CliRunner

from tests.corpus import corpus_dir
from txtool.cli import cli
from txtool.commands import json_schemas
from txtool.commands.json_schemas import SCHEMAS, MapOutput, RoundtripJson, RulesOutput

ROOT = Path(__file__).resolve().parents[2]
FIXTURES = ROOT / "fixtures"


def txtool(*args: str) -> tuple[int, str, str]:
    result = CliRunner().invoke(cli, list(args), catch_exceptions=False)
    return result.exit_code, result.stdout, result.stderr


def validator(file_name: str) -> jsonschema.Draft202012Validator:
    schema = json.loads((ROOT / "schemas" / file_name).read_text())
    jsonschema.Draft202012Validator.check_schema(schema)
    return jsonschema.Draft202012Validator(schema)


@pytest.fixture(scope="module")
def corpus_robots() -> list[Path]:
    """The corpus files that are whole documents txtool reads (xacro libraries that need
    arguments to expand are left to the xacro tests)."""
    files = sorted(p for p in corpus_dir().iterdir() if p.name != "MANIFEST.tsv")
    readable = [p for p in files if txtool("show", str(p), "--format", "json")[0] == 0]
    assert len(readable) >= 30, [p.name for p in files if p not in readable]
    return readable


@pytest.mark.parametrize("file_name", sorted(SCHEMAS))
def test_checked_in_schemas_are_current(file_name):
    checked_in = (ROOT / "schemas" / file_name).read_text()
    assert checked_in == json_schemas.schema_text(file_name), (
        "run: python -m txtool.commands.json_schemas schemas")


def test_the_schemas_are_regenerated_by_running_the_module(tmp_path):
    import subprocess
    import sys

    done = subprocess.run([sys.executable, "-m", "txtool.commands.json_schemas", str(tmp_path)],
                          cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert (done.returncode, done.stdout, done.stderr) == (0, "", "")
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(SCHEMAS)
    for file_name in SCHEMAS:
        assert (tmp_path / file_name).read_text() == (ROOT / "schemas" / file_name).read_text()


def test_every_json_command_has_a_schema():
    """validate, show, map, roundtrip, rules (simulate's is its own, schemas/simulate...)."""
    from txtool.model.schema import schema_text as show_schema
    from txtool.reporters.report_schema import schema_text as report_schema

    assert (ROOT / "schemas" / "report.schema.json").read_text() == report_schema()
    assert (ROOT / "schemas" / "transmission.schema.json").read_text() == show_schema()
    assert set(SCHEMAS) == {"map.schema.json", "roundtrip.schema.json", "rules.schema.json"}


def test_show_json_of_the_corpus(corpus_robots):
    """Each key show can print, "readers" (--effective) and "actuator_limits" included."""
    schema = validator("transmission.schema.json")
    for robot in corpus_robots:
        for extra in ((), ("--effective", "--actuator-limits")):
            code, out, _ = txtool("show", str(robot), "--format", "json", *extra)
            assert code == 0, robot.name
            schema.validate(json.loads(out))


def test_validate_json_of_the_corpus_and_of_an_unreadable_file(tmp_path):
    schema = validator("report.schema.json")
    code, out, _ = txtool("validate", "--format", "json", "--jobs", "1", str(corpus_dir()),
                          str(tmp_path / "missing.urdf"))
    report = json.loads(out)
    assert code == 2 and report["summary"]["errors"] > 0 and report["summary"]["files"] >= 40
    assert report["unreadable"] == [{"path": str(tmp_path / "missing.urdf"),
                                     "message": f"{tmp_path / 'missing.urdf'}: no such file"}]
    schema.validate(report)
    with pytest.raises(jsonschema.ValidationError, match="'errors' was unexpected"):
        schema.validate({**report, "errors": report["unreadable"]})


def test_roundtrip_json_of_the_corpus(corpus_robots):
    schema = validator("roundtrip.schema.json")
    cycles = 0
    for robot in corpus_robots:
        code, out, _ = txtool("roundtrip", str(robot), "--format", "json")
        assert code in (0, 1), robot.name
        schema.validate(json.loads(out))
        document = RoundtripJson.model_validate_json(out)
        assert (document.against, document.transmissions) == (None, [])
        cycles += len(document.cycles)
    assert cycles > 100


def test_roundtrip_against_json():
    schema = validator("roundtrip.schema.json")
    for other in ("demo_robot.ros2-p2.urdf", "four_bar.ros1.urdf"):
        code, out, _ = txtool("roundtrip", str(FIXTURES / "demo_robot.urdf"), "--against",
                              str(FIXTURES / other), "--format", "json")
        compared = json.loads(out)
        assert code == (0 if compared["ok"] else 1)
        schema.validate(compared)
        document = RoundtripJson.model_validate_json(out)
        assert document.path.endswith("demo_robot.urdf") and document.against.endswith(other)
        assert (document.cycles, document.skipped) == ([], [])
    without = {key: value for key, value in compared.items() if key != "cycles"}
    with pytest.raises(jsonschema.ValidationError, match="'cycles' is a required property"):
        schema.validate(without)  # one shape: every key, with or without --against


def test_map_json_of_the_corpus(corpus_robots):
    schema = validator("map.schema.json")
    mapped = 0
    for robot in corpus_robots:
        shown = json.loads(txtool("show", str(robot), "--format", "json")[1])
        for transmission in shown["transmissions"][:3]:
            values = ",".join("0.5" for _ in transmission["joints"]) or "0.5"
            code, out, err = txtool("map", str(robot), "-t", transmission["name"], "--to",
                                    "actuator", "--position", values, "--effort", values)
            if code != 0:  # not loadable, a duplicate name: one line on stderr
                assert out == "" and err.count("\n") == 1, (robot.name, err)
                continue
            code, out, _ = txtool("map", str(robot), "-t", transmission["name"], "--to",
                                  "actuator", "--position", values, "--effort", values,
                                  "--format", "json")
            assert code == 0
            schema.validate(json.loads(out))
            output = MapOutput.model_validate_json(out)
            assert len(output.position) == len(output.effort) >= 1 and not output.velocity
            mapped += 1
    assert mapped >= 30


def test_rules_json_is_always_a_list():
    schema = validator("rules.schema.json")
    code, out, _ = txtool("rules", "--format", "json")
    from txtool.rules import all_rules

    every = json.loads(out)
    assert code == 0 and [row["code"] for row in every] == list(all_rules())
    schema.validate(every)
    for name in ("TX106", "zero-reduction"):
        code, out, _ = txtool("rules", name, "--format", "json")
        one = json.loads(out)
        assert code == 0 and [row["code"] for row in one] == ["TX106"]
        schema.validate(one)
        assert RulesOutput.model_validate_json(out).root[0].name == "zero-reduction"
    with pytest.raises(jsonschema.ValidationError):
        schema.validate(one[0])  # a bare object, as a single rule was printed before


def test_txtool_schema_prints_each_schema_by_name():
    from click.testing import CliRunner

    from txtool.cli import cli
    from txtool.commands.schema import SCHEMAS

    listed = CliRunner().invoke(cli, ["schema", "--list"])
    assert listed.exit_code == 0
    assert [line.split()[0] for line in listed.output.splitlines()] == list(SCHEMAS)
    assert {file_name for file_name, _ in SCHEMAS.values()} == {
        path.name for path in (ROOT / "schemas").glob("*.schema.json")}
    for name, (file_name, _) in SCHEMAS.items():
        result = CliRunner().invoke(cli, ["schema", name])
        assert result.exit_code == 0, name
        assert result.output == (ROOT / "schemas" / file_name).read_text(), name
    assert CliRunner().invoke(cli, ["schema"]).output == (
        ROOT / "schemas" / "transmission.schema.json").read_text()
