"""What the reader takes of each member, through ``txtool.read``: the first declaration of a
joint in its ``<ros2_control>``, the first reduction ros2_control reads a text from, the first
role and each interface of a ROS 1 member, in whatever order the children stand."""

from __future__ import annotations

import txtool
from txtool.model.core import Number

ROS2 = """<robot name="r">
  <ros2_control name="c" type="system">
    <joint name=" j1 "><command_interface name="position"/><state_interface name="position"/>
    </joint>
    <joint name="j1"><command_interface name="velocity"/></joint>
    <transmission name="t">
      <plugin>transmission_interface/SimpleTransmission</plugin>
      <joint name="j1" role="joint1">
        <mechanical_reduction><!-- none --></mechanical_reduction>
        <mechanical_reduction> 2.5 </mechanical_reduction>
        <mechanical_reduction>3</mechanical_reduction>
      </joint>
      <actuator name="a1" role="actuator1"/>
    </transmission>
    <transmission name="u">
      <plugin>transmission_interface/SimpleTransmission</plugin>
      <joint name="j2" read_only=" TRUE "><role>joint1</role><offset/></joint>
      <actuator name="a2"><role> actuator1 </role><role>actuator2</role></actuator>
    </transmission>
  </ros2_control>
</robot>"""

ROS1 = """<robot name="r">
  <transmission name="t">
    <type>transmission_interface/DifferentialTransmission</type>
    <joint name="j1">
      <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
      <!-- a comment between -->
      <offset>0.5</offset><role> joint1 </role><offset>7</offset>
      <hardwareInterface> </hardwareInterface>
      <hardwareInterface>PositionJointInterface</hardwareInterface>
    </joint>
    <actuator name="a1"><mechanicalReduction>50</mechanicalReduction><role>actuator1</role>
      <mechanicalReduction>60</mechanicalReduction><role>actuator2</role></actuator>
  </transmission>
</robot>"""


def test_ros2_members_take_the_first_declaration_and_the_first_reduction_with_a_text():
    t, u = txtool.read(ROS2)
    (joint,) = t.joints
    assert (joint.interfaces, joint.state_interfaces) == (("position",), ("position",))
    assert joint.mechanical_reduction == Number(value=2.5, text=" 2.5 ")
    assert joint.offset is None
    assert t.actuators[0].role == "actuator1" and t.actuators[0].interfaces == ()
    (undeclared,) = u.joints
    assert (undeclared.interfaces, undeclared.state_interfaces) == ((), ())
    assert undeclared.offset == Number(value=None, text="")  # ros2_control's default
    assert (undeclared.role, undeclared.read_only) == ("joint1", True)
    assert u.actuators[0].role == "actuator1"
    assert u.dialect == "ros2-p1"


def test_ros1_members_take_the_first_role_reduction_and_offset_and_each_interface():
    (t,) = txtool.read(ROS1)
    joint, actuator = t.joints[0], t.actuators[0]
    assert joint.role == "joint1"
    assert joint.offset == Number(value=0.5, text="0.5")
    assert joint.interfaces == ("hardware_interface/EffortJointInterface",
                                "PositionJointInterface")
    assert joint.mechanical_reduction is None
    assert actuator.role == "actuator1"
    assert actuator.mechanical_reduction == Number(value=50.0, text="50")
