"""A coupled transmission's actuator reductions as ros2_control will read them: ros_control's
std::stod reads a text's leading number (hexadecimal too), so the conversion writes the value
it read where ros2_control would read the text otherwise (the joints' numbers:
tests/foundation/test_numbers_across_dialects.py)."""

from __future__ import annotations

import pytest

import txtool
from tests.foundation.test_numbers_across_dialects import ROS1_TEXTS

DIFFERENTIAL = """<robot name="r">
  <transmission name="t">
    <type>transmission_interface/DifferentialTransmission</type>
    <joint name="a"><role>joint1</role>
      <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>
    <joint name="b"><role>joint2</role>
      <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>
    <actuator name="m1"><role>actuator1</role><mechanicalReduction>{text}</mechanicalReduction>
    </actuator>
    <actuator name="m2"><role>actuator2</role><mechanicalReduction>50</mechanicalReduction>
    </actuator>
  </transmission>
</robot>
"""


@pytest.mark.parametrize(("text", "written"), ROS1_TEXTS)
def test_a_ros1_actuator_reduction_is_written_as_ros2_will_read_it(text, written):
    done = txtool.convert(DIFFERENTIAL.format(text=text), to="ros2-p2")
    (t,) = txtool.read(done.text)
    assert [a.mechanical_reduction.text for a in t.actuators] == [written, "50"]
    (before,) = txtool.read(DIFFERENTIAL.format(text=text))
    assert t.actuators[0].mechanical_reduction.value == before.actuators[0].mechanical_reduction.value
