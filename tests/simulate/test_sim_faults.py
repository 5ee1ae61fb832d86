"""The fault matrix: each wrong config fails with its cause named; correct copies pass.

The robot is the 3-DoF test arm (simple shoulder n=50; elbow/wrist coupled by a differential or
a four-bar with actuator reductions 30 and 20, elbow offset 0.1 rad). Each candidate is the
robot's own config with one fault; the cause lines are what ``diagnose`` finds in the maps.
"""

from __future__ import annotations

import pytest

from tests.simulate.robots import arm_ros1, arm_ros2, planar_two_link, write
from txtool.simulation.run import Options, simulate_one

ROS2_WRIST_JOINTS = """      <joint name="elbow" role="joint1"><offset>0.1</offset></joint>
      <joint name="wrist" role="joint2"/>"""


def four_bar_ros2() -> str:
    return arm_ros2().replace("DifferentialTransmission", "FourBarLinkageTransmission")


def swapped_actuator_names() -> str:
    text = arm_ros1().replace('"m_left"', '"m_tmp"').replace('"m_right"', '"m_left"')
    return text.replace('"m_tmp"', '"m_right"')


def ros2_joints_in_other_xml_order() -> str:
    text = arm_ros2()
    assert ROS2_WRIST_JOINTS in text
    reordered = """      <joint name="wrist" role="joint2"/>
      <joint name="elbow" role="joint1"><offset>0.1</offset></joint>"""
    return text.replace(ROS2_WRIST_JOINTS, reordered)


def causes(run) -> list[str]:
    return [r.removeprefix("likely cause: ") for r in run.reasons
            if r.startswith("likely cause: ")]


def run_pair(tmp_path, robot_text: str, candidate_text: str, **options):
    robot = write(tmp_path, "robot.urdf", robot_text)
    candidate = write(tmp_path, "candidate.urdf", candidate_text)
    return simulate_one(Options(robot=robot, duration=options.pop("duration", 2.0), **options),
                        candidate)


FAULTS = {
    "reversed sign": (arm_ros1, lambda: arm_ros1(n=-50), {}, [
        "joint 'shoulder': direction reversed in the config's transmission 't_shoulder' "
        "(reduction -50, the robot's 50)",
    ]),
    "ratio x2": (arm_ros1, lambda: arm_ros1(n=100), {}, [
        "joint 'shoulder': reduction off by a factor 2 in the config's transmission "
        "'t_shoulder' (reduction 100, the robot's 50)",
    ]),
    "offset +0.1 rad": (arm_ros1, lambda: arm_ros1(offset=0.2), {}, [
        "joint 'elbow': offset off by +0.1 rad in the config's transmission 't_wrist' "
        "(0.2, the robot's 0.1)",
    ]),
    # The roles move the offset with the joint, so only the swap is a difference. With equal
    # joint reductions, swapping the differential's joints is also reversing its 2nd actuator.
    "swapped joints": (arm_ros1, lambda: arm_ros1(swap=True), {}, [
        "joints 'elbow' and 'wrist' swapped in the config's transmission 't_wrist' ('elbow' "
        "reads 'wrist'; 'wrist' reads 'elbow'); the same as direction reversed on actuator "
        "'m_right'",
    ]),
    "swapped actuators": (arm_ros1, swapped_actuator_names, {}, [
        "actuators 'm_left' and 'm_right' swapped in the config's transmission 't_wrist' "
        "('m_left' reads 'm_right'; 'm_right' reads 'm_left')",
    ]),
    # ar (30, 20), jr (1, 1): ros2_control applies A^T = [30 20; 0 20] to the actuator efforts
    # that ros_control's inverse of [30 0; -30 20] computed (four_bar_linkage_transmission.h
    # :241-242 and :309-310 at 133d768c), so K = [30 20; 0 20] [30 0; -30 20]^-1 = [2 1; 1 1].
    "ROS 1 four-bar effort on a ROS 2 robot": (
        four_bar_ros2, lambda: arm_ros1(kind="FourBarLinkageTransmission"),
        {"duration": 4.0}, [
            "transmission 't_wrist': the config's effort map is ros_control's (ROS 1) four-bar "
            "map, which does not conserve power (ros_control#523), while the robot's is the "
            "power-conserving one of ros2_control (PR #1837): the applied torques of 'elbow' "
            "and 'wrist' are [2 1; 1 1] times the commanded ones",
        ]),
    "ROS 2 XML order": (arm_ros2, ros2_joints_in_other_xml_order, {}, [
        "joint 'elbow': offset off by -0.1 rad in the config's transmission 't_wrist' "
        "(0, the robot's 0.1)",
        "joint 'wrist': offset off by +0.1 rad in the config's transmission 't_wrist' "
        "(0.1, the robot's 0)",
        "transmission 't_wrist' lists its joints as wrist, elbow: ros2_control takes their "
        "parameters in XML order but binds them to the joints sorted by name (elbow, wrist); "
        "roles are not used (ros2_control#3382)",
    ]),
}


@pytest.mark.parametrize("fault", list(FAULTS))
def test_each_fault_fails_with_its_cause_named(tmp_path, fault):
    robot, candidate, options, expected = FAULTS[fault]
    run = run_pair(tmp_path, robot(), candidate(), **options)
    assert not run.passed
    assert causes(run) == expected
    # The symptoms come first, the causes last.
    assert run.reasons[-len(expected):] == [f"likely cause: {c}" for c in expected]
    assert "tracking error" in run.reasons[0] or "transmissions apply" in run.reasons[0]


CORRECT = {
    "ROS 1 copy": (arm_ros1, arm_ros1, {}),
    "ROS 2 conversion of a ROS 1 robot": (arm_ros1, arm_ros2, {}),
    "ROS 1 conversion of a ROS 2 robot": (arm_ros2, arm_ros1, {}),
    "ROS 1 four-bar with ros2_control's effort map": (
        four_bar_ros2, lambda: arm_ros1(kind="FourBarLinkageTransmission"),
        {"duration": 4.0, "convention": "ros2"}),
}


@pytest.mark.parametrize("case", list(CORRECT))
def test_correct_copies_pass_with_nothing_to_diagnose(tmp_path, case):
    robot, candidate, options = CORRECT[case]
    run = run_pair(tmp_path, robot(), candidate(), **options)
    assert run.passed, run.reasons
    assert not any("differs from the robot" in note for note in run.notes)


def test_a_wrong_effort_map_fails_even_where_tracking_hides_it(tmp_path):
    """High gains and a loose tolerance: the ROS 1 four-bar map tracks, the torque is wrong."""
    run = run_pair(tmp_path, four_bar_ros2(), arm_ros1(kind="FourBarLinkageTransmission"),
                   duration=4.0, bandwidth=100.0, tolerance=0.1)
    assert not any("tracking error" in r for r in run.reasons)
    assert max(j.max_error for j in run.joints.values()) < 0.1
    torque = [r for r in run.reasons if "the robot's transmissions apply" in r]
    assert [r.split(":")[0] for r in torque] == ["joint 'elbow'", "joint 'wrist'"]
    assert "controller commands" in torque[0] and "of the peak torque" in torque[0]
    assert causes(run)[0].startswith("transmission 't_wrist': the config's effort map is "
                                     "ros_control's (ROS 1) four-bar map")


def test_a_difference_within_the_tolerance_fails_all_the_same(tmp_path):
    run = run_pair(tmp_path, arm_ros1(), arm_ros1(offset=0.1005))
    assert not any("tracking error" in r for r in run.reasons)
    assert run.reasons == [
        "the config's maps differ from the robot's (it tracks within the tolerance on this "
        "motion): joint 'elbow': offset off by +0.0005 rad in the config's transmission "
        "'t_wrist' (0.1005, the robot's 0.1)"]
    assert run.verdict == "fail"


def test_an_actuator_reduction_of_a_differential_is_named_on_the_actuator(tmp_path):
    text = arm_ros1().replace("<mechanicalReduction>30</mechanicalReduction>",
                              "<mechanicalReduction>60</mechanicalReduction>")
    run = run_pair(tmp_path, arm_ros1(), text)
    assert causes(run) == ["actuator 'm_left': reduction off by a factor 2 in the config's "
                           "transmission 't_wrist' (reduction 60, the robot's 30)"]


def test_a_different_transmission_kind_is_named(tmp_path):
    run = run_pair(tmp_path, arm_ros1(), arm_ros1(kind="FourBarLinkageTransmission"))
    assert causes(run) == [
        f"joint '{j}': the config has a four-bar transmission 't_wrist' where the robot has a "
        "differential transmission 't_wrist'" for j in ("elbow", "wrist")]


def two_link(first: str, second: str) -> str:
    simple = ('<transmission name="t_{0}"><type>transmission_interface/SimpleTransmission</type>'
              '<joint name="{1}"/><actuator name="m_{0}"><mechanicalReduction>40'
              "</mechanicalReduction></actuator></transmission>")
    transmissions = simple.format("q1", first) + simple.format("q2", second)
    return planar_two_link(1.0, 0.5, 0.5, 0.2, 0.2, 0.01, 0.01).replace(
        "</robot>", transmissions + "</robot>")


def test_swapped_simple_transmissions_name_joints_and_actuators(tmp_path):
    run = run_pair(tmp_path, two_link("q1", "q2"), two_link("q2", "q1"))
    assert not run.passed
    assert causes(run) == [
        "joints 'q1' and 'q2' swapped in the config's transmission 't_q2' ('q1' reads 'q2'; "
        "'q2' reads 'q1'); the same as swapping actuators 'm_q1' and 'm_q2'"]


def test_a_self_check_that_fails_on_limits_blames_no_transmission(tmp_path):
    robot = write(tmp_path, "arm.urdf", arm_ros1())
    params = write(tmp_path, "p.toml", "[actuators.m_left]\nvelocity_limit = 10.0\n")
    # the default motion is slowed to the limit; this trajectory is not (m_left: 30 x elbow)
    fast = write(tmp_path, "fast.csv", "time,elbow\n0,0\n1,0.5\n2,0\n")
    own = simulate_one(Options(robot=robot, params=params, trajectory=fast), None)
    assert not own.passed and not causes(own)
    assert any(r.startswith("actuator 'm_left'") for r in own.reasons), own.reasons
    copy = write(tmp_path, "copy.urdf", arm_ros1())
    run = simulate_one(Options(robot=robot, params=params, trajectory=fast), copy)
    assert causes(run) == ["not the transmissions: the config's maps equal the robot's (look "
                           "at the gains, the limits or the reference)"]


def test_a_changed_hardware_interface_fails_naming_both(tmp_path):
    position = arm_ros1().replace(
        '<joint name="shoulder"><hardwareInterface>hardware_interface/EffortJointInterface',
        '<joint name="shoulder"><hardwareInterface>hardware_interface/PositionJointInterface')
    assert position != arm_ros1()
    run = run_pair(tmp_path, arm_ros1(), position)
    assert "joint 'shoulder': the config commands it through position, the robot through " \
           "effort" in run.reasons
    assert run.verdict == "fail"


def test_the_same_interface_in_another_dialect_is_no_change(tmp_path):
    from tests.simulate.robots import arm_ros2

    run = run_pair(tmp_path, arm_ros1(), arm_ros2())
    assert not any("commands it through" in r for r in run.reasons)


def twin_fingers(left_joint: str, right_joint: str) -> str:
    """Two identical fingers on the base with identical transmissions."""
    from tests.simulate.robots import link

    def finger(name: str, child: str, y: float) -> str:
        return (f'<joint name="{name}" type="revolute"><parent link="base"/>'
                f'<child link="{child}"/><origin xyz="0 {y} 0"/><axis xyz="0 0 1"/>'
                '<limit lower="-1" upper="1" effort="10" velocity="2"/></joint>')

    def transmission(name: str, joint: str, actuator: str) -> str:
        return (f'<transmission name="{name}"><type>transmission_interface/SimpleTransmission'
                f'</type><joint name="{joint}"><hardwareInterface>hardware_interface/'
                f'EffortJointInterface</hardwareInterface></joint><actuator name="{actuator}">'
                '<mechanicalReduction>40</mechanicalReduction></actuator></transmission>')

    return (f'<robot name="gripper"><link name="base"/>{link("l", 0.1, 0.05)}'
            f'{link("r", 0.1, 0.05)}{finger("left", "l", 0.05)}{finger("right", "r", -0.05)}'
            f'{transmission("t_left", left_joint, "m_left")}'
            f'{transmission("t_right", right_joint, "m_right")}</robot>')


def test_swapped_twin_joints_fail(tmp_path):
    run = run_pair(tmp_path, twin_fingers("left", "right"), twin_fingers("right", "left"))
    assert run.verdict == "fail"
    assert any("joints 'left' and 'right' swapped" in r for r in run.reasons), run.reasons
