from __future__ import annotations

import pytest

from tests.rules.helpers import check, problems
from txtool.rules.tx102_unknown_type import edit_distance, nearest_standard

ROS1 = """
<robot name="r">
  <transmission name="t">
    <type>{type}</type>
  </transmission>
</robot>
"""
ROS2 = """
<robot name="r">
  <ros2_control name="hw" type="actuator">
    <transmission name="t">
      <plugin>{type}</plugin>
    </transmission>
  </ros2_control>
</robot>
"""


def test_missing_prefix_fires_at_the_plugin_as_a_warning_with_a_suggestion():
    # Another namespace (here none) may be an installed plugin: a warning, not an error.
    found = problems(ROS2.format(type="SimpleTransmission"), select=["TX102"])
    assert [(p.line, p.column, p.code, p.severity) for p in found] == [
        (4, 7, "TX102", "warning")
    ]
    assert "did you mean 'transmission_interface/SimpleTransmission'?" in found[0].message


def test_transmission_interface_typos_are_left_to_tx113():
    xml = ROS1.format(type="transmission_interface/DiferentialTransmission")
    assert check(xml, select=["TX102"]) == []


def test_missing_prefix_suggests_the_plugin_name():
    found = problems(ROS1.format(type="FourBarLinkageTransmission"), select=["TX102"])
    assert "did you mean 'transmission_interface/FourBarLinkageTransmission'" in found[0].message


def test_unknown_custom_type_is_reported_without_suggestion():
    found = problems(ROS2.format(type="my_hw/RotationToLinear"), select=["TX102"])
    assert len(found) == 1 and "did you mean" not in found[0].message


@pytest.mark.parametrize(
    "type_",
    [
        "transmission_interface/SimpleTransmission",
        "transmission_interface/FourBarLinkageTransmission",
        "pr2_mechanism_model/SimpleTransmission",
        "sr_mechanism_model/J0Transmission",
        "franka_hw/FrankaStateInterface",
    ],
)
def test_standard_and_known_custom_families_pass(type_):
    assert check(ROS1.format(type=type_), select=["TX102"]) == []


def test_known_families_option_silences_a_custom_family():
    xml = ROS2.format(type="my_hw/RotationToLinear")
    assert check(xml, select=["TX102"], rules={"TX102": {"known-families": ["my_hw/"]}}) == []


def test_nearest_standard_and_edit_distance():
    assert edit_distance("kitten", "sitting") == 3
    assert nearest_standard("SimpleTansmission") == "transmission_interface/SimpleTransmission"
    assert nearest_standard("transmission_interface/RotationToLinerTansmission") is None
