"""TX404: ros_control takes coupled values by <role> but the data in XML order.

Sources: ros-controls/ros_control transmission_interface/src/joint_state_interface_provider.cpp
:132 @133d768 (``jnt_state_data.position[i]`` is ``transmission_info.joints_[i]``) and
four_bar_linkage_transmission_loader.cpp:49 @17b626a (values indexed by role).
"""

from __future__ import annotations

import pytest

from tests.corpus import corpus_file
from tests.rules.helpers import check, problems

EFFORT = "<hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>"
DIFFERENTIAL = """
<transmission name="wrist">
  <type>transmission_interface/DifferentialTransmission</type>
  {joints}
  {actuators}
</transmission>
"""
FLEX = f'<joint name="flex"><role>{{role}}</role><mechanicalReduction>-2</mechanicalReduction>{EFFORT}</joint>'
ROLL = f'<joint name="roll"><role>{{role}}</role><mechanicalReduction>2</mechanicalReduction>{EFFORT}</joint>'
M1 = '<actuator name="m1"><role>{role}</role><mechanicalReduction>50</mechanicalReduction></actuator>'
M2 = '<actuator name="m2"><role>{role}</role><mechanicalReduction>-50</mechanicalReduction></actuator>'
IN_ORDER_ACTUATORS = M1.format(role="actuator1") + M2.format(role="actuator2")


def test_joints_listed_against_their_roles_are_an_error_naming_both_joints():
    joints = FLEX.format(role="joint2") + ROLL.format(role="joint1")
    found = check(DIFFERENTIAL.format(joints=joints, actuators=IN_ORDER_ACTUATORS),
                  select=["TX404"])
    assert found == [(3, 3, "TX404", "error")]
    (problem,) = problems(DIFFERENTIAL.format(joints=joints, actuators=IN_ORDER_ACTUATORS),
                          select=["TX404"])
    assert "joint 'flex' (role joint2) is listed before 'roll' (role joint1)" in problem.message
    assert "'flex' is driven with the values written on 'roll'" in problem.message


def test_actuators_are_checked_on_their_own():
    joints = ROLL.format(role="joint1") + FLEX.format(role="joint2")
    actuators = M2.format(role="actuator2") + M1.format(role="actuator1")
    assert check(DIFFERENTIAL.format(joints=joints, actuators=actuators),
                 select=["TX404"]) == [(4, 3, "TX404", "error")]


def test_members_in_role_order_pass_whatever_their_names():
    joints = ROLL.format(role="joint1") + FLEX.format(role="joint2")
    assert check(DIFFERENTIAL.format(joints=joints, actuators=IN_ORDER_ACTUATORS),
                 select=["TX404"]) == []


@pytest.mark.parametrize("roles", [("joint1", "joint1"), ("joint1", "bogus"), ("", "joint1")])
def test_roles_that_are_not_a_swapped_pair_are_left_to_tx107(roles):
    joints = FLEX.format(role=roles[0]) + ROLL.format(role=roles[1])
    assert check(DIFFERENTIAL.format(joints=joints, actuators=IN_ORDER_ACTUATORS),
                 select=["TX404"]) == []


def test_ros2_is_left_to_tx401():
    xml = """
    <ros2_control name="hw" type="system">
      <joint name="flex"/><joint name="roll"/>
      <transmission name="wrist">
        <plugin>transmission_interface/DifferentialTransmission</plugin>
        <joint name="roll" role="joint2"/><joint name="flex" role="joint1"/>
        <actuator name="m1" role="actuator1"/><actuator name="m2" role="actuator2"/>
      </transmission>
    </ros2_control>
    """
    assert check(xml, select=["TX404"]) == []


@pytest.mark.parametrize("name", ["ros_control__differential_transmission_loader_full.urdf",
                                  "ros_control__four_bar_linkage_transmission_loader_full.urdf"])
def test_ros_control_test_robots_list_bar_joint_role_joint2_first(name):
    # Their loader tests check the values by role only; the data binding is what TX404 is about.
    path = corpus_file(name)
    found = [(p.line, p.code) for p in problems(path.read_text(), select=["TX404"])]
    assert found == [(7, "TX404")]
