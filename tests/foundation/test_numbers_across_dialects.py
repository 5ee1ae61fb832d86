"""Numbers as the target's loader will read them, through the public API (``txtool.read`` and
``txtool.convert``): a text the target reads as another value is rewritten to the value the
source's loader read, for offsets as for reductions, in both directions; a pre-Hydro reduction
under ``<transmission>`` stands for the actuator's only when the actuator has none."""

from __future__ import annotations

import pytest

import txtool

ROS1 = """<robot name="r">
  <transmission name="t">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="j"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
      <offset>{offset}</offset></joint>
    <actuator name="m">{actuator}</actuator>{legacy}
  </transmission>
</robot>
"""
ROS2 = """<robot name="r">
  <ros2_control name="s" type="system"><hardware><plugin>x/Y</plugin></hardware>
    <joint name="j"><command_interface name="effort"/></joint>
    <transmission name="t">
      <plugin>transmission_interface/SimpleTransmission</plugin>
      <joint name="j" role="joint1"><mechanical_reduction>{reduction}</mechanical_reduction>
        <offset>{offset}</offset></joint>
      <actuator name="m" role="actuator1"/>
    </transmission>
  </ros2_control>
</robot>
"""


def ros1(offset: str = "0.25", actuator: str = "<mechanicalReduction>50</mechanicalReduction>",
         legacy: str = "") -> str:
    return ROS1.format(offset=offset, actuator=actuator, legacy=legacy)


# ros_control reads with std::stod (a number's leading part, hexadecimal too); ros2_control's
# stod reads the whole text or falls back to the default.
ROS1_TEXTS = [("0.25abc", "0.25"), ("0.25 junk", "0.25"), ("0x10", "16"),
              (" 0.25 ", " 0.25 "), ("+0.25", "+0.25"), (".25", ".25"), ("1e-1", "1e-1")]


@pytest.mark.parametrize(("text", "written"), ROS1_TEXTS)
@pytest.mark.parametrize("to", ["ros2-p1", "ros2-p2"])
def test_a_ros1_offset_is_written_as_ros2_will_read_it(text, written, to):
    done = txtool.convert(ros1(offset=text), to=to)
    (t,) = txtool.read(done.text)
    assert (t.joints[0].offset.text, done.losses) == (written, [])
    assert t.joints[0].offset.value == txtool.read(ros1(offset=text))[0].joints[0].offset.value


@pytest.mark.parametrize(("text", "written"), ROS1_TEXTS)
def test_a_ros1_reduction_is_written_as_ros2_will_read_it(text, written):
    done = txtool.convert(ros1(actuator=f"<mechanicalReduction>{text}</mechanicalReduction>"),
                          to="ros2-p2")
    (t,) = txtool.read(done.text)
    assert t.joints[0].mechanical_reduction.text == written


@pytest.mark.parametrize(("text", "written"), [("0.5", "0.5"), (" 2 ", " 2 "), ("1e1", "1e1")])
def test_a_ros2_offset_keeps_its_text_in_ros1_where_ros_control_reads_the_same(text, written):
    done = txtool.convert(ROS2.format(reduction="50", offset=text), to="ros1")
    (t,) = txtool.read(done.text)
    assert t.joints[0].offset.text == written and t.joints[0].offset.value == float(text)


def test_a_ros2_offset_ros2_control_cannot_read_is_carried_as_the_default_it_used():
    done = txtool.convert(ROS2.format(reduction="50", offset="0.5abc"), to="ros1")
    (t,) = txtool.read(done.text)
    assert (t.joints[0].offset.text, t.joints[0].offset.value) == ("0", 0.0)


LEGACY = "\n    <mechanicalReduction>7</mechanicalReduction>"


def test_a_pre_hydro_reduction_stands_for_an_actuator_without_one():
    (t,) = txtool.read(ros1(actuator="", legacy=LEGACY))
    assert t.actuators[0].mechanical_reduction.value == 7.0


def test_the_actuator_s_own_reduction_wins_over_a_pre_hydro_one():
    (t,) = txtool.read(ros1(legacy=LEGACY))
    assert t.actuators[0].mechanical_reduction.value == 50.0
    done = txtool.convert(ros1(legacy=LEGACY), to="ros2-p2")
    (converted,) = txtool.read(done.text)
    assert converted.joints[0].mechanical_reduction.value == 50.0
