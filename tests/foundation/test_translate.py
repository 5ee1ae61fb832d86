"""Dialect translation rules, one test each, on inline snippets."""

from __future__ import annotations

import pytest

from txtool.dialects.read import read_source
from txtool.io.xmlio import Source, parse_bytes
from txtool.transform.convert import convert_source

ROS1_SIMPLE = b"""<robot name="r">
  <transmission name="t">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="j"><hardwareInterface>hardware_interface/PositionJointInterface</hardwareInterface>
      <offset>0.25</offset></joint>
    <actuator name="m"><mechanicalReduction>325.949</mechanicalReduction></actuator>
  </transmission>
</robot>
"""


def source(data: bytes) -> Source:
    return Source("t.urdf", data, parse_bytes(data, "t.urdf"))


def read(data: bytes):
    return [f.transmission for f in read_source(source(data))]


def test_simple_reduction_moves_from_actuator_to_joint_with_its_text():
    result = convert_source(source(ROS1_SIMPLE), "ros2-p2")
    assert result.losses == []
    (t,) = read(result.data)
    joint, actuator = t.joints[0], t.actuators[0]
    assert joint.mechanical_reduction.text == "325.949"
    assert joint.offset.text == "0.25"
    assert actuator.mechanical_reduction is None
    assert (joint.role, actuator.role) == ("joint1", "actuator1")
    assert joint.interfaces == ("position",)
    assert joint.state_interfaces == ("position", "velocity")
    assert b'<ros2_control name="r" type="system">' in result.data
    assert b"<plugin>mock_components/GenericSystem</plugin>" in result.data


def test_simple_reduction_moves_back_to_the_actuator():
    ros2 = convert_source(source(ROS1_SIMPLE), "ros2-p2").data
    back = convert_source(source(ros2), "ros1")
    assert back.losses == []
    t = [x for x in read(back.data)][0]
    assert t.dialect == "ros1"
    assert t.actuators[0].mechanical_reduction.text == "325.949"
    assert t.joints[0].mechanical_reduction is None
    assert t.joints[0].role is None and t.actuators[0].role is None
    assert t.joints[0].interfaces == ("hardware_interface/PositionJointInterface",)


def test_ros2_actuator_reduction_on_a_simple_transmission_is_a_loss():
    data = b"""<robot name="r"><ros2_control name="hw" type="system">
      <joint name="j"><command_interface name="position"/></joint>
      <transmission name="t"><plugin>transmission_interface/SimpleTransmission</plugin>
        <actuator name="m" role="actuator1"><mechanical_reduction>50</mechanical_reduction></actuator>
        <joint name="j" role="joint1"/>
      </transmission></ros2_control></robot>"""
    result = convert_source(source(data), "ros1")
    assert any("ignored by ros2_control" in loss for loss in result.losses)
    (t,) = read(result.data)
    assert t.actuators[0].mechanical_reduction.value == 1.0  # what ros2_control used


def test_ros1_simple_joint_reduction_is_a_loss():
    data = ROS1_SIMPLE.replace(b"<offset>0.25</offset>",
                               b"<mechanicalReduction>7</mechanicalReduction>")
    result = convert_source(source(data), "ros2-p1")
    assert any("ignored by ros_control" in loss for loss in result.losses)


def test_coupled_without_roles_is_a_loss():
    data = b"""<robot name="r"><transmission name="d">
      <type>transmission_interface/DifferentialTransmission</type>
      <joint name="a"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>
      <joint name="b"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>
      <actuator name="m1"><mechanicalReduction>10</mechanicalReduction></actuator>
      <actuator name="m2"><mechanicalReduction>10</mechanicalReduction></actuator>
    </transmission></robot>"""
    result = convert_source(source(data), "ros2-p2")
    assert any("need roles joint1/joint2" in loss for loss in result.losses)


def test_custom_types_pass_through_untouched_and_are_reported():
    data = b"""<robot name="r"><transmission name="c" type="pr2_mechanism_model/WristTransmission">
      <rightActuator name="r" mechanicalReduction="60"/></transmission></robot>"""
    result = convert_source(source(data), "ros2-p2")
    assert result.data == data  # nothing in the document is lost: not a loss, but said
    assert result.losses == []
    assert result.warnings == [
        "transmission 'c': custom type 'pr2_mechanism_model/WristTransmission' is not converted "
        "(txtool knows only the standard types); left as written, in ros1 form"]


def test_children_that_neither_loader_reads_are_carried_as_written():
    # iiwa_stack writes <robotNamespace> in every transmission; both loaders skip elements
    # they do not know, so carrying it changes nothing that loads.
    data = ROS1_SIMPLE.replace(b"</actuator>", b"</actuator><robotNamespace>/x</robotNamespace>")
    result = convert_source(source(data), "ros2-p2")
    assert result.losses == []
    assert "transmission 't': <robotNamespace> is read by neither loader; carried as written" in (
        result.notes)
    assert b"<robotNamespace>/x</robotNamespace>\n    </transmission>" in result.data
    back = convert_source(source(result.data), "ros1")
    assert back.losses == [] and b"<robotNamespace>/x</robotNamespace>" in back.data


def test_a_child_the_target_loader_would_read_is_dropped_as_a_loss():
    # ros_control ignores <mechanical_reduction>; ros2_control would read it as the reduction.
    data = ROS1_SIMPLE.replace(b"<offset>", b"<mechanical_reduction>9</mechanical_reduction><offset>")
    result = convert_source(source(data), "ros2-p2")
    assert result.losses == [
        "joint 'j': <mechanical_reduction> is not read in ros1 but would be in ros2-p2; dropped"]
    (t,) = read(result.data)
    assert t.joints[0].mechanical_reduction.text == "325.949"


@pytest.mark.parametrize("text,written", [("50abc", "50"), (" 1e2 ", " 1e2 "), ("+4", "+4")])
def test_numbers_the_target_reads_differently_are_rewritten(text, written):
    data = ROS1_SIMPLE.replace(b"325.949", text.encode())
    (t,) = read(convert_source(source(data), "ros2-p2").data)
    assert t.joints[0].mechanical_reduction.text == written


def test_default_namespace_is_kept_on_new_elements():
    data = ROS1_SIMPLE.replace(b'<robot name="r">', b'<robot name="r" xmlns="http://www.ros.org">')
    result = convert_source(source(data), "ros2-p2")
    assert b'xmlns=""' not in result.data
    assert read(result.data)[0].dialect == "ros2-p2"


def test_transmission_goes_into_the_component_that_declares_its_joints():
    data = b"""<robot name="r">
  <ros2_control name="Arm" type="system">
    <hardware><plugin>arm/Hw</plugin></hardware>
    <joint name="j"><command_interface name="velocity"/></joint>
  </ros2_control>
""" + ROS1_SIMPLE.split(b"\n", 1)[1]
    result = convert_source(source(data), "ros2-p2")
    (t,) = read(result.data)
    assert t.ros2_control == "Arm"
    assert result.data.count(b"<ros2_control") == 1


XACRO_MACRO = b"""<robot xmlns:xacro="http://www.ros.org/wiki/xacro" name="r">
  <xacro:macro name="arm_trans" params="prefix ratio">
    <transmission name="${prefix}_trans">
      <type>transmission_interface/SimpleTransmission</type>
      <joint name="${prefix}_joint">
        <hardwareInterface>hardware_interface/PositionJointInterface</hardwareInterface>
      </joint>
      <actuator name="${prefix}_motor">
        <mechanicalReduction>${ratio}</mechanicalReduction>
      </actuator>
    </transmission>
  </xacro:macro>
</robot>
"""


def test_unexpanded_xacro_keeps_expressions_and_macro_scope():
    result = convert_source(source(XACRO_MACRO), "ros2-p2")
    assert result.losses == []
    text = result.data.decode()
    macro = text.index("<xacro:macro")
    assert macro < text.index('<ros2_control name="${prefix}_trans"') < text.index(
        "</xacro:macro>")
    assert "<mechanical_reduction>${ratio}</mechanical_reduction>" in text
    back = convert_source(source(result.data), "ros1").data.decode()
    assert "<mechanicalReduction>${ratio}</mechanicalReduction>" in back


def test_comments_inside_a_converted_transmission_are_carried():
    data = ROS1_SIMPLE.replace(b"<offset>0.25</offset>", b"<offset>0.25</offset><!-- calibrated -->")
    data = data.replace(b"<type>", b"<!-- wrist --><type>")
    result = convert_source(source(data), "ros2-p2")
    text = result.data.decode()
    start, end = text.index('<transmission name="t">'), text.index("</transmission>")
    assert start < text.index("<!-- wrist -->") < text.index("<plugin>", start)
    joint = text.index('<joint name="j" role="joint1">')
    assert joint < text.index("<!-- calibrated -->") < end
