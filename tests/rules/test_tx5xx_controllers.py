"""Controller configurations against the robot they drive (TX500-TX503).

Each test writes a robot and a controller YAML, runs ``txtool validate ROBOT --controllers
YAML`` through the library's ``validate``, and expects the findings in the YAML file at the
controller's name (line, column, code): each standard controller type of ros_controllers
(ROS 1) and ros2_controllers (ROS 2), with the interfaces it claims.
"""

from __future__ import annotations

import textwrap

import pytest

import txtool

JOINTS = """
  <link name="base"/><link name="a"/><link name="b"/><link name="w1"/><link name="w2"/>
  <joint name="j1" type="revolute"><parent link="base"/><child link="a"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="j2" type="revolute"><parent link="a"/><child link="b"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="left" type="continuous"><parent link="base"/><child link="w1"/></joint>
  <joint name="right" type="continuous"><parent link="base"/><child link="w2"/></joint>
"""


def ros1_robot(**interfaces: str) -> str:
    """A ROS 1 robot whose joints have transmissions with these interfaces (joint=Interface)."""
    body = "".join(
        f'<transmission name="t_{joint}"><type>transmission_interface/SimpleTransmission</type>'
        f'<joint name="{joint}"><hardwareInterface>hardware_interface/{iface}'
        f'</hardwareInterface></joint><actuator name="m_{joint}"><mechanicalReduction>1'
        "</mechanicalReduction></actuator></transmission>\n"
        for joint, iface in interfaces.items())
    return f'<robot name="r">{JOINTS}{body}</robot>\n'


def ros2_robot(**joints: tuple[str, str]) -> str:
    """A ROS 2 robot: joint=("command,interfaces", "state,interfaces")."""
    body = "".join(
        f'<joint name="{joint}">'
        + "".join(f'<command_interface name="{c}"/>' for c in commands.split(",") if c)
        + "".join(f'<state_interface name="{s}"/>' for s in states.split(",") if s)
        + "</joint>"
        for joint, (commands, states) in joints.items())
    return (f'<robot name="r">{JOINTS}<ros2_control name="s" type="system"><hardware><plugin>'
            f"mock_components/GenericSystem</plugin></hardware>{body}</ros2_control></robot>\n")


def findings(tmp_path, robot: str, yaml: str, **options) -> list[tuple[int, int, str]]:
    (tmp_path / "robot.urdf").write_text(robot)
    (tmp_path / "controllers.yaml").write_text(textwrap.dedent(yaml).lstrip("\n"))
    found = txtool.validate([str(tmp_path / "robot.urdf")],
                            controllers=[str(tmp_path / "controllers.yaml")], **options)
    assert all(p.path.endswith("controllers.yaml") for p in found if p.code >= "TX500")
    return [(p.line, p.column, p.code) for p in found if p.code >= "TX500"]


# ROS 1: each standard type, the interface it requires, and the joint parameter it reads.
ROS1_TYPES = [
    ("position_controllers/JointPositionController", "PositionJointInterface", "joint"),
    ("position_controllers/JointGroupPositionController", "PositionJointInterface", "joints"),
    ("velocity_controllers/JointVelocityController", "VelocityJointInterface", "joint"),
    ("velocity_controllers/JointPositionController", "VelocityJointInterface", "joint"),
    ("velocity_controllers/JointGroupVelocityController", "VelocityJointInterface", "joints"),
    ("effort_controllers/JointPositionController", "EffortJointInterface", "joint"),
    ("effort_controllers/JointVelocityController", "EffortJointInterface", "joint"),
    ("effort_controllers/JointEffortController", "EffortJointInterface", "joint"),
    ("effort_controllers/JointGroupEffortController", "EffortJointInterface", "joints"),
    ("effort_controllers/JointGroupPositionController", "EffortJointInterface", "joints"),
    ("position_controllers/JointTrajectoryController", "PositionJointInterface", "joints"),
    ("velocity_controllers/JointTrajectoryController", "VelocityJointInterface", "joints"),
    ("effort_controllers/JointTrajectoryController", "EffortJointInterface", "joints"),
    ("pos_vel_controllers/JointTrajectoryController", "PosVelJointInterface", "joints"),
    ("pos_vel_acc_controllers/JointTrajectoryController", "PosVelAccJointInterface", "joints"),
    ("position_controllers/GripperActionController", "PositionJointInterface", "joint"),
    ("effort_controllers/GripperActionController", "EffortJointInterface", "joint"),
]
OTHER = {"PositionJointInterface": "EffortJointInterface"}


@pytest.mark.parametrize(("type_", "interface", "key"), ROS1_TYPES)
def test_ros1_each_type_needs_its_hardware_interface(tmp_path, type_, interface, key):
    joints = "j1" if key == "joint" else "[j1, j2]"
    yaml = f"""
    arm:
      controller:
        type: {type_}
        {key}: {joints}
    """
    provided = {"j1": interface, "j2": interface}
    assert findings(tmp_path, ros1_robot(**provided), yaml) == []
    other = OTHER.get(interface, "PositionJointInterface")
    assert findings(tmp_path, ros1_robot(j1=other, j2=interface), yaml) == [(2, 3, "TX501")]


def test_ros1_the_message_is_the_managers_reason(tmp_path):
    yaml = """
    c:
      type: position_controllers/JointPositionController
      joint: j1
    """
    (tmp_path / "robot.urdf").write_text(ros1_robot(j1="EffortJointInterface"))
    (tmp_path / "c.yaml").write_text(textwrap.dedent(yaml).lstrip("\n"))
    [problem] = txtool.validate([str(tmp_path / "robot.urdf")],
                                controllers=[str(tmp_path / "c.yaml")])
    assert problem.message.endswith(
        "This controller requires a hardware interface of type "
        "'hardware_interface::PositionJointInterface'")
    (tmp_path / "robot.urdf").write_text(ros1_robot(j1="EffortJointInterface",
                                                    j2="PositionJointInterface"))
    [problem] = txtool.validate([str(tmp_path / "robot.urdf")],
                                controllers=[str(tmp_path / "c.yaml")])
    assert problem.message.endswith(
        "Could not find resource 'j1' in 'hardware_interface::PositionJointInterface'")


def test_ros1_joint_state_controller_and_diff_drive(tmp_path):
    yaml = """
    joint_state_controller:
      type: joint_state_controller/JointStateController
      publish_rate: 50
    base:
      type: diff_drive_controller/DiffDriveController
      left_wheel: left
      right_wheel: [right]
    """
    robot = ros1_robot(left="VelocityJointInterface", right="EffortJointInterface")
    assert findings(tmp_path, robot, yaml) == [(4, 1, "TX501")]


def test_ros1_missing_and_undriven_joints(tmp_path):
    yaml = """
    arm:
      type: effort_controllers/JointTrajectoryController
      joints: [j1, j2, nowhere]
    """
    assert findings(tmp_path, ros1_robot(j1="EffortJointInterface"), yaml) == [
        (1, 1, "TX500"), (1, 1, "TX500")]


def test_ros1_legacy_interface_names_are_the_same_class(tmp_path):
    robot = ros1_robot(j1="EffortJointInterface").replace(
        "hardware_interface/EffortJointInterface", "EffortJointInterface")
    yaml = """
    c:
      type: effort_controllers/JointEffortController
      joint: j1
    """
    assert findings(tmp_path, robot, yaml) == []


def test_ros1_a_robot_without_transmissions_is_not_judged(tmp_path):
    """Its RobotHW (C++) registers the interfaces: nothing in the files says which."""
    yaml = """
    c:
      type: effort_controllers/JointEffortController
      joint: j1
    """
    assert findings(tmp_path, f'<robot name="r">{JOINTS}</robot>\n', yaml) == []


def manager(*controllers: tuple[str, str], params: str = "") -> str:
    listed = "".join(f"    {name}:\n      type: {type_}\n" for name, type_ in controllers)
    return f"controller_manager:\n  ros__parameters:\n    update_rate: 100\n{listed}{params}"


FULL = ("position,velocity,effort", "position,velocity,effort")


@pytest.mark.parametrize(("type_", "params", "command", "state"), [
    ("joint_trajectory_controller/JointTrajectoryController",
     "joints: [j1]\n    command_interfaces: [velocity]\n    state_interfaces: [position]",
     "velocity", "position"),
    ("forward_command_controller/ForwardCommandController",
     "joints: [j1]\n    interface_name: effort", "effort", None),
    ("position_controllers/JointGroupPositionController", "joints: [j1]", "position", None),
    ("velocity_controllers/JointGroupVelocityController", "joints: [j1]", "velocity", None),
    ("effort_controllers/JointGroupEffortController", "joints: [j1]", "effort", None),
    ("parallel_gripper_action_controller/GripperActionController", "joint: j1", "position",
     "velocity"),
    ("position_controllers/GripperActionController", "joint: j1", "position", "velocity"),
    ("effort_controllers/GripperActionController", "joint: j1", "effort", "velocity"),
    ("admittance_controller/AdmittanceController",
     "joints: [j1]\n    command_interfaces: [position]\n    state_interfaces: [velocity]",
     "position", "velocity"),
    ("joint_state_broadcaster/JointStateBroadcaster",
     "joints: [j1]\n    interfaces: [effort]", None, "effort"),
])
def test_ros2_each_type_claims_its_interfaces(tmp_path, type_, params, command, state):
    yaml = manager(("c", type_), params=f"c:\n  ros__parameters:\n    {params}\n")
    assert findings(tmp_path, ros2_robot(j1=FULL), yaml) == []
    if command is not None:
        commands = ",".join(i for i in FULL[0].split(",") if i != command)
        assert findings(tmp_path, ros2_robot(j1=(commands, FULL[1])), yaml) == [(4, 5, "TX501")]
    if state is not None:
        states = ",".join(i for i in FULL[1].split(",") if i != state)
        assert findings(tmp_path, ros2_robot(j1=(FULL[0], states)), yaml) == [(4, 5, "TX502")]


def test_ros2_diff_drive_wheels_and_feedback(tmp_path):
    params = ("base:\n  ros__parameters:\n    left_wheel_names: [left]\n"
              "    right_wheel_names: [right]\n")
    yaml = manager(("base", "diff_drive_controller/DiffDriveController"), params=params)
    wheels = {"left": ("velocity", "position"), "right": ("velocity", "velocity")}
    assert findings(tmp_path, ros2_robot(**wheels), yaml) == [(4, 5, "TX502")]
    yaml = yaml.replace("[right]\n", "[right]\n    position_feedback: false\n")
    wheels["left"] = ("velocity", "velocity")
    assert findings(tmp_path, ros2_robot(**wheels), yaml) == []


def test_ros2_a_namespaced_controller_and_its_wildcard_parameters(tmp_path):
    yaml = """
    /robot/controller_manager:
      ros__parameters:
        arm:
          type: joint_trajectory_controller/JointTrajectoryController
    /**/arm:
      ros__parameters:
        joints: [j1, j9]
        command_interfaces: [position]
        state_interfaces: [position]
    """
    assert findings(tmp_path, ros2_robot(j1=("position", "position")), yaml) == [
        (3, 5, "TX500")]


def test_ros2_an_unknown_type_is_a_warning_and_a_ros1_type_is_unknown(tmp_path):
    yaml = manager(("jsc", "joint_state_controller/JointStateController"),
                   ("jsb", "joint_state_broadcaster/JointStateBroadcaster"))
    (tmp_path / "robot.urdf").write_text(ros2_robot(j1=FULL))
    (tmp_path / "c.yaml").write_text(yaml)
    found = txtool.validate([str(tmp_path / "robot.urdf")],
                            controllers=[str(tmp_path / "c.yaml")])
    assert [(p.line, p.code, p.severity) for p in found if p.code >= "TX500"] == [
        (4, "TX503", "warning")]


def test_a_type_the_workspace_exports_is_known(tmp_path):
    vendor = tmp_path / "vendor_controllers"
    vendor.mkdir()
    (vendor / "package.xml").write_text(
        '<package format="3"><name>vendor_controllers</name><export><controller_interface '
        'plugin="${prefix}/plugins.xml"/></export></package>')
    (vendor / "plugins.xml").write_text(
        '<library path="v"><class name="vendor_controllers/Arm" type="v::Arm" '
        'base_class_type="controller_interface::ControllerInterface"/></library>')
    robot_package = tmp_path / "robot_bringup"
    (robot_package / "config").mkdir(parents=True)
    (robot_package / "package.xml").write_text(
        '<package format="3"><name>robot_bringup</name></package>')
    (robot_package / "robot.urdf").write_text(ros2_robot(j1=FULL))
    yaml = manager(("arm", "vendor_controllers/Arm"), ("other", "vendor_controllers/Leg"))
    (robot_package / "config" / "c.yaml").write_text(yaml)
    found = txtool.validate([str(robot_package)])
    assert [(p.line, p.code) for p in found if p.code >= "TX500"] == [(6, "TX503")]


def test_a_package_walk_pairs_the_robot_with_its_controller_files(tmp_path):
    (tmp_path / "package.xml").write_text('<package format="3"><name>p</name></package>')
    (tmp_path / "urdf").mkdir()
    (tmp_path / "config").mkdir()
    (tmp_path / "urdf" / "robot.urdf").write_text(ros1_robot(j1="EffortJointInterface"))
    (tmp_path / "config" / "arm.yaml").write_text(
        "arm:\n  type: position_controllers/JointPositionController\n  joint: j1\n")
    (tmp_path / "config" / "other.yaml").write_text("not_controllers:\n  rate: 5\n")
    found = [p for p in txtool.validate([str(tmp_path)]) if p.code >= "TX500"]
    assert [(p.path, p.line, p.column, p.code) for p in found] == [
        (str(tmp_path / "config" / "arm.yaml"), 1, 1, "TX501")]
    # Named alone, the robot is judged only against the files --controllers names.
    assert [p for p in txtool.validate([str(tmp_path / "urdf" / "robot.urdf")])
            if p.code >= "TX500"] == []


def test_the_robot_with_most_of_the_claimed_joints_is_the_one_judged(tmp_path):
    """A package with an arm and a gripper: each controller file is for one of them."""
    (tmp_path / "package.xml").write_text('<package format="3"><name>p</name></package>')
    (tmp_path / "arm.urdf").write_text(ros1_robot(j1="EffortJointInterface"))
    (tmp_path / "gripper.urdf").write_text(
        '<robot name="g"><link name="a"/><link name="b"/><joint name="finger" type="prismatic">'
        '<parent link="a"/><child link="b"/><limit lower="0" upper="1" effort="1" velocity="1"/>'
        '</joint><transmission name="t"><type>transmission_interface/SimpleTransmission</type>'
        '<joint name="finger"><hardwareInterface>hardware_interface/PositionJointInterface'
        '</hardwareInterface></joint><actuator name="m"/></transmission></robot>')
    (tmp_path / "gripper.yaml").write_text(
        "g:\n  type: position_controllers/GripperActionController\n  joint: finger\n")
    assert [p for p in txtool.validate([str(tmp_path)]) if p.code >= "TX500"] == []


def test_selection_and_configured_severity_apply(tmp_path):
    yaml = """
    c:
      type: effort_controllers/JointEfortController
      joint: j1
    """
    robot = ros1_robot(j1="EffortJointInterface")
    assert findings(tmp_path, robot, yaml, ignore=["TX503"]) == []
    assert findings(tmp_path, robot, yaml, select=["TX503"]) == [(1, 1, "TX503")]


def test_ros2_a_type_among_the_controllers_own_parameters(tmp_path):
    """ros2_control_demos' layout: no list under controller_manager; joint names with launch
    substitutions are unknown, not missing."""
    yaml = """
    joint_state_broadcaster:
      ros__parameters:
        type: joint_state_broadcaster/JointStateBroadcaster
    forward_position_controller:
      ros__parameters:
        type: forward_command_controller/ForwardCommandController
        joints: [$(var prefix)j1, j2]
        interface_name: effort
    """
    robot = ros2_robot(j1=("position", "position"), j2=("position", "position"))
    assert findings(tmp_path, robot, yaml) == [(4, 1, "TX501")]


def test_alternatives_in_one_file_are_warnings(tmp_path):
    """A file with, for the same joints, a controller the robot accepts and one it refuses: a
    launch file spawns one of them; the other is refused only if it is loaded."""
    yaml = """
    position:
      type: position_controllers/JointGroupPositionController
      joints: [j1]
    velocity:
      type: velocity_controllers/JointGroupVelocityController
      joints: [j1]
    """
    (tmp_path / "robot.urdf").write_text(ros1_robot(j1="PositionJointInterface"))
    (tmp_path / "c.yaml").write_text(textwrap.dedent(yaml).lstrip("\n"))
    found = txtool.validate([str(tmp_path / "robot.urdf")], controllers=[str(tmp_path / "c.yaml")])
    assert [(p.line, p.code, p.severity) for p in found] == [(4, "TX501", "warning")]
    assert "'position' of this file drives the joint as the robot is" in found[0].message


def test_an_interface_written_as_a_xacro_expression_makes_a_warning(tmp_path):
    """ur_description's transmissions take ${transmission_hw_interface}, which ur_gazebo's
    launch files set: the robot as expanded with the defaults is not the robot launched."""
    robot = ros1_robot(j1="PositionJointInterface", j2="PositionJointInterface").replace(
        '<robot name="r">', '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
        '<xacro:arg name="hw" default="hardware_interface/PositionJointInterface"/>'
        '<xacro:property name="hw" value="$(arg hw)"/>').replace(
        "hardware_interface/PositionJointInterface</hardwareInterface>",
        "${hw}</hardwareInterface>")
    (tmp_path / "robot.urdf.xacro").write_text(robot)
    (tmp_path / "c.yaml").write_text(
        "arm:\n  type: effort_controllers/JointTrajectoryController\n  joints: [j1, j2]\n")
    found = txtool.validate([str(tmp_path / "robot.urdf.xacro")],
                            controllers=[str(tmp_path / "c.yaml")])
    assert [(p.line, p.code, p.severity) for p in found] == [(1, "TX501", "warning")]
    assert "joints 'j1', 'j2' have no hardware interface" in found[0].message
    effort = txtool.validate([str(tmp_path / "robot.urdf.xacro")],
                             controllers=[str(tmp_path / "c.yaml")],
                             xacro_args={"hw": "hardware_interface/EffortJointInterface"})
    assert effort == []


def test_other_nodes_types_are_no_controllers(tmp_path):
    """A filter chain's parameters have a ``type`` too: it is no controller (and a file of
    them alone is no controller configuration)."""
    yaml = """
    mean:
      name: mean
      type: filters/MeanFilter
    arm:
      type: effort_controllers/JointEfortController
      joint: j1
    """
    assert findings(tmp_path, ros1_robot(j1="EffortJointInterface"), yaml) == [(4, 1, "TX503")]


def test_ros2_a_chained_controllers_reference_interfaces_are_not_the_robots(tmp_path):
    yaml = manager(("pid", "pid_controller/PidController"),
                   ("jtc", "joint_trajectory_controller/JointTrajectoryController"),
                   params="jtc:\n  ros__parameters:\n    joints: [j1]\n"
                          "    command_joints: [pid/j1]\n    command_interfaces: [velocity]\n"
                          "    state_interfaces: [position]\n")
    assert findings(tmp_path, ros2_robot(j1=("effort", "position")), yaml) == []
