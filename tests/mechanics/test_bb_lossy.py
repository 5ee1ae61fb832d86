"""``convert --to bb`` refuses (exit 1, nothing written) what BB cannot carry faithfully, with
the reason; ``--allow-lossy`` writes it anyway and reports the same reasons as warnings."""

from __future__ import annotations

from pathlib import Path

import pytest

from tests.mechanics.test_bb_export import convert, robot, ros1, ros2

SIMPLE = "transmission_interface/SimpleTransmission"


def refused(tmp_path: Path, xml: str) -> list[str]:
    """The error lines of a refused conversion; checks that nothing was written."""
    code, out, err = convert(tmp_path, xml)
    assert (code, out) == (1, "")
    lines = err.splitlines()
    assert lines[-1].endswith("would be lost; nothing written (use --allow-lossy to accept)")
    errors = [line for line in lines if line.startswith("error: ")]
    code, out, err_lossy = convert(tmp_path, xml, "--allow-lossy")
    assert code == 0
    assert [line.replace("warning: ", "error: ", 1) for line in err_lossy.splitlines()
            if line.startswith("warning: ")] == errors
    return [line.removeprefix("error: ") for line in errors]


def test_legacy_type_attribute_that_ros_control_skips(tmp_path: Path) -> None:
    body = """<transmission name="t" type="SimpleTransmission"><joint name="shoulder"/>
      <actuator name="m"/><mechanicalReduction>40</mechanicalReduction></transmission>"""
    assert refused(tmp_path, robot(body)) == [
        "transmission 't': ros_control skips it: its type 'SimpleTransmission' is a type= "
        "attribute and it has no <type> element (TX302 fixes that)",
        "transmission 't': ros_control never reads a <mechanicalReduction> directly under "
        "<transmission>; exported as the actuator's",
    ]


def test_joint_missing_from_the_robot(tmp_path: Path) -> None:
    assert refused(tmp_path, robot(ros1("t", "elbow", "m", "3", "0.1"))) == [
        "transmission 't': joint 'elbow' is not in this robot: its type, and so the offset's "
        "unit, is unknown (written as an angle)"]


def test_joint_dropped_by_bb_importer(tmp_path: Path) -> None:
    """A joint whose parent link is not defined (a world anchor) is dropped by BB's importer
    (lib/bb/urdf/importer.ex:117-135 @64ab268)."""
    joints = """<joint name="anchor" type="revolute"><parent link="world"/>
      <child link="base"/></joint>"""
    assert refused(tmp_path, robot(ros1("t", "anchor", "m", "3"), joints)) == [
        "transmission 't': joint 'anchor' is dropped by BB's URDF importer (its parent link "
        "'world' is not defined)"]


def test_fixed_joint(tmp_path: Path) -> None:
    joints = '<joint name="bolt" type="fixed"><parent link="base"/><child link="arm"/></joint>'
    assert refused(tmp_path, robot(ros1("t", "bolt", "m", "3"), joints)) == [
        "transmission 't': joint 'bolt' is fixed: an actuator on it has nothing to move"]


@pytest.mark.parametrize("joints, expected", [
    # ros2_control's SimpleTransmission::configure refuses two joint names
    # (transmission_interface simple_transmission.hpp: "Joint names given to transmissions
    # should be identical"), so the source does not load either.
    ('<joint name="shoulder" role="joint1"/><joint name="slide" role="joint1"/>',
     ["transmission 't': a simple transmission joins one joint and one actuator, this has 2 "
      "and 1; its first joint and actuator are exported",
      "transmission 't': not loadable: a simple transmission takes one joint, found "
      "'shoulder', 'slide' (configure: joint names should be identical)"]),
    ("", ["transmission 't': a simple transmission without a joint has nothing to drive"]),
])
def test_simple_transmission_with_two_joints_or_none(tmp_path: Path, joints: str,
                                                      expected: list[str]) -> None:
    body = ros2(f"""<transmission name="t"><plugin>{SIMPLE}</plugin>{joints}
      <actuator name="m" role="actuator1"/></transmission>""")
    assert refused(tmp_path, robot(body)) == expected


def test_ros1_simple_with_two_joints_is_not_exported(tmp_path: Path) -> None:
    body = f"""<transmission name="t"><type>{SIMPLE}</type><joint name="shoulder"/>
      <joint name="slide"/><actuator name="m"><mechanicalReduction>2</mechanicalReduction>
      </actuator></transmission>"""
    assert refused(tmp_path, robot(body)) == [
        "transmission 't': a simple transmission joins one joint and one actuator, this has 2 "
        "and 1 (ros_control refuses it)"]
    assert convert(tmp_path, robot(body), "--allow-lossy")[1] == ""


def test_joint_reduction_that_ros_control_ignores(tmp_path: Path) -> None:
    body = ros1("t", "shoulder", "m", "10",
                joint_extra="<mechanicalReduction>4</mechanicalReduction>")
    assert refused(tmp_path, robot(body)) == [
        "joint 'shoulder': <mechanicalReduction> 4 is ignored by ros_control for simple "
        "transmissions (it reads the actuator's); not exported"]
    assert "      reduction 10.0\n" in convert(tmp_path, robot(body), "--allow-lossy")[1]


def test_actuator_values_that_ros2_control_ignores(tmp_path: Path) -> None:
    body = ros2(f"""<transmission name="t"><plugin>{SIMPLE}</plugin>
      <actuator name="m" role="actuator1"><mechanical_reduction>50</mechanical_reduction>
      <offset>0.2</offset></actuator><joint name="shoulder" role="joint1"/></transmission>""")
    assert refused(tmp_path, robot(body)) == [
        "actuator 'm': <mechanical_reduction> 50 is ignored by ros2_control for simple "
        "transmissions (it reads the joint's); not exported",
        "actuator 'm': <offset> 0.2 is ignored by ros2_control for simple transmissions (it "
        "reads the joint's); not exported",
    ]
    out = convert(tmp_path, robot(body), "--allow-lossy")[1]
    assert "  actuator :m, Driver\n" in out  # runs 1:1, as ros2_control loads it


def test_actuator_name_invented(tmp_path: Path) -> None:
    body = ros2(f"""<transmission name="t"><plugin>{SIMPLE}</plugin>
      <joint name="shoulder" role="joint1"><mechanical_reduction>9</mechanical_reduction>
      </joint></transmission>""")
    assert refused(tmp_path, robot(body)) == [
        "transmission 't': no actuator: named it :shoulder_motor (BB needs a name; "
        "ros2_control calls it 'actuator1')"]
    assert "  actuator :shoulder_motor, Driver do\n" in convert(
        tmp_path, robot(body), "--allow-lossy")[1]


def test_actuator_named_like_a_link(tmp_path: Path) -> None:
    """Names are unique across links, joints, sensors and actuators
    (lib/bb/dsl/uniqueness_transformer.ex:7-11 @107cca2)."""
    assert refused(tmp_path, robot(ros1("t", "shoulder", "arm", "9"))) == [
        "transmission 't': actuator :arm is already the name of a link or joint (BB needs link, "
        "joint and actuator names unique); named it :arm_2"]


def test_actuator_name_used_twice(tmp_path: Path) -> None:
    # open_manipulator's omy_f3m.urdf names the gripper's actuators like the arm's
    body = ros1("t1", "shoulder", "actuator1", "9") + ros1("t2", "slide", "actuator1", "3")
    assert refused(tmp_path, robot(body)) == [
        "transmission 't2': actuator :actuator1 is already the name of the actuator of "
        "transmission 't1' (BB needs link, joint and actuator names unique); named it "
        ":actuator1_2"]


@pytest.mark.parametrize("kind, what", [
    ("DifferentialTransmission", "differential type"),
    ("FourBarLinkageTransmission", "four-bar type"),
])
def test_coupled_transmissions(tmp_path: Path, kind: str, what: str) -> None:
    body = f"""<transmission name="c"><type>transmission_interface/{kind}</type>
      <joint name="shoulder"><role>joint1</role></joint><joint name="slide"><role>joint2</role>
      </joint><actuator name="a1"><role>actuator1</role></actuator>
      <actuator name="a2"><role>actuator2</role></actuator></transmission>"""
    assert refused(tmp_path, robot(body)) == [
        f"transmission 'c': {what} 'transmission_interface/{kind}' is not representable in BB "
        "(BB has simple transmissions only)"]


def test_zero_reduction_is_not_exported(tmp_path: Path) -> None:
    # BB would accept reduction 0.0 and raise ArithmeticError dividing by it at run time
    assert refused(tmp_path, robot(ros1("t", "shoulder", "m", "0"))) == [
        "transmission 't': not loadable: reduction ratio cannot be zero"]


def test_member_without_a_name(tmp_path: Path) -> None:
    # ros_control's parser_test_invalid.urdf: <actuator name=""> and <joint name="">
    assert refused(tmp_path, robot(ros1("t", "shoulder", "", "9"))) == [
        "transmission 't': a joint or actuator without a name (ros_control's parser refuses it)"]
