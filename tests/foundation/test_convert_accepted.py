"""ROS 1 -> ROS 2 writes what ros2_control's parser accepts, where a faithful form exists.

Each decision follows the loaders' code (docs/conversion.md, "What the target accepts"):
mimic joints keep their command interfaces with ``mimic="false"``; a transmission on a fixed
joint or on one the robot lacks is left as written; each ROS 1 hardware interface becomes
its command interfaces; an existing block that declares some of a transmission's joints, and
a macro called several times, refuse the conversion with one line. tests/oracle/
test_conversion_accepted.py hands the results to the compiled parsers.
"""

from __future__ import annotations

import re
import textwrap

from lxml import etree

_LINK = re.compile(r'link="(l[0-9]+)"')


def _joint(name: str, kind: str = "revolute", parent: int = 0, child: int = 1,
           mimic: str | None = None) -> str:
    inner = (f'<parent link="l{parent}"/><child link="l{child}"/><axis xyz="0 0 1"/>'
             '<limit lower="-1" upper="1" effort="10" velocity="1"/>')
    if mimic:
        inner += f'<mimic joint="{mimic}"/>'
    return f'  <joint name="{name}" type="{kind}">{inner}</joint>\n'


def _transmission(name: str, joint: str, interface: str = "hardware_interface/EffortJointInterface"
                  ) -> str:
    return (f'  <transmission name="{name}">\n'
            "    <type>transmission_interface/SimpleTransmission</type>\n"
            f'    <joint name="{joint}"><hardwareInterface>{interface}</hardwareInterface></joint>\n'
            f'    <actuator name="{name}_motor"><mechanicalReduction>2</mechanicalReduction>'
            "</actuator>\n"
            "  </transmission>\n")


def _robot(*parts: str) -> str:
    """The robot of ``parts`` with the links its joints name: one tree, as urdfdom requires."""
    body = "".join(parts)
    links = "".join(f'<link name="{name}"/>' for name in sorted(set(_LINK.findall(body))))
    return f'<robot name="gripper">\n  {links}\n{body}</robot>\n'


GRIPPER = _robot(
    _joint("left", "prismatic", 0, 1), _joint("right", "prismatic", 0, 2, mimic="left"),
    _transmission("left_trans", "left"), _transmission("right_trans", "right"))


def _declarations(out: str) -> dict[str, tuple[str | None, list[str]]]:
    block = etree.fromstring(out.encode()).find("ros2_control")
    return {j.get("name"): (j.get("mimic"), [c.get("name") for c in j.findall("command_interface")])
            for j in block.findall("joint")}


def test_a_mimic_joint_keeps_its_command_interface_and_says_mimic_false(run, tmp_path):
    path = tmp_path / "gripper.urdf"
    path.write_text(GRIPPER)
    code, out, err = run("convert", str(path), "--to", "ros2-p2")
    assert code == 0
    assert _declarations(out) == {"left": (None, ["effort"]), "right": ("false", ["effort"])}
    assert ("note: joint 'right' mimics 'left' in the URDF: declared with mimic=\"false\", so "
            "that ros2_control keeps its command interfaces as ros_control did") in err
    # Converting back recognizes the block: the document comes back.
    back_path = tmp_path / "gripper.ros2.urdf"
    back_path.write_text(out)
    code, back, _ = run("convert", str(back_path), "--to", "ros1")
    assert code == 0 and "mimic" not in back.split("<transmission", 1)[1]


def test_only_the_mimic_of_a_joint_the_document_says_for_every_argument_counts(run, tmp_path):
    # The right finger mimics the left one only for some arguments (its definition in a
    # xacro:if): the document does not say, and no mimic="false" is written; a <mimic> that
    # is not a joint's own child is no joint's.
    conditional = (
        '  <xacro:unless value="${coupled}">\n' + _joint("right", "prismatic", 0, 2)
        + '  </xacro:unless>\n  <xacro:if value="${coupled}">\n'
        + _joint("right", "prismatic", 0, 2, mimic="left") + "  </xacro:if>\n")
    stray = '  <gazebo reference="left"><mimic joint="right"/></gazebo>\n'
    path = tmp_path / "gripper.urdf.xacro"
    path.write_text(_robot(_joint("left", "prismatic", 0, 1), conditional, stray,
                           _transmission("left_trans", "left"),
                           _transmission("right_trans", "right"))
                    .replace('<robot name="gripper">',
                             '<robot name="gripper" xmlns:xacro="http://ros.org/wiki/xacro">'))
    code, out, err = run("convert", "--no-xacro", str(path), "--to", "ros2-p2")
    assert code == 0
    assert _declarations(out) == {"left": (None, ["effort"]), "right": (None, ["effort"])}
    assert "mimics" not in err


def test_a_transmission_on_a_fixed_joint_is_left_as_written(run, tmp_path):
    path = tmp_path / "arm.urdf"
    robot = _robot(_joint("shoulder"), _joint("flange", "fixed", 1, 2),
                   _transmission("shoulder_trans", "shoulder"),
                   _transmission("flange_trans", "flange"))
    path.write_text(robot)
    code, out, err = run("convert", str(path), "--to", "ros2-p2")
    assert code == 0
    assert err.startswith(
        "warning: transmission 'flange_trans': left as written, not carried into "
        "<ros2_control>: ros2_control refuses a robot whose <ros2_control> declares its joint "
        "(\"Joint 'flange' is of type 'fixed'. Fixed joints do not make sense in "
        "ros2_control.\", component_parser.cpp), and ros_control could not drive it either; "
        "correct the joint's name or type, or delete the transmission\n")
    assert list(_declarations(out)) == ["shoulder"]
    assert _transmission("flange_trans", "flange") in out  # byte for byte, where it stood


def test_a_transmission_on_a_joint_the_robot_lacks_is_left_as_written(run, tmp_path):
    path = tmp_path / "arm.urdf"
    path.write_text(_robot(_joint("shoulder"), _transmission("shoulder_trans", "shoulder"),
                           _transmission("ghost_trans", "ghost")))
    code, out, err = run("convert", str(path), "--to", "ros2-p2")
    assert code == 0
    assert "(\"Joint 'ghost' not found in URDF\", component_parser.cpp)" in err
    assert list(_declarations(out)) == ["shoulder"]
    assert _transmission("ghost_trans", "ghost") in out


def test_a_xacro_file_as_written_may_get_its_joints_elsewhere(run, tmp_path):
    # Its robot may include the joint: nothing says it lacks one.
    path = tmp_path / "arm.urdf.xacro"
    path.write_text(_robot(_joint("shoulder"), _transmission("elbow_trans", "elbow"))
                    .replace('<robot name="gripper">',
                             '<robot name="arm" xmlns:xacro="http://ros.org/wiki/xacro">'))
    code, out, err = run("convert", "--no-xacro", str(path), "--to", "ros2-p2")
    assert code == 0 and list(_declarations(out)) == ["elbow"]


def test_every_ros1_interface_becomes_its_command_interfaces(run, tmp_path):
    names = {"a": "hardware_interface/PositionJointInterface", "b": "VelocityJointInterface",
             "c": "hardware_interface/BiDirectionalEffortJointInterface",
             "d": "hardware_interface/PosVelJointInterface",
             "e": "hardware_interface/PosVelAccJointInterface",
             "f": "hardware_interface/JointStateInterface"}
    joints = "".join(_joint(name, child=i + 1) for i, name in enumerate(names))
    path = tmp_path / "arm.urdf"
    path.write_text(_robot(joints, *(_transmission(f"{n}_trans", n, i) for n, i in names.items())))
    code, out, err = run("convert", str(path), "--to", "ros2-p2")
    assert code == 0
    assert {name: commands for name, (_, commands) in _declarations(out).items()} == {
        "a": ["position"], "b": ["velocity"], "c": ["effort"], "d": ["position", "velocity"],
        "e": ["position", "velocity", "acceleration"], "f": []}
    assert ("note: joint 'd': hardware_interface/PosVelJointInterface (ros_control's combined "
            "command handle) is declared as the command interfaces position, velocity") in err


def test_a_joint_naming_no_interface_takes_its_actuators(run, tmp_path):
    # rrbot's committed URDF: the interface on the actuator only, as gazebo_ros_control reads it.
    path = tmp_path / "rrbot.urdf"
    path.write_text(_robot(_joint("joint1"), '  <transmission name="tran1">\n'
                           "    <type>transmission_interface/SimpleTransmission</type>\n"
                           '    <joint name="joint1"/>\n'
                           '    <actuator name="motor1"><hardwareInterface>EffortJointInterface'
                           "</hardwareInterface><mechanicalReduction>1</mechanicalReduction>"
                           "</actuator>\n  </transmission>\n"))
    code, out, err = run("convert", str(path), "--to", "ros2-p2")
    assert code == 0
    assert _declarations(out) == {"joint1": (None, ["effort"])}
    assert err.startswith("note: joint 'joint1': names no <hardwareInterface>; given its "
                          "actuator's (EffortJointInterface), as gazebo_ros_control reads it")


def test_a_block_declaring_some_of_the_joints_refuses_a_second_block(run, tmp_path):
    block = ('  <ros2_control name="hw" type="system">\n'
             "    <hardware><plugin>my/Hardware</plugin></hardware>\n"
             '    <joint name="a"><command_interface name="effort"/></joint>\n'
             "  </ros2_control>\n")
    differential = ('  <transmission name="wrist">\n'
                    "    <type>transmission_interface/DifferentialTransmission</type>\n"
                    + "".join(f'    <joint name="{j}"><role>joint{i}</role><hardwareInterface>'
                              "EffortJointInterface</hardwareInterface><mechanicalReduction>1"
                              "</mechanicalReduction></joint>\n"
                              for i, j in ((1, "a"), (2, "b")))
                    + "".join(f'    <actuator name="m{i}"><role>actuator{i}</role>'
                              "<mechanicalReduction>1</mechanicalReduction></actuator>\n"
                              for i in (1, 2))
                    + "  </transmission>\n")
    path = tmp_path / "wrist.urdf"
    path.write_text(_robot(_joint("a"), _joint("b", child=2), block, differential))
    code, out, err = run("convert", str(path), "--to", "ros2-p2")
    assert (code, out) == (1, "")
    assert err.splitlines() == [
        "error: transmission 'wrist': <ros2_control name=\"hw\"> declares its joint(s) a but "
        "not b: a <ros2_control> of its own would declare them a second time (two hardware "
        "components claiming one joint); declare all its joints in one <ros2_control>, then "
        "convert again",
        # what the written file would be: the resource manager's own verdict on it
        "error: line 13: TX209 duplicate-interface for ros2_control (humble, jazzy, kilted, "
        "rolling): joint 'a' of <ros2_control> 'gripper' exports command interface 'a/effort', "
        "which <ros2_control> 'hw' (line 5) exports too: ros2_control's resource manager keeps "
        "one handle per name (Humble drops this block's without a word; from Jazzy on it logs "
        "\"Tried to insert CommandInterface with already existing key\"), so this block's "
        "hardware never gets it",
        "txtool: 2 item(s) would be lost; nothing written (use --allow-lossy to accept)"]


MACRO = """\
<robot name="cart" xmlns:xacro="http://ros.org/wiki/xacro">
  <xacro:macro name="wheel" params="side">
    <link name="${side}"/><joint name="${side}_wheel" type="continuous"><parent link="base"/><child link="${side}"/></joint>
    <transmission name="${side}_trans">
      <type>transmission_interface/SimpleTransmission</type>
      <joint name="${side}_wheel"><hardwareInterface>hardware_interface/VelocityJointInterface</hardwareInterface></joint>
      <actuator name="${side}_motor"><mechanicalReduction>1</mechanicalReduction></actuator>
    </transmission>
  </xacro:macro>
  <link name="base"/>
  <xacro:wheel side="left"/>
  <xacro:wheel side="right"/>
</robot>
"""


def test_a_macro_called_twice_is_refused_with_one_line_naming_it(run, tmp_path):
    path = tmp_path / "cart.urdf.xacro"
    path.write_text(MACRO)
    code, out, err = run("convert", "--no-xacro", str(path), "--to", "ros2-p2")
    assert (code, out) == (1, "")
    assert err.splitlines() == [
        "error: transmission '${side}_trans': inside <xacro:macro name=\"wheel\"> (line 2), "
        "which this file expands 2 times (called at line 11, line 12): converted there, each call "
        "would be a "
        "<ros2_control> hardware component of its own; write the transmissions where the "
        "robot's one <ros2_control> is (outside the macro), or convert the expanded robot",
        "txtool: 1 item(s) would be lost; nothing written (use --allow-lossy to accept)"]
    # The expanded robot converts: one block for both wheels.
    code, out, err = run("convert", str(path), "--to", "ros2-p2")
    assert code == 0 and out.count("<ros2_control ") == 1


def test_the_transmissions_of_one_macro_go_into_one_block(run, tmp_path):
    both = MACRO.replace('params="side"', 'params="side other"').replace(
        "  </xacro:macro>",
        '    <transmission name="${other}_trans">\n'
        "      <type>transmission_interface/SimpleTransmission</type>\n"
        '      <joint name="${other}_wheel"><hardwareInterface>hardware_interface/'
        "VelocityJointInterface</hardwareInterface></joint>\n"
        '      <actuator name="${other}_motor"><mechanicalReduction>1</mechanicalReduction>'
        "</actuator>\n    </transmission>\n  </xacro:macro>").replace(
        '  <xacro:wheel side="left"/>\n  <xacro:wheel side="right"/>\n',
        '  <xacro:wheel side="left" other="right"/>\n')
    path = tmp_path / "cart.urdf.xacro"
    path.write_text(both)
    code, out, err = run("convert", "--no-xacro", str(path), "--to", "ros2-p2")
    assert code == 0
    assert out.count("<ros2_control ") == 1 and out.count("<transmission ") == 2
    back = tmp_path / "cart.ros2.urdf.xacro"
    back.write_text(out)
    code, out, err = run("convert", "--no-xacro", str(back), "--to", "ros1")
    assert code == 0 and "<ros2_control" not in out


def test_migrate_counts_the_calls_in_the_other_files_and_names_the_next_steps(
        run, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)

    def write(name: str, text: str) -> None:
        path = tmp_path / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(textwrap.dedent(text).lstrip("\n"))

    write("cart_description/package.xml", """
        <package format="2"><name>cart_description</name>
          <buildtool_depend>catkin</buildtool_depend></package>
        """)
    write("cart_description/urdf/wheel.urdf.xacro", MACRO.replace(
        '  <xacro:wheel side="left"/>\n  <xacro:wheel side="right"/>\n', ""))
    write("cart_description/urdf/cart.urdf.xacro", """
        <robot name="cart" xmlns:xacro="http://ros.org/wiki/xacro">
          <xacro:include filename="$(find cart_description)/urdf/wheel.urdf.xacro"/>
          <xacro:wheel side="left"/>
          <xacro:wheel side="right"/>
        </robot>
        """)
    code, _, err = run("migrate", "--write", "--to", "ros2-p2", "cart_description")
    assert code == 1
    assert ("which the files migrated with it expand 2 times (called at cart_description/urdf/cart.urdf.xacro:3, "
            "cart_description/urdf/cart.urdf.xacro:4)") in err
    # Written from the robot instead: one block, and what else the package must change.
    write("cart_description/urdf/wheel.urdf.xacro", MACRO.split("  <xacro:macro")[0]
          + """\
  <link name="base"/>
  <xacro:macro name="wheel" params="side">
    <link name="${side}"/><joint name="${side}_wheel" type="continuous"><parent link="base"/><child link="${side}"/></joint>
  </xacro:macro>
</robot>
""")
    write("cart_description/urdf/cart.gazebo", """
        <robot><gazebo><plugin name="gazebo_ros_control" filename="libgazebo_ros_control.so">
          <robotNamespace>/cart</robotNamespace></plugin></gazebo></robot>
        """)
    write("cart_description/urdf/cart.urdf.xacro", MACRO.split("  <xacro:macro")[0] + """\
  <xacro:include filename="$(find cart_description)/urdf/wheel.urdf.xacro"/>
  <xacro:wheel side="left"/>
  <xacro:wheel side="right"/>
""" + "".join(_transmission(f"{side}_trans", f"{side}_wheel") for side in ("left", "right"))
          + "</robot>\n")
    code, _, err = run("migrate", "--write", "--to", "ros2-p2", "cart_description")
    assert code == 0, err
    lines = err.splitlines()
    assert lines[0].startswith("warning: cart_description/urdf/cart.urdf.xacro: "
                               "<ros2_control name=\"cart\"> generated with the placeholder")
    assert lines[1] == "changed cart_description/urdf/cart.urdf.xacro (2 transmission(s) to ros2-p2)"
    assert lines[2].startswith(
        "warning: cart_description/urdf/cart.gazebo: the robot's <gazebo> plugin "
        "'libgazebo_ros_control.so' (line 1) is ROS 1's gazebo_ros_control: nothing under "
        "ROS 2 loads it")
    assert lines[2].endswith("; its <robotNamespace>/cart</robotNamespace> becomes "
                             "<ros><namespace>/cart</namespace></ros>")
    assert lines[3].startswith(
        "warning: cart_description/package.xml: package 'cart_description' builds with "
        "catkin: ROS 2 (colcon, and txtool's readers) takes it for a ROS 1 package")
    assert lines[4:] == ["1 file(s) changed"]


def test_a_macro_called_once_inside_a_macro_called_twice_is_expanded_twice(run, tmp_path):
    nested = MACRO.replace(
        '  <xacro:wheel side="left"/>\n  <xacro:wheel side="right"/>\n',
        '  <xacro:macro name="axle" params="side">\n    <xacro:wheel side="${side}"/>\n'
        '  </xacro:macro>\n  <xacro:axle side="left"/>\n  <xacro:axle side="right"/>\n')
    path = tmp_path / "cart.urdf.xacro"
    path.write_text(nested)
    code, out, err = run("convert", "--no-xacro", str(path), "--to", "ros2-p2")
    assert (code, out) == (1, "")
    assert ("inside <xacro:macro name=\"wheel\"> (line 2), which this file expands 2 times (called at "
            "line 12 in <xacro:macro name=\"axle\">)") in err


def test_xacro_is_known_by_its_prefix_whatever_namespace_it_is_bound_to(run, tmp_path):
    # Robotnik's files bind xacro: to http://wiki.ros.org/xacro; xacro reads the prefix.
    path = tmp_path / "cart.urdf.xacro"
    path.write_text(MACRO.replace("http://ros.org/wiki/xacro", "http://wiki.ros.org/xacro"))
    code, out, err = run("convert", "--no-xacro", str(path), "--to", "ros2-p2")
    assert (code, out) == (1, "")
    assert "which this file expands 2 times (called at line 11, line 12)" in err
