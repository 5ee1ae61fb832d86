"""TX210: what urdfdom's model builder refuses in a whole robot (ros/urdfdom
urdf_parser/src/model.cpp ``parseURDF``; urdf_model/model.h ``initTree``/``initRoot``), which
makes ros2_control's parser throw "Failed to parse URDF file"."""

from __future__ import annotations

from tests.rules.helpers import check, problems

TRANSMISSION = """
  <transmission name="t">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="shoulder">
      <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
    </joint>
    <actuator name="m"><mechanicalReduction>50</mechanicalReduction></actuator>
  </transmission>"""


def robot(body: str, name: str = ' name="r"') -> str:
    return f'<robot{name}>\n{body}{TRANSMISSION}\n</robot>\n'


ARM = """  <link name="base"/>
  <link name="arm"/>
  <joint name="shoulder" type="continuous">
    <parent link="{parent}"/><child link="arm"/>
  </joint>"""


def test_a_joint_whose_parent_link_is_missing():
    found = problems(robot(ARM.format(parent="torso")), select=["TX210"])
    assert [(p.line, p.column, p.code, p.severity) for p in found] == [(5, 5, "TX210", "error")]
    assert found[0].message == (
        'urdfdom refuses the robot ("Failed to build tree: parent link [torso] of joint '
        '[shoulder] not found"): so do the readers of the robot built on it (ros2_control '
        'throws "Failed to parse URDF file")')
    assert found[0].refuses_whole


def test_a_tree_passes():
    assert check(robot(ARM.format(parent="base")), select=["TX210"]) == []


def test_each_link_and_joint_urdfdom_cannot_read():
    body = """  <link name="base"/>
  <link/>
  <link name="base"/>
  <joint type="fixed"><parent link="base"/><child link="base"/></joint>
  <joint name="shoulder" type="hinge"><parent link="base"/><child link="base"/></joint>
  <joint name="elbow" type="revolute"><parent link="base"/><child link="base"/></joint>
  <joint name="wrist" type="prismatic"><parent link="base"/><child link="base"/>
    <limit effort="1"/></joint>
  <joint name="wrist" type="fixed"><parent link="base"/><child link="base"/></joint>"""
    assert check(robot(body, name=""), select=["TX210"]) == [
        (1, 1, "TX210", "error"),  # No name given for the robot.
        (3, 3, "TX210", "error"),  # No name given for the link.
        (4, 3, "TX210", "error"),  # link 'base' is not unique.
        (5, 3, "TX210", "error"),  # unnamed joint found
        (6, 3, "TX210", "error"),  # Joint [shoulder] has no known type [hinge]
        (7, 3, "TX210", "error"),  # Joint [elbow] is of type REVOLUTE but it does not ...
        (9, 5, "TX210", "error"),  # joint limit: no velocity
        (10, 3, "TX210", "error"),  # joint 'wrist' is not unique.
    ]


def test_links_that_are_not_one_tree():
    two = """  <link name="base"/>
  <link name="arm"/>
  <link name="spare"/>
  <joint name="shoulder" type="continuous"><parent link="base"/><child link="arm"/></joint>"""
    found = problems(robot(two), select=["TX210"])
    assert [(p.line, p.column) for p in found] == [(4, 3)]
    assert "Two root links found: [base] and [spare]" in found[0].message
    none = """  <link name="base"/>
  <link name="arm"/>
  <joint name="shoulder" type="continuous"><parent link="base"/><child link="arm"/></joint>
  <joint name="back" type="fixed"><parent link="arm"/><child link="base"/></joint>"""
    found = problems(robot(none), select=["TX210"])
    assert [(p.line, p.column) for p in found] == [(2, 3)]
    assert "No root link found. The robot xml is not a valid tree." in found[0].message


def test_a_link_with_two_parents_is_what_urdfdom_accepts():
    body = """  <link name="base"/>
  <link name="arm"/>
  <joint name="shoulder" type="continuous"><parent link="base"/><child link="arm"/></joint>
  <joint name="again" type="fixed"><parent link="base"/><child link="arm"/></joint>"""
    assert check(robot(body), select=["TX210"]) == []


def test_a_robot_no_controller_reads_is_not_judged():
    bare = '<robot name="r">\n' + ARM.format(parent="torso") + "\n</robot>\n"
    assert check(bare, select=["TX210"]) == []


def test_a_xacro_file_read_as_written_is_not_judged():
    """Its links may come from what it includes (here: an include that cannot be found)."""
    source = """<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="$(find missing_description)/urdf/base.xacro"/>
  <link name="arm"/>
  <joint name="shoulder" type="continuous"><parent link="base"/><child link="arm"/></joint>
""" + TRANSMISSION + "\n</robot>\n"
    assert check(source, filename="robot.urdf.xacro", select=["TX210"]) == []


def test_after_expansion_the_robot_is_whole():
    source = """<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="parent" value="torso"/>
  <link name="base"/>
  <link name="arm"/>
  <joint name="shoulder" type="continuous"><parent link="${parent}"/><child link="arm"/></joint>
""" + TRANSMISSION + "\n</robot>\n"
    found = problems(source, filename="robot.urdf.xacro", select=["TX210"])
    assert [(p.line, p.code) for p in found] == [(5, "TX210")]
    assert found[0].message.endswith("(after xacro expansion)")


def test_a_xacro_fragment_without_a_robot_name_is_not_judged():
    """Written to be included: its joints hang from its includer's links."""
    source = """<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <link name="arm"/>
  <joint name="shoulder" type="continuous"><parent link="base"/><child link="arm"/></joint>
""" + TRANSMISSION + "\n</robot>\n"
    assert check(source, filename="arm.urdf.xacro", select=["TX210"]) == []
    plain = source.replace(' xmlns:xacro="http://www.ros.org/wiki/xacro"', "")
    # as a plain file, it is a robot urdfdom refuses first for its missing name
    assert check(plain, select=["TX210"]) == [(1, 1, "TX210", "error")]
