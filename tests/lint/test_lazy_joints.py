"""The robot's joints as rules see them: a mapping that reads a joint when first asked for."""

from __future__ import annotations

from lxml import etree

from txtool.model.robot import JointsOnDemand, joint_elements

ROBOT = """<robot name="r">
  <joint name="a" type="revolute"><mimic joint="b"/></joint>
  <joint name="b" type="fixed"/>
</robot>"""


def test_joints_read_on_demand_behave_as_a_mapping():
    joints = JointsOnDemand(joint_elements(etree.fromstring(ROBOT)), limits=False)
    assert list(joints) == ["a", "b"] and len(joints) == 2
    assert "a" in joints and "c" not in joints
    assert joints.get("c") is None and joints.get("c", "none") == "none"
    first = joints.get("a")
    assert (first.name, first.type, first.mimic) == ("a", "revolute", "b")
    assert joints.get("a") is first and joints["a"] is first  # read once
    assert joints["b"].type == "fixed"
    assert dict(joints.items())["b"] is joints["b"]


def test_joints_read_with_their_limits_for_roundtrip():
    joints = JointsOnDemand(joint_elements(etree.fromstring(
        '<robot name="r"><joint name="a" type="revolute"><limit lower="-1" upper="2" '
        'effort="3" velocity="4"/></joint></robot>')))
    assert (joints["a"].lower, joints["a"].upper, joints["a"].velocity) == (-1.0, 2.0, 4.0)
