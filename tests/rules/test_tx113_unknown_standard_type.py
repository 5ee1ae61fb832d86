"""TX113: a transmission_interface/ type that is not one of the three standard ones.

ros_control refuses it: transmission_interface_loader.cpp:139-147 @0a09467 ("Unsupported type"),
tested by UnsupportedTransmissionType, transmission_interface_loader_test.cpp:125-135 @3e1dd9d.
"""

from __future__ import annotations

import pytest

from tests.rules.helpers import check, problems

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


def test_ros2_typo_is_an_error_with_a_suggestion():
    found = problems(ROS2.format(type="transmission_interface/SimpleTansmission"), select=["TX113"])
    assert [(p.line, p.column, p.code, p.severity) for p in found] == [
        (4, 7, "TX113", "error")
    ]
    assert "did you mean 'transmission_interface/SimpleTransmission'?" in found[0].message
    assert "no transmission loader has that name" in found[0].message


def test_ros1_typo_says_ros_control_refuses_it():
    found = problems(ROS1.format(type="transmission_interface/DiferentialTransmission"),
                     select=["TX113"])
    assert check(ROS1.format(type="transmission_interface/DiferentialTransmission"),
                 select=["TX113"]) == [(3, 5, "TX113", "error")]
    assert "ros_control refuses it (\"Unsupported type\")" in found[0].message
    assert "'transmission_interface/DifferentialTransmission'" in found[0].message


def test_a_made_up_name_in_the_namespace_is_a_warning_without_suggestion():
    # ros2_control_test_assets' actuator_only_custom_plugin uses this name (corpus file). No
    # near-miss of a standard name: it may be a vendor's plugin (pluginlib looks up any
    # registered name, transmission_interface_loader.cpp TransmissionInterfaceLoader::load).
    found = problems(ROS2.format(type="transmission_interface/RotationToLinerTansmission"),
                     select=["TX113"])
    assert [(p.line, p.column, p.severity) for p in found] == [(4, 7, "warning")]
    assert "did you mean" not in found[0].message
    assert "loads it only where a package registering it is installed" in found[0].message


@pytest.mark.parametrize(
    "type_",
    [
        "transmission_interface/SimpleTransmission",
        "transmission_interface/DifferentialTransmission",
        "transmission_interface/FourBarLinkageTransmission",
        "my_hw/RotationToLinear",
        "SimpleTransmission",
    ],
)
def test_standard_types_and_other_namespaces_pass(type_):
    assert check(ROS1.format(type=type_), select=["TX113"]) == []
