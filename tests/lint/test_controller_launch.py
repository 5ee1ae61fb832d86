"""TX504 through ``txtool validate`` on a package: two controllers a launch file of the package
starts claim one command interface. What the spawner lines say decides it (ROS 2 Python and
XML launch files, ROS 1 XML ones): started, not started (``--inactive``, ``--load-only``,
``--stopped``), under a condition, named through an argument."""

from __future__ import annotations

import pytest
from click.testing import CliRunner

from txtool.cli import cli

ROS2_ROBOT = """<robot name="r">
  <link name="a"/><link name="b"/>
  <joint name="j" type="revolute"><parent link="a"/><child link="b"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <ros2_control name="r" type="system">
    <hardware><plugin>mock_components/GenericSystem</plugin></hardware>
    <joint name="j"><command_interface name="position"/><command_interface name="velocity"/>
      <state_interface name="position"/></joint>
  </ros2_control>
</robot>
"""
ROS2_CONTROLLERS = """\
controller_manager:
  ros__parameters:
    pos:
      type: position_controllers/JointGroupPositionController
    pos_too:
      type: forward_command_controller/ForwardCommandController
    vel:
      type: velocity_controllers/JointGroupVelocityController
pos:
  ros__parameters:
    joints: [j]
pos_too:
  ros__parameters:
    joints: [j]
    interface_name: position
vel:
  ros__parameters:
    joints: [j]
"""
ROS1_ROBOT = """<robot name="r">
  <link name="a"/><link name="b"/>
  <joint name="j" type="revolute"><parent link="a"/><child link="b"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <transmission name="t"><type>transmission_interface/SimpleTransmission</type>
    <joint name="j">
      <hardwareInterface>hardware_interface/PositionJointInterface</hardwareInterface>
      <hardwareInterface>hardware_interface/VelocityJointInterface</hardwareInterface></joint>
    <actuator name="m"><mechanicalReduction>1</mechanicalReduction></actuator>
  </transmission>
</robot>
"""
ROS1_CONTROLLERS = """\
state:
  type: joint_state_controller/JointStateController
pos:
  type: position_controllers/JointPositionController
  joint: j
vel:
  type: velocity_controllers/JointVelocityController
  joint: j
"""


def spawner_py(arguments: str, extra: str = "") -> str:
    return ("from launch import LaunchDescription\nfrom launch_ros.actions import Node\n"
            "def generate_launch_description():\n    return LaunchDescription([\n"
            f'        Node(package="controller_manager", executable="spawner",\n'
            f"             arguments={arguments}{extra}),\n    ])\n")


def run_package(tmp_path, monkeypatch, robot: str, controllers: str,
                launches: dict[str, str]) -> tuple[int, list[str]]:
    monkeypatch.chdir(tmp_path)
    (tmp_path / "package.xml").write_text('<package format="3"><name>p</name></package>')
    for folder in ("urdf", "config", "launch"):
        (tmp_path / folder).mkdir()
    (tmp_path / "urdf" / "robot.urdf").write_text(robot)
    (tmp_path / "config" / "controllers.yaml").write_text(controllers)
    for name, text in launches.items():
        (tmp_path / "launch" / name).write_text(text)
    result = CliRunner().invoke(cli, ["validate", ".", "-q", "--color", "never", "--select",
                                      "TX5"], catch_exceptions=False)
    return result.exit_code, result.stdout.splitlines()


@pytest.mark.parametrize(("launches", "expected"), [
    # one spawner starts both position controllers: the second is refused
    ({"a.launch.py": spawner_py('["pos", "pos_too", "-c", "/controller_manager"]')},
     ["config/controllers.yaml:5:5: error TX504 controllers-claim-one-interface: controller 'pos_too' "
      "(forward_command_controller/ForwardCommandController) claims command interface "
      "'j/position', which 'pos' claims too, and launch/a.launch.py:5 starts both: the "
      "controller manager refuses the one activated second: Resource conflict for controller "
      "'pos_too'. Command interface 'j/position' is already claimed"]),
    # position and velocity of one joint: two interfaces, no conflict in ROS 2
    ({"a.launch.py": spawner_py('["pos", "vel"]')}, []),
    # not started: --inactive, --load-only, per controller --inactive
    ({"a.launch.py": spawner_py('["pos", "pos_too", "--inactive"]')}, []),
    ({"a.launch.py": spawner_py('["pos", "pos_too", "--load-only"]')}, []),
    ({"a.launch.py": spawner_py('["--controller", "pos", "--controller", "pos_too", '
                                '"--inactive"]')}, []),
    # a condition, or a word known only at launch where an option may stand
    ({"a.launch.py": spawner_py('["pos", "pos_too"]', ", condition=IfCondition(x)")}, []),
    ({"a.launch.py": spawner_py('["pos", "pos_too", flag]')}, []),
    # what follows --ros-args is the node's ROS arguments, no controller
    ({"a.launch.py": spawner_py('["pos", "--ros-args", "-r", "pos_too"]')}, []),
    # a name given through --param-file's value is no controller
    ({"a.launch.py": spawner_py('["pos", "--param-file", "pos_too"]')}, []),
    # alternatives in two launch files
    ({"a.launch.py": spawner_py('["pos"]'), "b.launch.py": spawner_py('["pos_too"]')}, []),
    # an XML launch file of ROS 2
    ({"a.launch.xml": '<launch>\n<node pkg="controller_manager" exec="spawner" '
                      'args="pos pos_too"/>\n</launch>\n'},
     ["config/controllers.yaml:5:5: error TX504 controllers-claim-one-interface: controller 'pos_too' "
      "(forward_command_controller/ForwardCommandController) claims command interface "
      "'j/position', which 'pos' claims too, and launch/a.launch.xml:2 starts both: the "
      "controller manager refuses the one activated second: Resource conflict for controller "
      "'pos_too'. Command interface 'j/position' is already claimed"]),
    # launch files that do not parse give nothing
    ({"a.launch.py": "def (:\n", "b.launch.xml": "<launch><node"}, []),
])
def test_ros2_spawners(tmp_path, monkeypatch, launches, expected):
    code, lines = run_package(tmp_path, monkeypatch, ROS2_ROBOT, ROS2_CONTROLLERS, launches)
    assert (code, lines) == (1 if expected else 0, expected)


def test_two_spawners_of_one_launch_file(tmp_path, monkeypatch):
    launch = spawner_py('["pos"]').replace(
        "    ])\n", '        Node(package="controller_manager", executable="spawner",\n'
                   '             arguments=["pos_too"]),\n    ])\n')
    code, lines = run_package(tmp_path, monkeypatch, ROS2_ROBOT, ROS2_CONTROLLERS,
                              {"a.launch.py": launch})
    assert code == 1
    assert [line.split(" claims")[0] for line in lines] == [
        "config/controllers.yaml:5:5: error TX504 controllers-claim-one-interface: controller 'pos_too' "
        "(forward_command_controller/ForwardCommandController)"]
    assert "launch/a.launch.py:7 starts both" in lines[0]


@pytest.mark.parametrize(("node", "expected"), [
    ('<node pkg="controller_manager" type="spawner" name="s" args="state pos vel"/>',
     ["config/controllers.yaml:6:1: error TX504 controllers-claim-one-interface: "
      "controller 'vel' "
      "(velocity_controllers/JointVelocityController) claims joint 'j', which 'pos' claims "
      "too, and launch/a.launch:3 starts both: the controller manager refuses to start them "
      "together: Could not switch controllers, due to resource conflict"]),
    ('<node pkg="controller_manager" type="controller_manager" name="s" '
     'args="spawn pos vel"/>', ["config/controllers.yaml:6:1: error TX504"]),
    ('<node pkg="controller_manager" type="spawner" name="s" args="pos vel --stopped"/>', []),
    ('<node pkg="controller_manager" type="spawner" name="s" args="pos $(arg other)"/>', []),
    ('<node pkg="controller_manager" type="spawner" name="s" args="state pos" />\n'
     '<node pkg="controller_manager" type="spawner" name="t" args="vel" '
     'if="$(arg velocity)"/>', []),
    ('<group unless="$(arg sim)"><node pkg="controller_manager" type="spawner" name="s" '
     'args="pos vel"/></group>', []),
    ('<node pkg="controller_manager" type="spawner" name="s" args="state"/>\n'
     '<node pkg="controller_manager" type="spawner" name="t" args="pos"/>', []),
])
def test_ros1_spawners(tmp_path, monkeypatch, node, expected):
    """ROS 1: a joint's handle is claimed whatever the interface: position and velocity
    controllers of one joint conflict; the joint state controller claims nothing."""
    code, lines = run_package(tmp_path, monkeypatch, ROS1_ROBOT, ROS1_CONTROLLERS,
                              {"a.launch": f'<launch>\n<arg name="x"/>\n{node}\n</launch>\n'})
    assert code == (1 if expected else 0)
    assert [line[:len(e)] for line, e in zip(lines, expected, strict=True)] == expected
