"""What the ROS 2 parsers refuse, in the cases the rules' own tests leave out: which findings
make the whole robot fail to load (a conversion may then not write it), a coupled
transmission with one joint in an actuator component, an actuator component's second
actuator, the first owner of an interface three blocks export, and urdfdom's limits."""

from __future__ import annotations

import pytest

from tests.rules.helpers import check, problems

LINKS = """  <link name="base"/><link name="arm"/><link name="tool"/>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="arm"/>
    <limit lower="-1" upper="1" effort="10" velocity="1"/></joint>
  <joint name="wrist" type="revolute"><parent link="arm"/><child link="tool"/>
    <limit lower="-1" upper="1" effort="10" velocity="1"/></joint>
"""


def block(name: str, joint: str, component: str = "system", members: str = "") -> str:
    return f"""  <ros2_control name="{name}" type="{component}">
    <hardware><plugin>mock_components/GenericSystem</plugin></hardware>
    <joint name="{joint}"><command_interface name="position"/></joint>{members}
  </ros2_control>
"""


def robot(*blocks: str) -> str:
    return '<robot name="r">\n' + LINKS + "".join(blocks) + "</robot>\n"


COUPLED = """
    <transmission name="t">
      <plugin>transmission_interface/{plugin}</plugin>
      <joint name="shoulder" role="joint1"/>{more}
      <actuator name="m1" role="actuator1"/><actuator name="m2" role="actuator2"/>
    </transmission>"""


@pytest.mark.parametrize(("code", "document"), [
    ("TX207", robot(block("hw", "shoulder", "actuator", COUPLED.format(
        plugin="DifferentialTransmission", more='<joint name="wrist" role="joint2"/>')))),
    ("TX208", robot(block("hw", "shoulder"), block("hw", "wrist"))),
    ("TX210", robot(block("hw", "shoulder")).replace('<link name="tool"/>', "")),
])
def test_the_parsers_refusals_fail_the_whole_robot(code, document):
    """A conversion that writes such a robot writes one no hardware of which loads, even where
    the input had the finding already (lint.target_check)."""
    (found,) = problems(document, select=[code])
    assert found.code == code and found.severity == "error" and found.refuses_whole


def test_a_loader_failure_of_one_transmission_is_no_refusal_of_the_robot():
    (found,) = problems(robot(block("hw", "shoulder", "system", COUPLED.format(
        plugin="DifferentialTransmission", more=""))), select=["TX103"])
    assert not found.refuses_whole


def test_a_coupled_transmission_of_one_joint_in_an_actuator_component_is_tx103s():
    """One joint satisfies the parser; the differential loader then wants two (TX103), and the
    actuators' names are none of TX207's business (that check is a SimpleTransmission's)."""
    document = robot(block("hw", "shoulder", "actuator",
                           COUPLED.format(plugin="DifferentialTransmission", more="")))
    assert check(document, select=["TX103", "TX207"]) == [(10, 5, "TX103", "error")]


def test_a_simple_transmission_with_two_foreign_actuators_is_one_finding_at_the_first():
    document = robot(block("hw", "shoulder", "actuator",
                           COUPLED.format(plugin="SimpleTransmission", more="")))
    found = problems(document, select=["TX207"])
    assert [(p.line, p.column, p.code) for p in found] == [(13, 7, "TX207")]
    assert found[0].message.startswith("actuator 'm1' of transmission 't':")


def test_an_interface_three_blocks_export_names_its_first_owner_each_time():
    document = robot(block("a", "shoulder"), block("b", "shoulder"), block("c", "shoulder"))
    found = problems(document, select=["TX209"])
    assert [(p.line, p.column) for p in found] == [(13, 5), (17, 5)]
    assert all("which <ros2_control> 'a' (line 7) exports too" in p.message for p in found)


@pytest.mark.parametrize(("joint", "said"), [
    ('<joint name="wrist" type="prismatic"><parent link="arm"/><child link="tool"/></joint>',
     "Joint [wrist] is of type PRISMATIC without limits"),
    ('<joint name="wrist" type="prismatic"><parent link="arm"/><child link="tool"/>'
     '<limit lower="0" upper="1"/></joint>', "joint limit: no effort"),
    ('<joint name="wrist" type="prismatic"><parent link="arm"/><child link="tool"/>'
     '<limit effort="1"/></joint>', "joint limit: no velocity"),
])
def test_urdfdom_wants_a_prismatic_joints_limits_effort_first(joint, said):
    lines = LINKS.splitlines()
    document = robot(block("hw", "shoulder")).replace(
        "\n".join(lines[3:5]), "  " + joint)
    (found,) = problems(document, select=["TX210"])
    assert found.message.startswith(f'urdfdom refuses the robot ("{said}")')


def test_an_actuator_components_simple_transmission_of_two_actuators_is_both_rules():
    """The parser takes its one joint (TX207 names the foreign actuator it is handed two of);
    the loader uses one actuator (TX103)."""
    document = robot(block("hw", "shoulder", "actuator",
                           COUPLED.format(plugin="SimpleTransmission", more="")))
    assert [(line, code) for line, _, code, _ in check(document, select=["TX103", "TX207"])] \
        == [(10, "TX103"), (13, "TX207")]


ROS1 = """
<robot name="r">
  <transmission name="t">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="j"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
    </joint>{more}
  </transmission>
</robot>
"""
JOINT_AGAIN = """
    <joint name="j"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
    </joint>"""


@pytest.mark.parametrize(("more", "has"), [
    ("", "1 joint and 0 actuators"),
    (JOINT_AGAIN + '\n    <actuator name="m"/>', "2 joints and 1 actuator"),
])
def test_ros_control_refuses_a_simple_transmission_without_one_of_each(more, has):
    """Where ros2_control supplies the actuator, or reads a joint listed twice once, ros_control
    counts (checkJointDimension, checkActuatorDimension)."""
    (found,) = problems(ROS1.format(more=more), select=["TX103"])
    assert (found.line, found.severity) == (2, "error")
    assert found.message == (f"transmission 't' (SimpleTransmission) has {has}: ros_control "
                             "needs exactly 1 joint and 1 actuator and refuses it")


def test_std_stod_reads_a_reduction_starting_with_zero_as_zero():
    document = ROS1.format(
        more='\n    <actuator name="m"><mechanicalReduction>0abc</mechanicalReduction></actuator>')
    assert [(p.line, p.code, p.severity) for p in problems(document, select=["TX106"])] == [
        (6, "TX106", "error")]
