"""What the target check of a conversion says in the cases its main tests leave out: a robot
without transmissions is no robot refused for lacking <ros2_control>, a conversion to ROS 1
names ros_control alone where it refuses one, and the input's own finding on a transmission
does not hide what the conversion brings to it."""

from __future__ import annotations

import pytest

from tests.migrate.test_target_check import CLEAN, JOINTS


@pytest.fixture
def here(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    return tmp_path


def test_a_robot_without_transmissions_converts_to_ros2_without_a_refusal(run, here):
    (here / "bare.urdf").write_text(f'<?xml version="1.0"?>\n<robot name="arm">\n{JOINTS}</robot>\n')
    code, out, err = run("convert", "bare.urdf", "--to", "ros2-p2", "-o", "out.urdf")
    assert (code, out) == (0, "") and "refuses" not in err


def test_a_clean_robot_converts_back_to_ros1_with_the_replacement_noted(run, here):
    (here / "arm.urdf").write_text(CLEAN)
    assert run("convert", "arm.urdf", "--to", "ros2-p2", "-o", "ros2.urdf")[0] == 0
    code, out, err = run("convert", "ros2.urdf", "--to", "ros1", "-o", "back.urdf")
    assert (code, out, err) == (0, "", "note: <ros2_control name=\"arm\"> is what txtool "
                                "generates for its transmissions; replaced by them\n")


P2_UNDERFLOW = """<?xml version="1.0"?>
<robot name="arm">
  <link name="base"/><link name="l1"/>
  <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/>
    <limit effort="1" velocity="1" lower="-1" upper="1"/></joint>
  <ros2_control name="arm" type="system">
    <hardware><plugin>arm/Hardware</plugin></hardware>
    <joint name="j1"><command_interface name="effort"/></joint>
    <transmission name="t1">
      <plugin>transmission_interface/SimpleTransmission</plugin>
      <joint name="j1" role="joint1"><mechanical_reduction>1e-400</mechanical_reduction></joint>
    </transmission>
  </ros2_control>
</robot>
"""


def test_the_inputs_warning_on_a_transmission_does_not_hide_the_p1_form(run, here):
    """Humble reads the reduction as 0 (a warning of the input's and the output's); the
    <role> elements of Proposal 1 are still said to be what ros2_control refuses."""
    (here / "arm.urdf").write_text(P2_UNDERFLOW)
    code, out, err = run("convert", "arm.urdf", "--to", "ros2-p1", "-o", "p1.urdf")
    assert code == 0
    assert "warning: ros2-p1 is not what ros2_control reads" in err


def test_a_refusal_of_a_conversion_to_ros1_names_ros_control_alone(run, here):
    """The robot lacks a link (urdfdom refuses it): the ROS 1 file written has no
    <ros2_control>, so ros2_control is no reader of it to name."""
    (here / "arm.urdf").write_text(CLEAN.replace('<link name="l2"/>', ""))
    assert run("convert", "arm.urdf", "--to", "ros2-p2", "--allow-lossy", "-o", "ros2.urdf")[0] == 0
    code, out, err = run("convert", "ros2.urdf", "--to", "ros1", "-o", "back.urdf")
    assert (code, out) == (1, "") and not (here / "back.urdf").exists()
    (refused,) = [line for line in err.splitlines() if line.startswith("error:")]
    assert refused.startswith("error: line 6: TX210 urdf-refused for ros_control (noetic): "
                              "urdfdom refuses the robot")
