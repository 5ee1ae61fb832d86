from __future__ import annotations

from tests.rules.helpers import check, problems

ROS2 = """
<robot name="r">
  <ros2_control name="hw" type="system">
    <joint name="j"/>
    <transmission name="t">
      {plugin}
      <joint name="j" role="joint1"/>
    </transmission>
  </ros2_control>
</robot>
"""


def test_ros2_without_plugin_fires_at_the_transmission():
    found = problems(ROS2.format(plugin=""), select=["TX101"])
    assert [(p.line, p.column, p.code, p.severity) for p in found] == [(4, 5, "TX101", "error")]
    assert "Missing <plugin> tag" in found[0].message


def test_ros2_empty_plugin_fires_at_the_plugin():
    assert check(ROS2.format(plugin="<plugin> </plugin>"), select=["TX101"]) == [(5, 7, "TX101", "error")]


def test_ros1_empty_type_fires_even_with_the_legacy_attribute():
    xml = """
    <robot name="r">
      <transmission name="t" type="SimpleTransmission">
        <type></type>
      </transmission>
    </robot>
    """
    assert check(xml, select=["TX101"]) == [(3, 5, "TX101", "error")]


def test_ros1_legacy_attribute_alone_is_left_to_tx302():
    xml = '<robot name="r"><transmission name="t" type="pr2_mechanism_model/SimpleTransmission"/>'
    assert check(xml + "</robot>", select=["TX101"]) == []


def test_typed_transmissions_pass():
    plugin = "<plugin>transmission_interface/SimpleTransmission</plugin>"
    assert check(ROS2.format(plugin=plugin), select=["TX101"]) == []
