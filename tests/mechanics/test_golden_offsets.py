"""Absolute golden vectors with non-zero offsets: every kind, quantity and direction.

Round trips cannot see a fault that is the same both ways (an offset dropped on the way in and
on the way out), so each value here is worked out by hand from the loaders' formulas, with
offsets, signs and reductions other than 1 everywhere:

* simple: ros-controls/ros2_control @2448b7e
  ``transmission_interface/include/transmission_interface/simple_transmission.hpp``:194, :198,
  :202 (actuator -> joint effort, velocity, position) and :210, :214, :218 (joint -> actuator);
  ros_control's ``simple_transmission.h`` has the same formulas.
* differential: ros2_control @7792ce3 ``.../differential_transmission.hpp``:267-272, :281-284,
  :293-296 (actuator -> joint position, velocity, effort) and :311-316, :325-328, :337-340
  (joint -> actuator); ros_control's ``differential_transmission.h`` is the same.
* four-bar: ros2_control @95d3f86 ``.../four_bar_linkage_transmission.hpp``:265-268, :278-280
  (actuator -> joint position, velocity) and :308-311, :321-322 (joint -> actuator). Its effort
  lines :290-292 and :332-333 are the ROS 1 form, identical to ros_control's
  ``four_bar_linkage_transmission.h`` ``actuatorToJointEffort``/``jointToActuatorEffort``
  (ros_control#523, still open). ros2_control replaced them in PR #1837 (issue #1746) with
  ``tau_j = A^-T tau_a`` for the velocity map A above: ``e_j0 = jr0 e_a0 ar0 + e_a1 ar1``,
  ``e_j1 = jr1 e_a1 ar1``; ``e_a0 = (e_j0 - e_j1 / jr1) / (jr0 ar0)``,
  ``e_a1 = e_j1 / (ar1 jr1)`` (../shared/reference/ros-control-transmissions.md, 1.3).

Inputs in each direction are chosen independently (not the other direction's outputs), and all
values are exact in binary, so the tolerance only absorbs rounding.
"""

from __future__ import annotations

import numpy as np
import pytest

from txtool.dialects.read import read_source
from txtool.io.xmlio import Source, parse_bytes
from txtool.mechanics import from_parameters, from_transmission, linear

TOL = 1e-12


def close(actual: object, expected: object) -> None:
    np.testing.assert_allclose(np.asarray(actual, dtype=float), expected, rtol=0, atol=TOL)


# --- simple: n = -4, offset 0.25 ------------------------------------------------------------

# The reduction sits on the actuator in ROS 1 and on the joint in ROS 2; the maps are the same.
SIMPLE = {"ros1": ((-4.0,), (1.0,)), "ros2": ((1.0,), (-4.0,))}
SIMPLE_OFFSET = (0.25,)
# quantity: (actuator in, joint out) and (joint in, actuator out)
SIMPLE_TO_JOINT = {
    "position": ([3.0], [-0.5]),  # 3 / -4 + 0.25
    "absolute_position": ([3.0], [-0.5]),
    "velocity": ([2.0], [-0.5]),  # 2 / -4
    "effort": ([1.5], [-6.0]),  # 1.5 * -4
    "torque": ([1.5], [-6.0]),
    "force": ([1.5], [-6.0]),
}
SIMPLE_TO_ACTUATOR = {
    "position": ([1.0], [-3.0]),  # (1 - 0.25) * -4
    "velocity": ([0.75], [-3.0]),  # 0.75 * -4
    "effort": ([2.0], [-0.5]),  # 2 / -4
    "torque": ([2.0], [-0.5]),
    "force": ([2.0], [-0.5]),
}


@pytest.mark.parametrize("placement", sorted(SIMPLE))
@pytest.mark.parametrize("quantity", sorted(SIMPLE_TO_JOINT))
def test_simple_actuator_to_joint(placement: str, quantity: str) -> None:
    ar, jr = SIMPLE[placement]
    m = from_parameters("t", "simple", ar, jr, SIMPLE_OFFSET)
    given, expected = SIMPLE_TO_JOINT[quantity]
    close(m.actuator_to_joint(quantity, given), expected)


@pytest.mark.parametrize("placement", sorted(SIMPLE))
@pytest.mark.parametrize("quantity", sorted(SIMPLE_TO_ACTUATOR))
def test_simple_joint_to_actuator(placement: str, quantity: str) -> None:
    ar, jr = SIMPLE[placement]
    m = from_parameters("t", "simple", ar, jr, SIMPLE_OFFSET)
    given, expected = SIMPLE_TO_ACTUATOR[quantity]
    close(m.joint_to_actuator(quantity, given), expected)


# --- differential: ar (4, -2), jr (0.5, 2), offsets (0.5, -0.25) -----------------------------

DIFF = ((4.0, -2.0), (0.5, 2.0), (0.5, -0.25))
DIFF_TO_JOINT = {
    # x_a / ar = (0.5, -1.5): ((0.5 - 1.5) / 1 + 0.5, (0.5 + 1.5) / 4 - 0.25)
    "position": ([2.0, 3.0], [-0.5, 0.25]),
    "absolute_position": ([2.0, 3.0], [-0.5, 0.25]),
    "velocity": ([2.0, 3.0], [-1.0, 0.5]),
    # e_a * ar = (4, -1): (0.5 * (4 - 1), 2 * (4 + 1))
    "effort": ([1.0, 0.5], [1.5, 10.0]),
}
DIFF_TO_ACTUATOR = {
    # x_j - off = (0.5, 1): ((0.25 + 2) * 4, (0.25 - 2) * -2)
    "position": ([1.0, 0.75], [9.0, 3.5]),
    "velocity": ([1.0, 0.75], [8.0, 2.0]),  # ((0.5 + 1.5) * 4, (0.5 - 1.5) * -2)
    "effort": ([3.0, 4.0], [1.0, -1.0]),  # e_j / jr = (6, 2): (8 / 8, 4 / -4)
}


@pytest.mark.parametrize("quantity", sorted(DIFF_TO_JOINT))
def test_differential_actuator_to_joint(quantity: str) -> None:
    m = from_parameters("t", "differential", *DIFF)
    given, expected = DIFF_TO_JOINT[quantity]
    close(m.actuator_to_joint(quantity, given), expected)


@pytest.mark.parametrize("quantity", sorted(DIFF_TO_ACTUATOR))
def test_differential_joint_to_actuator(quantity: str) -> None:
    m = from_parameters("t", "differential", *DIFF)
    given, expected = DIFF_TO_ACTUATOR[quantity]
    close(m.joint_to_actuator(quantity, given), expected)


# --- four-bar: ar (2, -4), jr (0.5, 2), offsets (0.5, -0.25) ---------------------------------

FOUR_BAR = ((2.0, -4.0), (0.5, 2.0), (0.5, -0.25))
FOUR_BAR_TO_JOINT = {
    # x_a0 / (jr0 ar0) = 3: (3 + 0.5, (2 / -4 - 3) / 2 - 0.25)
    "position": ([3.0, 2.0], [3.5, -2.0]),
    "velocity": ([3.0, 2.0], [3.0, -1.75]),
}
FOUR_BAR_TO_ACTUATOR = {
    # x_j - off = (0.5, 1): (0.5 * 0.5 * 2, (0.5 + 1 * 2) * -4)
    "position": ([1.0, 0.75], [0.5, -10.0]),
    "velocity": ([1.0, 0.75], [1.0, -10.0]),
}
# convention: (actuator effort in, joint effort out), (joint effort in, actuator effort out)
FOUR_BAR_EFFORT = {
    # ROS 2: (0.5 * 1 * 2 + 0.5 * -4, 2 * 0.5 * -4); ((3 - 4 / 2) / 1, 4 / (-4 * 2))
    "ros2": (([1.0, 0.5], [-1.0, -4.0]), ([3.0, 4.0], [1.0, -0.5])),
    # ROS 1: (0.5 * (1 * 2), 2 * (0.5 * -4 - 1 * 2 * 0.5)); (3 / 1, (3 + 4 / 2) / -4)
    "ros1": (([1.0, 0.5], [1.0, -6.0]), ([3.0, 4.0], [3.0, -1.25])),
}


@pytest.mark.parametrize("convention", ["ros2", "ros1"])
@pytest.mark.parametrize("quantity", sorted(FOUR_BAR_TO_JOINT))
def test_four_bar_motion_actuator_to_joint(quantity: str, convention: str) -> None:
    m = from_parameters("t", "four_bar", *FOUR_BAR, convention=convention)
    given, expected = FOUR_BAR_TO_JOINT[quantity]
    close(m.actuator_to_joint(quantity, given), expected)
    if quantity == "position":
        close(m.actuator_to_joint("absolute_position", given), expected)


@pytest.mark.parametrize("convention", ["ros2", "ros1"])
@pytest.mark.parametrize("quantity", sorted(FOUR_BAR_TO_ACTUATOR))
def test_four_bar_motion_joint_to_actuator(quantity: str, convention: str) -> None:
    m = from_parameters("t", "four_bar", *FOUR_BAR, convention=convention)
    given, expected = FOUR_BAR_TO_ACTUATOR[quantity]
    close(m.joint_to_actuator(quantity, given), expected)


@pytest.mark.parametrize("convention", ["ros2", "ros1"])
def test_four_bar_effort_actuator_to_joint(convention: str) -> None:
    m = from_parameters("t", "four_bar", *FOUR_BAR, convention=convention)
    (given, expected), _ = FOUR_BAR_EFFORT[convention]
    for quantity in ("effort", "torque", "force"):
        close(m.actuator_to_joint(quantity, given), expected)


@pytest.mark.parametrize("convention", ["ros2", "ros1"])
def test_four_bar_effort_joint_to_actuator(convention: str) -> None:
    m = from_parameters("t", "four_bar", *FOUR_BAR, convention=convention)
    _, (given, expected) = FOUR_BAR_EFFORT[convention]
    close(m.joint_to_actuator("effort", given), expected)


# --- the linter's pure-Python matrices (txtool.mechanics.linear) -----------------------------

# tau_j = E tau_a, from the effort formulas above (rows: joints, columns: actuators).
FOUR_BAR_E = {
    "ros2": [[1.0, -4.0], [0.0, -8.0]],  # e_j0 = 1 * e_a0 - 4 * e_a1; e_j1 = -8 * e_a1
    "ros1": [[1.0, 0.0], [-2.0, -8.0]],  # e_j1 = 2 * (-4 * e_a1 - 2 * 0.5 * e_a0)
}


@pytest.mark.parametrize("convention", ["ros2", "ros1"])
def test_four_bar_effort_matrix_is_the_loaders(convention: str) -> None:
    ar, jr, _ = FOUR_BAR
    assert linear.effort_matrix("four_bar", ar, jr, convention) == FOUR_BAR_E[convention]
    m = from_parameters("t", "four_bar", *FOUR_BAR, convention=convention)
    close(m.effort_to_joint, FOUR_BAR_E[convention])
    close(m.effort_to_actuator @ np.array(FOUR_BAR_E[convention]), np.eye(2))


def test_velocity_matrices_are_the_loaders() -> None:
    ar, jr, _ = FOUR_BAR
    assert linear.velocity_matrix("four_bar", ar, jr) == [[1.0, 0.0], [-4.0, -8.0]]
    ar, jr, _ = DIFF
    assert linear.velocity_matrix("differential", ar, jr) == [[2.0, 8.0], [-1.0, 4.0]]
    assert linear.velocity_matrix("simple", (-4.0,), (1.0,)) == [[-4.0]]


def test_only_the_ros1_four_bar_effort_matrix_loses_power() -> None:
    ar, jr, _ = FOUR_BAR
    a = linear.velocity_matrix("four_bar", ar, jr)
    assert linear.transpose(linear.effort_matrix("four_bar", ar, jr, "ros2")) == a
    # E^T - A for ROS 1 = [[0, -2], [4, 0]]; max|A| = 8.
    ros1 = linear.transpose(linear.effort_matrix("four_bar", ar, jr, "ros1"))
    assert ros1 == [[1.0, -2.0], [0.0, -8.0]]
    assert max(abs(ros1[i][j] - a[i][j]) for i in range(2) for j in range(2)) / 8.0 == 0.5


# --- the same numbers from real XML, through each dialect's loader ---------------------------

ROS1_SIMPLE = b"""<robot name="r">
  <joint name="elbow" type="revolute"><parent link="a"/><child link="b"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <transmission name="elbow_trans">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="elbow"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
      <offset>0.25</offset><mechanicalReduction>7</mechanicalReduction></joint>
    <actuator name="elbow_motor"><mechanicalReduction>-4</mechanicalReduction></actuator>
  </transmission>
</robot>
"""
# ros2_control reads the joint's reduction and offset; the actuator's are ignored.
ROS2_SIMPLE = b"""<robot name="r">
  <joint name="elbow" type="revolute"><parent link="a"/><child link="b"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <ros2_control name="arm" type="system">
    <hardware><plugin>fake/Hardware</plugin></hardware>
    <joint name="elbow"><command_interface name="effort"/></joint>
    <transmission name="elbow_trans">
      <plugin>transmission_interface/SimpleTransmission</plugin>
      <actuator name="elbow_motor" role="actuator1">
        <mechanical_reduction>7</mechanical_reduction><offset>9</offset></actuator>
      <joint name="elbow" role="joint1">
        <mechanical_reduction>-4</mechanical_reduction><offset>0.25</offset></joint>
    </transmission>
  </ros2_control>
</robot>
"""


@pytest.mark.parametrize("document", [ROS1_SIMPLE, ROS2_SIMPLE], ids=["ros1", "ros2"])
def test_a_loaded_simple_transmission_applies_its_offset_both_ways(document: bytes) -> None:
    (found,) = read_source(Source("r.urdf", document, parse_bytes(document, "r.urdf")))
    m = from_transmission(found.transmission)
    for quantity, (given, expected) in SIMPLE_TO_JOINT.items():
        close(m.actuator_to_joint(quantity, given), expected)
    for quantity, (given, expected) in SIMPLE_TO_ACTUATOR.items():
        close(m.joint_to_actuator(quantity, given), expected)
