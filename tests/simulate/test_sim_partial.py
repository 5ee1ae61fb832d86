"""Partial robots: what cannot be simulated is left out with a note; the rest still runs."""

from __future__ import annotations

import json

import numpy as np
import pytest
from click.testing import CliRunner

from tests.simulate.robots import EFFORT, arm_ros1, link, write
from txtool.cli import cli
from txtool.simulation.run import Options, simulate_one

CUSTOM = f"""
  <transmission name="t_custom">
    <type>acme_mechanism_model/MagicTransmission</type>
    <joint name="shoulder">{EFFORT}</joint>
    <actuator name="m_shoulder"><mechanicalReduction>50</mechanicalReduction></actuator>
  </transmission>"""


def txtool(*args: str) -> tuple[int, str, str]:
    result = CliRunner().invoke(cli, ["simulate", *args], catch_exceptions=False)
    return result.exit_code, result.stdout, result.stderr


def test_custom_type_is_left_out_and_its_joint_driven_directly_with_a_json_note(tmp_path):
    robot = write(tmp_path, "custom.urdf", arm_ros1(shoulder=False, extra=CUSTOM))
    code, out, err = txtool(robot, "--format", "json", "--duration", "1")
    assert (code, err) == (0, "")
    doc = json.loads(out)["runs"][0]
    assert doc["verdict"] == "pass"  # the other transmission was checked
    line = (tmp_path / "custom.urdf").read_text().splitlines().index(
        "  <transmission name=\"t_custom\">") + 1
    assert (f"{robot}:{line}: transmission 't_custom' is not simulated: custom type "
            "'acme_mechanism_model/MagicTransmission' has no standard maths") in doc["notes"]
    assert "driven directly (no transmission in the robot, identity map): shoulder" \
        in doc["notes"]
    assert doc["actuators"]["shoulder"]["transmission"] is None  # a direct actuator
    assert doc["actuators"]["m_left"]["transmission"] == "t_wrist"


def test_skip_leaves_a_transmission_out_and_says_so(tmp_path):
    robot = write(tmp_path, "arm.urdf", arm_ros1())
    code, out, err = txtool(robot, "--skip", "t_wrist", "--duration", "1")
    assert (code, err) == (0, "")
    assert "transmission 't_wrist' is not simulated: skipped with --skip" in out
    assert "driven directly (no transmission in the robot, identity map): elbow, wrist" in out
    assert "PASS" in out
    code, out, err = txtool(robot, "--skip", "t_nope")
    assert code == 2 and out == ""
    assert err.strip() == f"txtool: --skip: no transmission named 't_nope' in {robot}"


def mimic_robot(leader: str, follower: str, transmission_on: str) -> str:
    """Two links on the base; ``follower`` mimics ``leader`` (-1, +0.1); one transmission."""
    def joint(name: str, child: str, extra: str = "") -> str:
        return (f'<joint name="{name}" type="revolute"><parent link="base"/>'
                f'<child link="{child}"/><axis xyz="0 0 1"/>'
                f'<limit lower="-1" upper="1" effort="10" velocity="2"/>{extra}</joint>')
    mimic = f'<mimic joint="{leader}" multiplier="-1" offset="0.1"/>'
    return f"""<robot name="gripper"><link name="base"/>{link("a", 0.5, 0.1)}{link("b", 0.5, 0.1)}
  {joint(leader, "a")}{joint(follower, "b", mimic)}
  <transmission name="t_finger">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="{transmission_on}">{EFFORT}</joint>
    <actuator name="m_finger"><mechanicalReduction>20</mechanicalReduction></actuator>
  </transmission>
</robot>"""


def test_transmission_on_a_mimic_joint_is_left_out_and_the_mimic_follows(tmp_path):
    # pinocchio places this mimic ("b_follow" after its leader "a_lead")
    robot = write(tmp_path, "g.urdf", mimic_robot("a_lead", "b_follow", "b_follow"))
    run = simulate_one(Options(robot=robot, duration=1.0), None)
    # its only transmission is left out: nothing of the config is checked
    assert (run.verdict, run.reasons, run.joints) == ("inconclusive", [], {})
    assert any("transmission 't_finger' is not simulated: joint 'b_follow' is a mimic joint "
               "(it follows its leader 'a_lead' and takes no transmission)" in n
               for n in run.notes)
    assert "mimic joints follow their leaders: b_follow" in run.notes


def test_mimic_pinocchio_cannot_place_becomes_an_independent_joint_following_its_leader(
        tmp_path):
    # "follow" sorts before its leader "lead": pinocchio refuses to build it with mimics
    robot = write(tmp_path, "g.urdf", mimic_robot("lead", "follow", "follow"))
    run = simulate_one(Options(robot=robot, duration=1.0), None)
    assert run.passed, run.reasons
    assert set(run.joints) == {"lead", "follow"}
    assert any(n.startswith("pinocchio cannot place the mimic joints (The parent joint of the "
                            "mimic joint is not in the kinematic tree)") and n.endswith(
                            "reference follows their leader: follow") for n in run.notes)
    q_ref = run.series.q_ref
    lead, follow = run.series.joints.index("lead"), run.series.joints.index("follow")
    assert np.ptp(q_ref[:, lead]) > 0.1
    assert np.allclose(q_ref[:, follow], -q_ref[:, lead] + 0.1)
    # the mimic is now a joint of the model: its transmission drives it
    assert run.actuators["m_finger"].transmission == "t_finger"


def test_transmission_on_an_absent_or_fixed_joint_is_left_out(tmp_path):
    absent = CUSTOM.replace("acme_mechanism_model/MagicTransmission",
                            "transmission_interface/SimpleTransmission").replace(
        '"shoulder"', '"ghost"').replace("t_custom", "t_ghost").replace("m_shoulder", "m_ghost")
    fixed = ('<link name="tool"/><joint name="tool_mount" type="fixed"><parent link="l3"/>'
             '<child link="tool"/></joint>' + absent.replace('"ghost"', '"tool_mount"')
             .replace("t_ghost", "t_tool").replace("m_ghost", "m_tool"))
    robot = write(tmp_path, "arm.urdf", arm_ros1(extra=absent + fixed))
    run = simulate_one(Options(robot=robot, duration=1.0), None)
    assert run.passed, run.reasons
    notes = " | ".join(run.notes)
    assert "transmission 't_ghost' is not simulated: joint 'ghost' is not a joint of the " \
           "robot" in notes
    assert "transmission 't_tool' is not simulated: joint 'tool_mount' is a fixed joint" in notes


def test_a_joint_moving_only_massless_links_is_locked(tmp_path):
    massless = ('<link name="frame"/><joint name="spin" type="revolute"><parent link="l3"/>'
                '<child link="frame"/><axis xyz="0 0 1"/>'
                '<limit lower="-1" upper="1" effort="1" velocity="1"/></joint>')
    robot = write(tmp_path, "arm.urdf", arm_ros1(extra=massless))
    run = simulate_one(Options(robot=robot, duration=1.0), None)
    assert run.passed, run.reasons
    assert "spin" not in run.joints
    assert "joint 'spin' moves only links without mass or inertia (frame): it is locked and " \
           "not simulated" in run.notes


def test_nothing_simulable_is_one_line_exit_2(tmp_path):
    robot = write(tmp_path, "fixed.urdf", '<robot name="r"><link name="a"/><link name="b"/>'
                  '<joint name="j" type="fixed"><parent link="a"/><child link="b"/></joint>'
                  "</robot>")
    code, out, err = txtool(robot)
    assert (code, out) == (2, "")
    assert err.strip() == f"txtool: {robot}: the robot has no moving joints"


@pytest.mark.parametrize("loader", ["auto", "ros2"])
def test_both_dialects_run_the_ros2_transmissions(tmp_path, loader):
    from tests.simulate.robots import arm_both

    robot = write(tmp_path, "both.urdf", arm_both())
    code, out, err = txtool(robot, "--loader", loader, "--format", "json", "--duration", "1")
    doc = json.loads(out)["runs"][0]
    assert (code, err) == (0, "")
    said = any("the ROS 2 ones are simulated" in n for n in doc["notes"])
    assert said == (loader == "auto")


BARE = ('<robot name="r"><link name="a"/><link name="b"/>'
        '<joint name="elbow" type="revolute"><parent link="a"/><child link="b"/>'
        '<axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>'
        "{}</robot>")


def test_a_robot_without_inertias_or_transmissions_is_inconclusive(tmp_path):
    """Nothing of the config to check whatever the model: inconclusive (exit 3) as
    docs/simulate.md promises for a config without transmissions, the inertias in a note."""
    robot = write(tmp_path, "bare.urdf", BARE.format(""))
    code, out, err = txtool(robot)
    assert (code, err) == (3, "")
    assert out.splitlines()[-2:] == [
        f"note: the robot could not be simulated either: {robot}: no joint moves a link with "
        "mass or inertia (joints elbow): simulate needs the URDF's <inertial> elements",
        "INCONCLUSIVE: nothing checked: the config has no transmission: every joint is driven "
        "directly"]


def test_a_robot_without_inertias_says_so(tmp_path):
    robot = write(tmp_path, "bare.urdf", BARE.format(
        '<transmission name="t"><type>transmission_interface/SimpleTransmission</type>'
        '<joint name="elbow"><hardwareInterface>hardware_interface/EffortJointInterface'
        '</hardwareInterface></joint><actuator name="m"><mechanicalReduction>2'
        "</mechanicalReduction></actuator></transmission>"))
    code, out, err = txtool(robot)
    assert (code, out) == (2, "")
    assert err.strip() == (f"txtool: {robot}: no joint moves a link with mass or inertia "
                           "(joints elbow): simulate needs the URDF's <inertial> elements")
