"""The JSON report: one shape for one config or many, every number with its unit, and the
document valid against schemas/simulate.schema.json."""

from __future__ import annotations

import json
from pathlib import Path

import jsonschema
import pytest
from click.testing import CliRunner

from tests.simulate.robots import arm_ros1, write
from txtool.cli import cli

ROOT = Path(__file__).resolve().parents[2]
SCHEMA = json.loads((ROOT / "schemas" / "simulate.schema.json").read_text(encoding="utf-8"))
CT_GAINS = "ct:\n  joints:\n    shoulder: {p: 400, d: 40, i: 1}\n"
ROS2_GAINS = """arm_controller:
  ros__parameters:
    joints: [elbow]
    command_interfaces: [effort]
    gains:
      elbow: {p: 20.0, d: 2.0}
"""


def txtool(*args: str) -> tuple[int, str, str]:
    result = CliRunner().invoke(cli, ["simulate", *args], catch_exceptions=False)
    return result.exit_code, result.stdout, result.stderr


def numbers_without_units(value, where="") -> list[str]:
    """Paths of the numbers whose object has no unit for them."""
    missing = []
    if isinstance(value, dict):
        units = value.get("units", {})
        for key, item in value.items():
            number = isinstance(item, int | float) and not isinstance(item, bool)
            if number and not (isinstance(units, dict) and units.get(key)):
                missing.append(f"{where}.{key}")
            missing += numbers_without_units(item, f"{where}.{key}")
    elif isinstance(value, list):
        for index, item in enumerate(value):
            missing += numbers_without_units(item, f"{where}[{index}]")
    return missing


@pytest.fixture(scope="module")
def documents(tmp_path_factory):
    """A failing config with gains from two files, and a comparison of three configs (a
    pass, a fail and one that checks nothing)."""
    folder = tmp_path_factory.mktemp("json")
    robot = write(folder, "arm.urdf", arm_ros1())
    flipped = write(folder, "flipped.urdf", arm_ros1(n=-50))
    blind = write(folder, "blind.urdf", arm_ros1().replace("transmission_interface/",
                                                           "acme/"))
    ct = write(folder, "ct.yaml", CT_GAINS)
    effort = write(folder, "ros2.yaml", ROS2_GAINS)
    one = txtool(robot, "--candidate", flipped, "--duration", "1", "--format", "json",
                 "--params", ct, "--params", effort)
    many = txtool(robot, "--candidate", robot, "--candidate", flipped, "--candidate", blind,
                  "--duration", "1", "--format", "json")
    return one, many


def test_one_config_and_many_have_the_same_shape(documents):
    (code, out, err), (code_many, out_many, err_many) = documents
    assert (code, err, code_many, err_many) == (1, "", 1, "")
    one, many = json.loads(out), json.loads(out_many)
    assert (one["verdict"], len(one["runs"])) == ("fail", 1)
    assert (many["verdict"], [r["verdict"] for r in many["runs"]]) == (
        "fail", ["pass", "fail", "inconclusive"])
    assert set(one) == set(many) == {"verdict", "runs"}
    assert set(one["runs"][0]) == set(many["runs"][0]) == set(many["runs"][2])


def test_every_number_has_its_unit(documents):
    for _, out, _ in documents:
        doc = json.loads(out)
        assert numbers_without_units(doc) == []
    gains = json.loads(documents[0][1])["runs"][0]["gains"]
    assert gains["elbow"]["source"]["given"]["units"] == {"p": "N·m/rad", "d": "N·m·s/rad"}
    assert gains["shoulder"]["source"]["given"]["units"] == {"p": "1/s²", "d": "1/s",
                                                             "i": "1/s³"}


def test_the_reports_validate_against_the_schema(documents):
    jsonschema.Draft202012Validator.check_schema(SCHEMA)
    for _, out, _ in documents:
        jsonschema.validate(json.loads(out), SCHEMA, cls=jsonschema.Draft202012Validator)


def test_the_schema_refuses_a_number_without_its_unit(documents):
    doc = json.loads(documents[0][1])
    del doc["runs"][0]["joints"]["shoulder"]["units"]["max_error"]
    with pytest.raises(jsonschema.ValidationError, match="'max_error' is a required property"):
        jsonschema.validate(doc, SCHEMA, cls=jsonschema.Draft202012Validator)
    assert numbers_without_units(doc) == [".runs[0].joints.shoulder.max_error"]
