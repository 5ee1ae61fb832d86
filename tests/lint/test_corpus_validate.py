"""Every corpus file validates (exit 0 or 1, never 2 or a crash) with its reviewed findings.

MANIFEST.tsv describes each file's quirks and intended defects; EXPECTED encodes the findings a
robotics engineer reviewed, with the reason: for the transmission rules (TX0xx/TX1xx) the exact
count per code, for the cross-check, dialect and ignored-value rules (TX2xx-TX4xx) the set of
codes. The exit code follows: a file fails only with an error, and an error means its loader
refuses it (the reason says why).
"""

from __future__ import annotations

import json
from collections import Counter

import pytest
from click.testing import CliRunner

from tests.corpus import corpus_file, corpus_names
from txtool.cli import cli

EXPECTED: dict[str, tuple[dict[str, int], set[str]]] = {
    # Errors only where the file's loader refuses it (ros_control for top-level ROS 1
    # transmissions, ros2_control inside <ros2_control>); each reason says why.
    # Unprefixed 'EffortJointInterface' is the only joint interface: ros_control refuses all 15
    # (transmission_interface_loader.cpp:190-194 @0a09467), but the robot's loader is its
    # <gazebo> plugin libbaxter_gazebo_ros_control.so (gazebo_ros_control's DefaultRobotHWSim),
    # which accepts them with a deprecation warning: warnings, exit 0.
    "baxter__baxter.urdf": ({}, {"TX300"}),  # TX300 at TX205's severity: one finding
    # macro with <hardwareInterface> and no <mechanicalReduction>: the simple loader requires it
    "franka_ros__franka_description_utils.xacro": ({"TX104": 1}, set()),
    # the same, but its loader is franka_gazebo's FrankaHWSim (its <gazebo> plugin's
    # robotSimType), which never reads reductions: warnings
    "franka_ros__panda-gazebo.urdf": ({"TX104": 7}, set()),
    # $(find rrbot_description) unresolved; hardwareInterface only in the actuator (pre-Indigo):
    # ros_control skips the joint and so the transmission
    "gazebo_ros_demos__rrbot_2013_hydro.xacro": ({"TX002": 1, "TX110": 1}, {"TX301"}),
    # hybrid type attribute beside <type>: ignored by ros_control
    "husky__husky.urdf": ({}, {"TX302"}),
    "husky__wheel.urdf.xacro": ({}, {"TX302"}),
    "iiwa_stack__iiwa.transmission.xacro": ({}, set()),
    # 7 clean transmissions; the extra <robotNamespace> child is ignored by the loader
    "iiwa_stack__iiwa14.urdf": ({}, set()),
    "interbotix__vx300s.urdf.xacro": ({}, {"TX202"}),
    # 13 clean transmissions (reduction 160 on the arm)
    "kinova_ros__j2s7s300.urdf": ({}, set()),
    "kinova_ros__kinova_common.xacro": ({"TX002": 1}, set()),
    "moveit_resources__pr2_robot.urdf": ({}, {"TX302"}),
    # unprefixed 'PositionJointInterface' only, 26 times: refused by ros_control, accepted by
    # its libgazebo_ros_control.so plugin (DefaultRobotHWSim): warnings; RHipYawPitch mimics
    # LHipYawPitch yet has its own transmission
    "nao_robot__naoV50.urdf": ({}, {"TX202", "TX300"}),
    # stale ROS 1 transmissions beside <ros2_control> blocks of a robot whose <gazebo> plugin
    # is gz_ros2_control: its readers (gz_ros2_control and ros2_control's component parser,
    # component_parser.cpp parse_resource_from_xml) read only <ros2_control>'s children, and
    # ros_control reads nothing here; one TX305 each (info), nothing about their contents
    # (the shared actuators, mimic joints and unprefixed interfaces load nowhere)
    "open_manipulator__omy_f3m.urdf": ({}, {"TX305"}),
    # macro library: unprefixed 'PositionJointInterface' only, refused by ros_control
    "open_manipulator__open_manipulator_x.gazebo.xacro": ({}, {"TX300"}),
    "pr2__base.transmission.xacro": ({}, {"TX302"}),
    "pr2__forearm.transmission.xacro": ({}, {"TX302"}),
    "pr2__gripper.transmission.xacro": ({}, {"TX302"}),
    "pr2__shoulder.transmission.xacro": ({}, {"TX302"}),
    "pr2__torso.transmission.xacro": ({}, {"TX302"}),
    "ros2_control_demos__example_8__rrbot_transmissions_system_position_only.ros2_control.xacro": (
        {}, set()
    ),
    "ros2_control_demos__example_8__rrbot_transmissions_system_position_only.urdf.xacro": (
        {"TX002": 1}, set()
    ),
    # 'transmission_interface/RotationToLinerTansmission': no package here registers it and it is
    # no near-miss of a standard name, so it loads only where a vendor package registers it
    # (pluginlib createUniqueInstance(type), transmission_interface_loader.cpp load): a warning
    "ros2_control_test_assets__actuator_only_custom_plugin.urdf": ({"TX113": 1}, set()),
    "ros2_control_test_assets__diffbot_urdf.urdf": ({}, {"TX302", "TX304"}),
    # joint31415 is not in the component: the parser throws
    "ros2_control_test_assets__invalid_hw_transmission_joint_mismatch.urdf": ({}, {"TX200"}),
    # joint2 is not in the actuator component (the parser's first refusal, TX200), and an
    # actuator component's transmission names one joint (TX207, the parser's next)
    "ros2_control_test_assets__invalid_transmission_too_many_joints.urdf": (
        {}, {"TX200", "TX207"}
    ),
    # Differential and FourBar on the same joints: ros2_control loads both (a warning)
    "ros2_control_test_assets__minimal_robot_hardware_resources.urdf": ({"TX109": 4}, set()),
    # ROS 1 style with only unprefixed interfaces: ros_control refuses both. Its own reader was
    # ros2_control's early parse_transmissions_from_urdf (transmission_interface/src/
    # transmission_parser.cpp @7f93398, any interface text), which ros2_control no longer
    # builds (transmission_interface/CMakeLists.txt @1796d3e): today only ros_control reads it.
    "ros2_control_test_assets__minimal_robot_transmissions.urdf": ({}, {"TX300"}),
    # 'transmission_interface/SimpleTansmission': the parser copies it, no loader has the name
    "ros2_control_test_assets__modular_robot_sensors_SimpleTansmission_typo.urdf": (
        {"TX113": 1}, set()
    ),
    "ros2_control_test_assets__multi_joints_transmission.urdf": ({}, set()),
    # bar_joint (role joint2) listed before foo_joint: ros_control takes the values by role but
    # the data in XML order, so bar_joint is driven with foo_joint's reduction and offset. The
    # loader tests check only the values by role (joint_state_interface_provider.cpp:132).
    "ros_control__differential_transmission_loader_full.urdf": ({}, {"TX404"}),
    "ros_control__four_bar_linkage_transmission_loader_full.urdf": ({}, {"TX402", "TX404"}),
    # 14 copies named alike (overwrite: warnings): 8 role defects, actuator reduction missing,
    # 3 non-numbers, 2 zeros, each refused by the four-bar loader; 10 list bar_joint first
    "ros_control__four_bar_linkage_transmission_loader_invalid.urdf": (
        {"TX104": 1, "TX105": 3, "TX106": 2, "TX107": 8, "TX108": 13}, {"TX402", "TX404"}
    ),
    # names and interfaces missing or empty, <type> missing, empty or with stray text
    "ros_control__parser_test_invalid.urdf": (
        {"TX100": 6, "TX101": 2, "TX108": 6, "TX110": 2, "TX113": 1}, set()
    ),
    # reduction missing, 'fifty', offset 'zero', reduction 0; four copies of one name
    "ros_control__simple_transmission_loader_invalid.urdf": (
        {"TX104": 1, "TX105": 2, "TX106": 1, "TX108": 3}, set()
    ),
    "ros_control__transmission_interface_loader_bidirectional_valid.urdf": ({}, set()),
    # the loader test DuplicateTransmissions loads it (a later one overwrites): a warning
    "ros_control__transmission_interface_loader_duplicate.urdf": ({"TX108": 1}, set()),
    # 8 clean transmissions; the mimic fingers have none
    "ros_kortex__gen3_robotiq_2f_85.urdf": ({}, set()),
    # the mimic right finger has its own transmission
    "sawyer_robot__sawyer.urdf": ({}, {"TX202"}),
    "shadow__middle.transmission.xacro": ({}, set()),
    # licence comment before the XML declaration: tinyxml2 refuses a declaration after a node
    "shadow__shadowhand_motor.urdf": ({"TX001": 1}, set()),
    # the ros2_control macro alone: no transmission in it (TX006 when named)
    "tiago__ros2_control.urdf.xacro": ({"TX006": 1}, set()),
    "tiago__ros2_control_transmissions.urdf.xacro": ({}, set()),
    # 33 top-level hey5_transmissions/Hey5Reducer plugins (custom, outside <ros2_control>) in
    # a robot whose <gazebo> plugin is gazebo_ros2_control: it parses only <ros2_control>'s
    # children (ros2_control's component parser), so they are read by nothing (TX305, info)
    "tiago_robot__tiago_pal-hey5.urdf": ({}, {"TX305"}),
    # 6 clean transmissions, interface on the joint only
    "universal_robot__ur5e.urdf": ({}, set()),
    "ur_description__ur_transmissions.xacro": ({}, set()),
    "urdf_sim_tutorial__12-gripper.urdf.xacro": ({}, {"TX302"}),
    # gripper joints name only the typo 'hardware_interface/EffortJoinInterface': refused
    "yumi__yumi.urdf": ({}, {"TX204", "TX205"}),
}


def _own(code: str) -> bool:
    return code.startswith(("TX0", "TX1"))


def test_every_corpus_file_has_an_expectation():
    names = corpus_names()
    if names == ["<corpus missing>"]:
        corpus_file("MANIFEST.tsv")  # skips, or fails under TXTOOL_REQUIRE_CORPUS=1
    assert sorted(EXPECTED) == names


@pytest.mark.parametrize("name", corpus_names())
def test_corpus_file_findings_match_its_documented_defects(name):
    path = corpus_file(name)
    result = CliRunner().invoke(cli, ["validate", "--format", "json", str(path)])
    assert result.exception is None or isinstance(result.exception, SystemExit)
    report = json.loads(result.stdout)
    codes = Counter(p["code"] for p in report["problems"])
    own, others = EXPECTED[name]
    failing = report["summary"]["errors"] > 0
    assert result.exit_code == (1 if failing else 0), result.stderr
    assert {c: n for c, n in codes.items() if _own(c)} == own
    assert {c for c in codes if not _own(c)} == others


@pytest.mark.parametrize(("name", "exit_code"), [
    # gazebo_ros_control (their <gazebo> plugin) accepts the unprefixed interfaces
    ("baxter__baxter.urdf", 0),
    ("nao_robot__naoV50.urdf", 0),
    # 'EffortJoinInterface' stops gazebo_ros_control too ("No matching hardware interface")
    ("yumi__yumi.urdf", 1),
])
def test_robots_described_for_gazebo_are_judged_by_gazebo_ros_control_too(name, exit_code):
    result = CliRunner().invoke(cli, ["validate", "--format", "json", "--select", "TX205",
                                      str(corpus_file(name))])
    report = json.loads(result.stdout)
    assert result.exit_code == exit_code
    severities = {p["severity"] for p in report["problems"]}
    assert severities == ({"warning"} if exit_code == 0 else {"error"})
    assert all("gazebo_ros_control (run by this robot's <gazebo> plugin" in p["message"]
               for p in report["problems"])
