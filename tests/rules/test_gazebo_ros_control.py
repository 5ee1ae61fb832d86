"""A robot Gazebo loads through gazebo_ros_control's DefaultRobotHWSim is judged by it too.

gazebo_ros_pkgs gazebo_ros_control/src/default_robot_hw_sim.cpp ``initSim`` @01c3a2c: the
first joint's first ``<hardwareInterface>``, with or without the ``hardware_interface/``
prefix (a deprecation warning), the actuator's when the joint names none, no reductions read;
any other interface name stops the robot ("No matching hardware interface found").
gazebo_ros_control_plugin.cpp ``Load``: ``robotSimType`` defaults to DefaultRobotHWSim.
"""

from __future__ import annotations

import pytest

from tests.rules.helpers import check, problems

PLUGIN = """<gazebo>
    <plugin name="gazebo_ros_control" filename="libgazebo_ros_control.so">{extra}</plugin>
  </gazebo>"""
ROBOT = """
<robot name="r">
  {plugin}
  <transmission name="t">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="j">{joint}</joint>
    <actuator name="m">{actuator}</actuator>
  </transmission>
</robot>
"""
REDUCTION = "<mechanicalReduction>1</mechanicalReduction>"


def robot(joint: str, actuator: str = REDUCTION, extra: str = "", plugin: bool = True) -> str:
    return ROBOT.format(plugin=PLUGIN.format(extra=extra) if plugin else "", joint=joint,
                        actuator=actuator)


def iface(name: str) -> str:
    return f"<hardwareInterface>{name}</hardwareInterface>"


def test_an_unprefixed_interface_is_a_warning_where_gazebo_ros_control_loads_the_robot():
    (problem,) = problems(robot(iface("EffortJointInterface")), select=["TX205"])
    assert (problem.line, problem.column, problem.severity) == (7, 5, "warning")
    assert problem.message.endswith(
        "gazebo_ros_control (run by this robot's <gazebo> plugin libgazebo_ros_control.so) "
        "accepts 'EffortJointInterface' with a deprecation warning: write "
        "'hardware_interface/EffortJointInterface' for both")


@pytest.mark.parametrize("extra", ["", "<robotSimType>gazebo_ros_control/DefaultRobotHWSim"
                                       "</robotSimType>"])
def test_the_default_sim_type_named_or_not(extra):
    assert check(robot(iface("PositionJointInterface"), extra=extra), select=["TX205"]) == [
        (7, 5, "TX205", "warning")]


def test_another_robot_sim_type_decides_for_itself_so_the_error_stays():
    extra = "<robotSimType>franka_gazebo/FrankaHWSim</robotSimType>"
    assert check(robot(iface("PositionJointInterface"), extra=extra), select=["TX205"]) == [
        (7, 5, "TX205", "error")]


def test_without_the_plugin_ros_control_decides():
    assert check(robot(iface("PositionJointInterface"), plugin=False), select=["TX205"]) == [
        (5, 5, "TX205", "error")]


def test_a_name_gazebo_ros_control_does_not_know_stays_an_error_and_says_both_refuse():
    (problem,) = problems(robot(iface("hardware_interface/EffortJoinInterface")),
                          select=["TX205"])
    assert problem.severity == "error"
    assert "so does gazebo_ros_control (run by this robot's <gazebo> plugin " \
           "libgazebo_ros_control.so): \"No matching hardware interface found\"" in problem.message


def test_an_interface_only_on_the_actuator_is_left_to_tx301():
    xml = robot("", actuator=REDUCTION + iface("hardware_interface/EffortJointInterface"))
    found = problems(xml, select=["TX110", "TX301"])
    assert [(p.code, p.severity) for p in found] == [("TX301", "warning")]
    assert found[0].message.endswith("gazebo_ros_control (run by this robot's <gazebo> plugin "
                                     "libgazebo_ros_control.so) takes the actuator's, with a "
                                     "warning")
    without = robot("", actuator=REDUCTION + iface("hardware_interface/EffortJointInterface"),
                    plugin=False)
    assert [p.code for p in problems(without, select=["TX110", "TX301"])] == ["TX110", "TX301"]


def test_a_missing_reduction_is_a_warning_since_gazebo_ros_control_never_reads_it():
    (problem,) = problems(robot(iface("hardware_interface/EffortJointInterface"), actuator=""),
                          select=["TX104"])
    assert problem.severity == "warning"
    assert problem.message.endswith("never reads reductions and loads it")


def test_a_configured_severity_still_wins():
    found = problems(robot(iface("EffortJointInterface")), select=["TX205"],
                     severity={"TX205": "error"})
    assert [p.severity for p in found] == ["error"]


FRANKA = "<robotSimType>franka_gazebo/FrankaHWSim</robotSimType>"


def test_franka_gazebo_never_reads_reductions_either():
    # frankaemika/franka_ros franka_gazebo/src/franka_hw_sim.cpp initSim @005ff25
    (problem,) = problems(robot(iface("hardware_interface/EffortJointInterface"), actuator="",
                                extra=FRANKA), select=["TX104"])
    assert problem.severity == "warning"
    assert ("franka_gazebo/FrankaHWSim (run by this robot's <gazebo> plugin "
            "libgazebo_ros_control.so) never reads reductions") in problem.message


def test_franka_gazebo_takes_only_prefixed_interfaces():
    assert check(robot(iface("EffortJointInterface"), extra=FRANKA), select=["TX205"]) == [
        (7, 5, "TX205", "error")]
