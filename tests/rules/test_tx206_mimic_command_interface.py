"""TX206: a URDF mimic joint commanded in <ros2_control>, which Jazzy and later refuse.

ros-controls/ros2_control hardware_interface/src/component_parser.cpp
``parse_control_resources_from_urdf`` @53b9999 throws "Activated mimic joints cannot have
command interfaces" (from 4.13, Jazzy; ros2_control#1553); Humble reads no mimic information.
"""

from __future__ import annotations

import pytest
from click.testing import CliRunner

from txtool.cli import cli

GRIPPER = """<robot name="gripper">
  <link name="base"/><link name="l"/><link name="r"/>
  <joint name="left_finger" type="prismatic"><parent link="base"/><child link="l"/>
    <limit effort="1" velocity="1" lower="0" upper="0.04"/></joint>
  <joint name="right_finger" type="prismatic"><parent link="base"/><child link="r"/>
    <limit effort="1" velocity="1" lower="0" upper="0.04"/><mimic joint="left_finger"/></joint>
  <ros2_control name="gripper" type="system">
    <hardware><plugin>mock_components/GenericSystem</plugin></hardware>
    <joint name="left_finger"><command_interface name="position"/></joint>
    <joint name="right_finger"{attribute}>{interfaces}</joint>
  </ros2_control>
</robot>
"""
COMMANDED = '<command_interface name="position"/><state_interface name="position"/>'


def validate(tmp_path, text: str, *args: str) -> tuple[int, list[str]]:
    path = tmp_path / "gripper.urdf"
    path.write_text(text)
    result = CliRunner().invoke(cli, ["validate", "--select", "TX206", *args, str(path)])
    return result.exit_code, [line.split(": ", 1)[1] for line in result.stdout.splitlines()
                              if "TX206" in line]


@pytest.mark.parametrize(("distro", "code", "severity"), [
    ("jazzy", 1, "error"), ("rolling", 1, "error"), (None, 0, "warning"), ("humble", 0, None)])
def test_a_commanded_mimic_joint_follows_the_distribution(tmp_path, distro, code, severity):
    text = GRIPPER.format(attribute="", interfaces=COMMANDED)
    found = validate(tmp_path, text, *(["--ros-distro", distro] if distro else []))
    assert found[0] == code
    if severity is None:
        assert found[1] == []
        return
    (line,) = found[1]
    assert line.startswith(f"{severity} TX206 mimic-command-interface: joint 'right_finger' "
                           "mimics 'left_finger' in the URDF and has a command interface here: "
                           "ros2_control from Jazzy on refuses the robot")
    assert ("Humble's parser reads no mimic information" in line) == (distro is None)


@pytest.mark.parametrize(("attribute", "interfaces"), [
    ("", '<state_interface name="position"/>'),  # only states: accepted
    (' mimic="false"', COMMANDED),  # an actuated joint, said so: accepted
])
def test_what_the_parser_accepts_is_not_reported(tmp_path, attribute, interfaces):
    text = GRIPPER.format(attribute=attribute, interfaces=interfaces)
    assert validate(tmp_path, text, "--ros-distro", "jazzy") == (0, [])
