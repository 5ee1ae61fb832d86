"""``txtool show``: what each loader binds (``--effective`` and the JSON's ``effective``).

Loader facts, from the loaders' source:

* ros_control indexes coupled parameters by <role> (ros-controls/ros_control
  transmission_interface/src/four_bar_linkage_transmission_loader.cpp:49 @17b626a) and fills
  the data vectors in XML order (transmission_interface/src/
  joint_state_interface_provider.cpp:132 @133d768).
* ros2_control takes coupled parameters in XML order (ros-controls/ros2_control
  transmission_interface/src/four_bar_linkage_transmission_loader.cpp:34-41 @7714d16) and
  orders the handles by name (transmission_interface/include/transmission_interface/
  accessor.hpp:43-45 @433ae5d).
* ros2_control's parser appends ``actuator1`` in an actuator component and throws unless such
  a transmission has one joint, and when a transmission joint is not a component joint
  (hardware_interface/src/component_parser.cpp:519-531, 546-558 @157446a).

Regenerate the golden files with ``TXTOOL_UPDATE_GOLDEN=1 pytest tests/foundation``.
"""

from __future__ import annotations

import json
import os
import textwrap
from pathlib import Path

import jsonschema
import pytest

from tests.corpus import corpus_dir, corpus_file, corpus_names

ROOT = Path(__file__).resolve().parents[2]
GOLDEN = Path(__file__).parent / "golden"
SCHEMA = json.loads((ROOT / "schemas" / "transmission.schema.json").read_text())
ROS1_FOUR_BAR = "ros_control__four_bar_linkage_transmission_loader_full.urdf"
ROS2_RESOURCES = "ros2_control_test_assets__minimal_robot_hardware_resources.urdf"


def golden(name: str, text: str) -> str:
    path = GOLDEN / name
    if os.environ.get("TXTOOL_UPDATE_GOLDEN") == "1":
        path.parent.mkdir(exist_ok=True)
        path.write_text(text)
    return path.read_text()


def write(tmp_path: Path, body: str, name: str = "robot.urdf") -> str:
    path = tmp_path / name
    path.write_text(f'<robot name="r">\n{textwrap.dedent(body).strip()}\n</robot>\n')
    return str(path)


def effective(run, path: str) -> list[dict]:
    code, out, err = run("show", path, "--format", "json")
    assert (code, err) == (0, "")
    data = json.loads(out)
    jsonschema.Draft202012Validator(SCHEMA).validate(data)
    return [t["effective"] for t in data["transmissions"]]


@pytest.mark.parametrize("name", [ROS1_FOUR_BAR, ROS2_RESOURCES])
def test_json_of_loader_test_robots_matches_golden(run, name):
    path = str(corpus_file(name))
    code, out, err = run("show", path, "--format", "json")
    assert (code, err) == (0, "")
    stable = out.replace(json.dumps(path)[1:-1], f"<corpus>/{name}")
    assert stable == golden(name.replace(".urdf", ".show.json"), stable)


def test_ros1_four_bar_binds_parameters_by_role_and_data_in_xml_order(run):
    (b,) = effective(run, str(corpus_file(ROS1_FOUR_BAR)))
    assert (b["loader"], b["loadable"], b["parameter_order"], b["data_order"]) == (
        "ros1", True, "role", "xml")
    # bar_joint (role joint2) is written first: it fills data slot 0, where joint1's values sit.
    assert [(s["joint"], s["joint_parameters_of"], s["joint_reduction"], s["joint_offset"])
            for s in b["slots"]] == [("bar_joint", "foo_joint", 2.0, 0.5),
                                     ("foo_joint", "bar_joint", -2.0, -0.5)]
    assert [(s["actuator"], s["actuator_reduction"]) for s in b["slots"]] == [
        ("foo_actuator", 50.0), ("bar_actuator", -50.0)]


def test_ros2_actuator_component_gets_actuator1_and_the_joint_reduction(run):
    simple, differential, four_bar = effective(run, str(corpus_file(ROS2_RESOURCES)))
    assert simple["component_type"] == "actuator"
    assert simple["added_actuators"] == ["actuator1"]
    (slot,) = simple["slots"]
    assert (slot["joint"], slot["joint_reduction"], slot["joint_offset"], slot["actuator"]) == (
        "joint1", 325.949, 0.0, "actuator1")
    assert (slot["defaults"], slot["not_read"]) == (["joint_offset"], ["actuator_reduction"])
    for b in (differential, four_bar):
        assert (b["parameter_order"], b["data_order"], b["notes"]) == ("xml", "name", [])
        assert [(s["joint"], s["joint_reduction"], s["actuator"], s["actuator_reduction"])
                for s in b["slots"]] == [("joint2", 2.0, "joint2_motor", 50.0),
                                         ("joint3", -2.0, "joint3_motor", -50.0)]


def test_text_view_of_the_actuator_component(run):
    path = str(corpus_file(ROS2_RESOURCES))
    code, out, err = run("show", "--effective", path)
    assert (code, err) == (0, "")
    assert out.startswith(f"{path}\n3 transmission(s), as their loaders bind them\n\n")
    block = out.split("\n\n")[1]
    assert block == textwrap.dedent("""\
        ros2_control_transmission1 (line 135): SimpleTransmission
          read by ros2_control in an actuator component
          #   joint    reduction        offset   actuator     reduction
          ─────────────────────────────────────────────────────────────
          0   joint1     325.949   0 (default)   actuator1   (not read)
          note: ros2_control's parser appends actuator 'actuator1' (reduction 1, offset 0) to a transmission
            of an actuator component""")


def test_ros2_handles_sorted_by_name_take_parameters_in_xml_order(run, tmp_path):
    path = write(tmp_path, """
        <ros2_control name="hw" type="system">
          <joint name="wrist_roll"/><joint name="wrist_flex"/>
          <transmission name="wrist">
            <plugin>transmission_interface/DifferentialTransmission</plugin>
            <joint name="wrist_roll" role="joint1"><mechanical_reduction>2</mechanical_reduction></joint>
            <joint name="wrist_flex" role="joint2"><mechanical_reduction>4</mechanical_reduction></joint>
            <actuator name="m1" role="actuator1"/><actuator name="m2" role="actuator2"/>
          </transmission>
        </ros2_control>""")
    (b,) = effective(run, path)
    assert [(s["joint"], s["joint_parameters_of"], s["joint_reduction"]) for s in b["slots"]] == [
        ("wrist_flex", "wrist_roll", 2.0), ("wrist_roll", "wrist_flex", 4.0)]
    assert b["notes"][0] == ("joint 'wrist_flex' is mapped with the parameters written on "
                             "'wrist_roll' (ros2_control takes parameters in XML order and "
                             "orders handles by name)")
    code, out, _ = run("show", "--effective", path)
    assert code == 0
    assert "  0   wrist_flex (values of wrist_roll)           2" in out
    assert all(len(line) <= 100 for line in out.splitlines()[1:])


def test_ros2_silent_defaults_are_named(run, tmp_path):
    (b,) = effective(run, write(tmp_path, """
        <ros2_control name="hw" type="system">
          <joint name="j"/>
          <transmission name="t">
            <plugin>transmission_interface/SimpleTransmission</plugin>
            <joint name="j" role="joint1"><mechanical_reduction>fifty</mechanical_reduction></joint>
            <actuator name="m" role="actuator1"><mechanical_reduction>50</mechanical_reduction></actuator>
          </transmission>
        </ros2_control>"""))
    (slot,) = b["slots"]
    assert (slot["joint_reduction"], slot["defaults"]) == (1.0, ["joint_reduction",
                                                                 "joint_offset"])
    assert b["notes"] == [
        "'j' mechanical_reduction 'fifty' is not a number: ros2_control silently uses 1",
        "actuator 'm' reduction is ignored: ros2_control's simple transmission reads the joint's",
    ]


@pytest.mark.parametrize(("component", "joints", "reason"), [
    ('type="actuator"', '<joint name="a"/><joint name="b"/>',
     "ros2_control's parser refuses the component: a transmission of an actuator component "
     "must have exactly one joint, found 2"),
    ('type="system"', '<joint name="a"/>',
     "ros2_control's parser refuses the component: joint 'b' is not declared in "
     '<ros2_control name="hw">'),
])
def test_what_ros2_control_parser_refuses(run, tmp_path, component, joints, reason):
    (b,) = effective(run, write(tmp_path, f"""
        <ros2_control name="hw" {component}>
          {joints}
          <transmission name="t">
            <plugin>transmission_interface/DifferentialTransmission</plugin>
            <joint name="a" role="joint1"/><joint name="b" role="joint2"/>
            <actuator name="m1" role="actuator1"/><actuator name="m2" role="actuator2"/>
          </transmission>
        </ros2_control>"""))
    assert (b["loadable"], b["reason"], b["slots"]) == (False, reason, [])


def test_plugins_are_unknown_and_misspelt_standard_types_refused(run, tmp_path):
    custom, typo = effective(run, write(tmp_path, """
        <transmission name="c"><type>pr2_mechanism_model/SimpleTransmission</type>
          <joint name="j"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>
          <actuator name="m"><mechanicalReduction>1</mechanicalReduction></actuator></transmission>
        <transmission name="t"><type>transmission_interface/SimpleTansmission</type>
          <joint name="j"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>
          <actuator name="m"><mechanicalReduction>1</mechanicalReduction></actuator></transmission>"""))
    assert custom["loadable"] is None and "a plugin, if one is installed" in custom["reason"]
    assert typo["loadable"] is False
    assert typo["reason"].startswith(
        "no transmission plugin is named 'transmission_interface/SimpleTansmission'")


def test_ros1_refusal_is_the_loader_reason(run):
    bindings = effective(run, str(corpus_file(
        "ros_control__four_bar_linkage_transmission_loader_invalid.urdf")))
    assert len(bindings) == 14 and not any(b["loadable"] for b in bindings)
    assert bindings[0]["reason"] == "joint 'bar_joint' has role None, expected joint1 or joint2"


@pytest.mark.parametrize("name", corpus_names())
def test_corpus_json_fits_the_schema_and_text_fits_100_columns(run, name):
    path = corpus_dir() / name
    if name == "MANIFEST.tsv":
        return
    code, out, _ = run("show", str(path), "--format", "json", "--actuator-limits")
    if code == 2:
        return  # needs packages or xacro arguments; the reader's tests cover that
    assert code == 0
    jsonschema.Draft202012Validator(SCHEMA).validate(json.loads(out))
    code, out, _ = run("show", str(path), "--effective")
    assert code == 0
    assert [line for line in out.splitlines()[1:] if len(line) > 100] == []


def test_simple_transmissions_name_what_their_loader_ignores_or_invents(run, tmp_path):
    ros1, ros2 = effective(run, write(tmp_path, """
        <transmission name="r1"><type>transmission_interface/SimpleTransmission</type>
          <joint name="a"><mechanicalReduction>9</mechanicalReduction><offset>0.25</offset>
            <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>
          <actuator name="m"><mechanicalReduction>50</mechanicalReduction></actuator></transmission>
        <ros2_control name="hw" type="system"><joint name="b"/>
          <transmission name="r2"><plugin>transmission_interface/SimpleTransmission</plugin>
            <joint name="b" role="joint1"><mechanical_reduction>3</mechanical_reduction></joint>
          </transmission></ros2_control>"""))
    (slot,) = ros1["slots"]
    assert (slot["actuator_reduction"], slot["joint_offset"], slot["not_read"]) == (
        50.0, 0.25, ["joint_reduction"])
    assert ros1["notes"] == ["joint 'a' reduction is ignored: ros_control's simple transmission "
                             "reads the actuator's"]
    (slot,) = ros2["slots"]
    assert (slot["joint_reduction"], slot["actuator"], slot["not_read"]) == (
        3.0, "actuator1", ["actuator_reduction"])
    assert ros2["notes"] == ["no <actuator>: the hardware plugin names the actuator handle "
                             "('actuator1' stands in here)"]


MISSPELT = """
    <transmission name="t">
      <type>transmission_interface/SimpleTransmission</type>
      <joint name="j"><hardwareInterface>PositionInterface</hardwareInterface></joint>
      <actuator name="m"><mechanicalReduction>50</mechanicalReduction></actuator>
    </transmission>
    <transmission name="good">
      <type>transmission_interface/SimpleTransmission</type>
      <joint name="k">
        <hardwareInterface>hardware_interface/PositionJointInterface</hardwareInterface>
      </joint>
      <actuator name="n"><mechanicalReduction>50</mechanicalReduction></actuator>
    </transmission>
"""


def test_show_marks_what_validate_says_the_loader_refuses(run, tmp_path):
    """An interface ros_control refuses (TX205; TX204 says why) no longer shows like a good
    one."""
    path = write(tmp_path, MISSPELT)
    code, out, err = run("show", path)
    assert (code, err) == (0, "")
    rows = out.splitlines()
    assert "┃ validate" in rows[2]
    assert "✗ TX205, ! TX204" in next(row for row in rows if "│ t:2 " in row)
    assert not any("TX" in row for row in rows if "good" in row)
    clean = write(tmp_path, MISSPELT.replace(">PositionInterface<",
                                             ">hardware_interface/PositionJointInterface<"),
                  "clean.urdf")
    assert "┃ validate" not in run("show", clean)[1]


def test_show_effective_says_the_loader_refuses_what_it_reads(run, tmp_path):
    code, out, err = run("show", "--effective", write(tmp_path, MISSPELT))
    assert (code, err) == (0, "")
    refused, good = out.split("\n\n")[1:3]
    assert refused.splitlines()[1] == ("  read by ros_control, which refuses it or reads it "
                                       "other than written (TX205)")
    assert ("  validate: error TX205: transmission 't' names no hardware interface ros_control "
            "knows\n    ('PositionInterface')") in refused
    assert good.splitlines()[1] == "  read by ros_control" and "validate" not in good
