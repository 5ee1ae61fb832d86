from __future__ import annotations

from tests.rules.helpers import check, problems

IFACE = "<hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>"


def ros1(name: str, joint: str) -> str:
    return (
        f'  <transmission name="{name}">\n'
        "    <type>transmission_interface/SimpleTransmission</type>\n"
        f'    <joint name="{joint}">{IFACE}</joint>\n'
        f'    <actuator name="{joint}_m"><mechanicalReduction>1</mechanicalReduction></actuator>\n'
        "  </transmission>\n"
    )


def test_second_transmission_with_the_same_name_fires():
    xml = '<robot name="r">\n' + ros1("t", "a") + ros1("t", "b") + "</robot>\n"
    found = problems(xml, select=["TX108"])
    assert [(p.line, p.column, p.code, p.severity) for p in found] == [(7, 3, "TX108", "warning")]
    assert "already used on line 2" in found[0].message


def test_different_names_pass():
    xml = '<robot name="r">\n' + ros1("t1", "a") + ros1("t2", "b") + "</robot>\n"
    assert check(xml, select=["TX108"]) == []


def test_ros1_and_ros2_names_do_not_collide():
    xml = """
    <robot name="r">
      <transmission name="t"><type>transmission_interface/SimpleTransmission</type></transmission>
      <ros2_control name="hw" type="system">
        <transmission name="t"><plugin>transmission_interface/SimpleTransmission</plugin>
        </transmission>
      </ros2_control>
    </robot>
    """
    assert check(xml, select=["TX108"]) == []


def test_literal_xacro_branches_are_not_compared():
    xml = """
    <robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
      <xacro:if value="$(arg a)"><transmission name="t"><type>x/Y</type></transmission></xacro:if>
      <xacro:unless value="$(arg a)"><transmission name="t"><type>x/Y</type></transmission>
      </xacro:unless>
    </robot>
    """
    assert check(xml, filename="r.xacro", no_xacro=True, select=["TX108"]) == []


def test_ros1_duplicate_loads_and_overwrites_so_it_is_a_warning():
    # ros_control's loader test DuplicateTransmissions allows a later transmission to overwrite
    # an earlier one: transmission_interface_loader_test.cpp:230-243 @3e1dd9d.
    xml = '<robot name="r">\n' + ros1("t", "a") + ros1("t", "b") + "</robot>\n"
    found = problems(xml, select=["TX108"])
    assert [(p.code, p.severity) for p in found] == [("TX108", "warning")]
    assert "ros_control loads both and the later one overwrites" in found[0].message


def test_ros2_duplicates_in_one_component_load_too():
    xml = """
    <robot name="r">
      <ros2_control name="hw" type="system">
        <joint name="a"><command_interface name="position"/></joint>
        <transmission name="t"><plugin>transmission_interface/SimpleTransmission</plugin>
          <joint name="a" role="joint1"/></transmission>
        <transmission name="t"><plugin>transmission_interface/SimpleTransmission</plugin>
          <joint name="a" role="joint1"/></transmission>
      </ros2_control>
    </robot>
    """
    found = problems(xml, select=["TX108"])
    assert [(p.line, p.column, p.code, p.severity) for p in found] == [(6, 5, "TX108", "warning")]
    assert "ros2_control loads both" in found[0].message
