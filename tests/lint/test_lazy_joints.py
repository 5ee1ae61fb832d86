"""The robot's joints as rules see them: a mapping that reads a joint when first asked for."""

from __future__ import annotations

from lxml import etree

from txtool.lint.context import Joints
from txtool.model.robot import joint_elements

ROBOT = """<robot name="r">
  <joint name="a" type="revolute"><mimic joint="b"/></joint>
  <joint name="b" type="fixed"/>
</robot>"""


def test_joints_read_on_demand_behave_as_a_mapping():
    joints = Joints(joint_elements(etree.fromstring(ROBOT)))
    assert list(joints) == ["a", "b"] and len(joints) == 2
    assert "a" in joints and "c" not in joints
    assert joints.get("c") is None and joints.get("c", "none") == "none"
    first = joints.get("a")
    assert (first.name, first.type, first.mimic) == ("a", "revolute", "b")
    assert joints.get("a") is first and joints["a"] is first  # read once
    assert joints["b"].type == "fixed"
    assert dict(joints.items())["b"] is joints["b"]
