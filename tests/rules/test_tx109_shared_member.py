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
    assert [(p.line, p.column, p.code) for p in found] == [(9, 5, "TX109")]
    assert "joint 'elbow' of transmission 'b' is also in transmission 'a' (line 2)" in (
        found[0].message
    )


def test_shared_actuator_fires():
    xml = '<robot name="r">\n' + ros1("a", "j1", "m") + ros1("b", "j2", "m") + "</robot>"
    assert check(xml, select=["TX109"]) == [(10, 5, "TX109")]


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
    assert check(xml, select=["TX108", "TX109"]) == [(7, 3, "TX108")]
