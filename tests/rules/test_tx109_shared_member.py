from __future__ import annotations

from tests.rules.helpers import check, problems

IFACE = "<hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>"


def ros1(name: str, joint: str, actuator: str, type_: str = "SimpleTransmission") -> str:
    return (
        f'  <transmission name="{name}">\n'
        f"    <type>transmission_interface/{type_}</type>\n"
        f'    <joint name="{joint}">{IFACE}</joint>\n'
        f'    <actuator name="{actuator}"><mechanicalReduction>1</mechanicalReduction></actuator>\n'
        "  </transmission>\n"
    )


def test_joint_in_two_transmissions_fires_at_the_second_joint():
    xml = '<robot name="r">\n' + ros1("a", "elbow", "m1") + ros1("b", "elbow", "m2") + "</robot>"
    found = problems(xml, select=["TX109"])
    assert [(p.line, p.column, p.code, p.severity) for p in found] == [(9, 5, "TX109", "warning")]
    assert "joint 'elbow' of transmission 'b' is also in transmission 'a' (line 2)" in (
        found[0].message
    )


def test_shared_actuator_fires():
    xml = '<robot name="r">\n' + ros1("a", "j1", "m") + ros1("b", "j2", "m") + "</robot>"
    assert check(xml, select=["TX109"]) == [(10, 5, "TX109", "warning")]


def test_distinct_members_pass():
    xml = '<robot name="r">\n' + ros1("a", "j1", "m1") + ros1("b", "j2", "m2") + "</robot>"
    assert check(xml, select=["TX109"]) == []


def test_custom_types_may_share_joints():
    xml = (
        '<robot name="r">\n' + ros1("a", "j1", "m1")
        + ros1("s", "j1", "m1").replace("transmission_interface/SimpleTransmission",
                                        "franka_hw/FrankaStateInterface")
        + "</robot>"
    )
    assert check(xml, select=["TX109"]) == []


def test_a_repeated_transmission_is_left_to_tx108():
    xml = '<robot name="r">\n' + ros1("a", "j1", "m1") + ros1("a", "j1", "m1") + "</robot>"
    assert check(xml, select=["TX108", "TX109"]) == [(7, 3, "TX108", "warning")]


def test_ros2_differential_and_four_bar_on_the_same_joints_load_so_it_is_a_warning():
    # ros2_control's own test robot does this (ros2_control_test_assets
    # minimal_robot_hardware_resources, a corpus file); the parser never compares members and
    # ros2_control never applies transmissions itself.
    block = """
    <robot name="r">
      <ros2_control name="hw" type="system">
        <joint name="joint1"><command_interface name="position"/></joint>
        <joint name="joint2"><command_interface name="position"/></joint>
        <transmission name="diff">
          <plugin>transmission_interface/DifferentialTransmission</plugin>
          <actuator name="m1" role="actuator1"/><actuator name="m2" role="actuator2"/>
          <joint name="joint1" role="joint1"/><joint name="joint2" role="joint2"/>
        </transmission>
        <transmission name="bar">
          <plugin>transmission_interface/FourBarLinkageTransmission</plugin>
          <actuator name="m3" role="actuator1"/><actuator name="m4" role="actuator2"/>
          <joint name="joint1" role="joint1"/><joint name="joint2" role="joint2"/>
        </transmission>
      </ros2_control>
    </robot>
    """
    found = problems(block, select=["TX109"])
    assert [(p.line, p.column, p.code, p.severity) for p in found] == [
        (13, 7, "TX109", "warning"), (13, 43, "TX109", "warning")
    ]
    assert "both load, but where both are applied the one applied last overwrites" in (
        found[0].message)
