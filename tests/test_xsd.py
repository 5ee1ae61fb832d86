"""The editor schemas in ``schemas/``: every fixture validates against its dialect's schema,
real robot descriptions are accepted, and the mistakes the schemas exist for are rejected."""

from __future__ import annotations

from pathlib import Path

import pytest
from lxml import etree

from tests.corpus import corpus_file
from txtool.dialects.read import read_source
from txtool.io.load import load

ROOT = Path(__file__).resolve().parent.parent
FIXTURES = ROOT / "fixtures"
SCHEMA_FILES = {
    "ros1": "ros1_transmission.xsd",
    "ros2-p1": "ros2_control_p1.xsd",
    "ros2-p2": "ros2_control_p2.xsd",
}


def schema(dialect: str) -> etree.XMLSchema:
    return etree.XMLSchema(etree.parse(str(ROOT / "schemas" / SCHEMA_FILES[dialect])))


def errors(dialect: str, document: etree._ElementTree) -> list[str]:
    checker = schema(dialect)
    checker.validate(document)
    return [f"{e.line}: {e.message}" for e in checker.error_log]


def dialects_of(path: Path) -> set[str]:
    return {found.transmission.dialect for found in read_source(load(str(path)))}


FIXTURE_NAMES = sorted(p.name for p in FIXTURES.glob("*.urdf"))


def test_fixtures_are_present() -> None:
    assert {"demo_robot.urdf", "four_bar.ros1.urdf", "rrbot_differential.ros2-p2.urdf"} <= set(
        FIXTURE_NAMES
    )


@pytest.mark.parametrize("name", FIXTURE_NAMES)
def test_fixture_validates_against_its_dialect(name: str) -> None:
    path = FIXTURES / name
    dialects = dialects_of(path)
    assert dialects, f"{name} has no transmission to validate"
    document = etree.parse(str(path))
    for dialect in sorted(dialects):
        found = errors(dialect, document)
        if "broken" in name:
            assert found, f"{name} is broken on purpose but passes the {dialect} schema"
        else:
            assert found == [], f"{name} against the {dialect} schema"


def test_broken_fixture_is_rejected_for_its_ros1_spelling() -> None:
    found = errors("ros2-p2", etree.parse(str(FIXTURES / "broken_robot.urdf")))
    assert any("'mechanicalReduction': This element is not expected" in e for e in found)
    assert any("'fifty' is not a valid value" in e for e in found)


def replaced(name: str, old: str, new: str) -> etree._ElementTree:
    text = (FIXTURES / name).read_text()
    assert old in text
    return etree.ElementTree(etree.fromstring(text.replace(old, new, 1).encode()))


def test_ros1_schema_rejects_a_misspelt_element() -> None:
    document = replaced(
        "demo_robot.urdf",
        "<mechanicalReduction>-100</mechanicalReduction>",
        "<mechanicalReducton>-100</mechanicalReducton>",
    )
    found = errors("ros1", document)
    assert len(found) == 1
    assert "Element 'mechanicalReducton': This element is not expected" in found[0]


def test_ros2_schema_rejects_a_misspelt_element() -> None:
    document = replaced(
        "rrbot_differential.ros2-p2.urdf",
        "<mechanical_reduction>50</mechanical_reduction>",
        "<mechanical_reducton>50</mechanical_reducton>",
    )
    found = errors("ros2-p2", document)
    assert len(found) == 1
    assert "Element 'mechanical_reducton': This element is not expected" in found[0]


def test_ros2_schema_requires_the_role_attribute() -> None:
    document = replaced(
        "rrbot_differential.ros2-p2.urdf", '<joint name="joint2" role="joint2">',
        '<joint name="joint2">',
    )
    found = errors("ros2-p2", document)
    assert len(found) == 1
    assert "Element 'joint': The attribute 'role' is required but missing" in found[0]


def test_proposal_1_schema_rejects_the_role_attribute() -> None:
    document = etree.parse(str(FIXTURES / "rrbot_differential.ros2-p2.urdf"))
    found = errors("ros2-p1", document)
    assert found and all("attribute 'role' is not allowed" in e for e in found)


def test_ros1_schema_rejects_an_unprefixed_interface() -> None:
    document = replaced(
        "four_bar.ros1.urdf",
        "hardware_interface/EffortJointInterface",
        "EffortJointInterface",
    )
    found = errors("ros1", document)
    assert len(found) == 1
    assert "'EffortJointInterface' is not a valid value" in found[0]


def test_ros2_schema_rejects_an_unknown_component_child() -> None:
    document = replaced(
        "rrbot_differential.ros2-p2.urdf", "<hardware>", "<hardwear/><hardware>"
    )
    found = errors("ros2-p2", document)
    assert len(found) == 1
    assert "Element 'hardwear': This element is not expected" in found[0]


XACRO_ROS1 = """<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="trans" params="joint hw">
    <transmission name="${joint}_trans">
      <type>transmission_interface/SimpleTransmission</type>
      <joint name="${joint}">
        <hardwareInterface>${hw}</hardwareInterface>
      </joint>
      <actuator name="${joint}_motor">
        <xacro:if value="${hw != ''}">
          <hardwareInterface>${hw}</hardwareInterface>
        </xacro:if>
        <mechanicalReduction>${160 * 2}</mechanicalReduction>
      </actuator>
    </transmission>
  </xacro:macro>
  <link name="base"><visual><geometry><box size="1 1 1"/></geometry></visual></link>
  <gazebo reference="base"><material>Gazebo/Red</material></gazebo>
</robot>
"""


def test_ros1_schema_accepts_xacro_as_written() -> None:
    assert errors("ros1", etree.ElementTree(etree.fromstring(XACRO_ROS1))) == []


@pytest.mark.parametrize(
    ("name", "dialect"),
    [
        ("franka_ros__panda-gazebo.urdf", "ros1"),
        ("ros2_control_test_assets__multi_joints_transmission.urdf", "ros2-p2"),
        ("ros2_control_test_assets__minimal_robot_hardware_resources.urdf", "ros2-p2"),
    ],
)
def test_real_robot_descriptions_are_accepted(name: str, dialect: str) -> None:
    assert errors(dialect, etree.parse(str(corpus_file(name)))) == []


def test_ros1_schema_rejects_a_real_unprefixed_robot() -> None:
    found = errors("ros1", etree.parse(str(corpus_file("baxter__baxter.urdf"))))
    assert len(found) == 30
    assert all("'EffortJointInterface' is not a valid value" in e for e in found)
