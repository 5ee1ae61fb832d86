"""``txtool migrate PATH --to ros2-p2 --controllers ROS1.yaml``: convert's report of what each
ROS 1 controller is in ROS 2, against the robot the migration writes (exit code and output
asserted together)."""

from __future__ import annotations

from click.testing import CliRunner

from tests.migrate.test_convert_controllers import ROBOT
from tests.rules.test_tx5xx_real_packages import RRBOT_CONTROL, rrbot_workspace
from txtool.cli import cli

CONTROLLERS = """\
arm:
  type: effort_controllers/JointTrajectoryController
  joints: [j]
hold:
  type: position_controllers/JointPositionController
  joint: j
"""
ARM = ("note: controllers.yaml:1:1: controller 'arm' (effort_controllers/JointTrajectoryController) "
       "is joint_trajectory_controller/JointTrajectoryController in ROS 2 (joints: [j], "
       "command_interfaces: [effort], state_interfaces: [position, velocity]); the converted "
       "<ros2_control> provides what it claims")
HOLD = ("warning: controllers.yaml:4:1: controller 'hold' (position_controllers/"
        "JointPositionController) is forward_command_controller/ForwardCommandController in "
        "ROS 2 (joints: [j], interface_name: position); the converted <ros2_control> lacks "
        "j/position (command)")
# Where these tests look, the robot's <ros2_control> says nothing of a placeholder.
PLUGIN = ("--hardware-plugin", "my/Hardware")


def migrate(*args: str) -> tuple[int, str, list[str]]:
    result = CliRunner().invoke(cli, ["migrate", *args], catch_exceptions=False)
    return result.exit_code, result.stdout, result.stderr.splitlines()


def test_write_says_what_each_controller_claims_of_the_written_robot(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "robot.urdf").write_text(ROBOT)
    (tmp_path / "controllers.yaml").write_text(CONTROLLERS)
    code, out, err = migrate("robot.urdf", "--to", "ros2-p2", "--write", *PLUGIN,
                             "--controllers", "controllers.yaml")
    # As convert: what the controllers lack is a warning; the migration stands.
    assert (code, out) == (0, "")
    assert err == ["changed robot.urdf (1 transmission(s) to ros2-p2)", "1 file(s) changed",
                   ARM, HOLD]
    assert b'<command_interface name="effort"/>' in (tmp_path / "robot.urdf").read_bytes()
    # Once migrated, the file as it stands is the robot judged.
    code, out, err = migrate("robot.urdf", "--to", "ros2-p2", "--check", *PLUGIN,
                             "--controllers", "controllers.yaml")
    assert (code, out) == (0, "")
    assert err == ["nothing to do (1 file(s) checked)", ARM, HOLD]


def test_diff_judges_what_would_be_written_and_writes_nothing(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "robot.urdf").write_text(ROBOT)
    (tmp_path / "controllers.yaml").write_text(CONTROLLERS)
    code, out, err = migrate("robot.urdf", "--to", "ros2-p1", "--diff", *PLUGIN,
                             "--controllers", "controllers.yaml")
    assert code == 1
    assert out.startswith("--- a/robot.urdf\n+++ b/robot.urdf\n")
    assert err[-4:] == ["would change robot.urdf (1 transmission(s) to ros2-p1)",
                        "1 file(s) would be changed", ARM, HOLD]
    assert (tmp_path / "robot.urdf").read_text() == ROBOT


def test_controllers_are_refused_as_convert_refuses_them(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "robot.urdf").write_text(ROBOT)
    (tmp_path / "controllers.yaml").write_text(CONTROLLERS)
    (tmp_path / "ros2.yaml").write_text(
        "controller_manager:\n  ros__parameters:\n    jsb:\n"
        "      type: joint_state_broadcaster/JointStateBroadcaster\n")
    assert migrate("robot.urdf", "--to", "ros2-p2", "--write", "--controllers", "ros2.yaml") == (
        2, "", ["txtool: ros2.yaml: no ROS 1 controller configuration (a controller namespace "
                "with a type)"])
    assert (tmp_path / "robot.urdf").read_text() == ROBOT  # refused before anything is written
    for target in (("--to", "ros1"), ()):
        assert migrate("robot.urdf", *target, "--check", "--controllers", "controllers.yaml") == (
            2, "", ["txtool: --controllers applies to --to ros2-p1 and ros2-p2"])
    assert migrate("robot.urdf", "--to", "ros2-p2", "--check", "--controllers", "none.yaml") == (
        2, "", ["txtool: none.yaml: no such file"])


def test_controllers_no_migrated_robot_drives(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "robot.urdf").write_text(ROBOT)
    (tmp_path / "other.urdf").write_text(ROBOT.replace('name="j"', 'name="k"'))
    (tmp_path / "controllers.yaml").write_text(CONTROLLERS.replace("[j]", "[z]")
                                               .replace("joint: j", "joint: z"))
    code, out, err = migrate(".", "--to", "ros2-p2", "--check", *PLUGIN,
                             "--controllers", "controllers.yaml")
    assert (code, out) == (1, "")
    assert err[-1] == ("note: controllers.yaml: no robot converted to ROS 2 here drives the "
                       "joints its controllers claim; not checked")




def test_rrbot_package_with_its_controllers(tmp_path, monkeypatch):
    """The workspace's rrbot_description (gazebo_ros_demos) migrated with the controllers of
    its rrbot_control package (config/rrbot_control.yaml of the same repository, as in
    tests/rules/test_tx5xx_real_packages.py): the ROS 2 controllers its effort
    transmissions serve."""
    src = rrbot_workspace(tmp_path, RRBOT_CONTROL)
    monkeypatch.chdir(tmp_path)
    code, out, err = migrate("src/rrbot_description", "--to", "ros2-p2", "--write", *PLUGIN,
                             "--controllers", "src/rrbot_control/config/rrbot_control.yaml")
    assert (code, out) == (0, "")
    yaml = "src/rrbot_control/config/rrbot_control.yaml"
    at = err.index("2 file(s) changed")
    assert err[at + 1:] == [
        f"note: {yaml}: against src/rrbot_description/urdf/rrbot.xacro, the robot driving "
        "most of the joints its controllers claim",
        f"note: {yaml}:3:3: controller 'joint_state_controller' (joint_state_controller/"
        "JointStateController) is joint_state_broadcaster/JointStateBroadcaster in ROS 2; the "
        "converted <ros2_control> provides what it claims",
        *(f"note: {yaml}:{line}:3: controller 'joint{n}_position_controller' (effort_controllers"
          "/JointPositionController) is pid_controller/PidController in ROS 2 (dof_names: "
          f"[joint{n}], command_interface: effort, reference_and_state_interfaces: [position]); "
          "its pid gains go to pid_controller's gains; the converted <ros2_control> provides "
          "what it claims" for n, line in ((1, 8), (2, 12))),
    ]
    written = (src / "rrbot_description" / "urdf" / "rrbot.xacro").read_text()
    assert '<joint name="joint1">' in written and "<plugin>my/Hardware</plugin>" in written
