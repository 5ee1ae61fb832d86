"""What convert and migrate write is judged by the loaders of the target: ros2_control of each
ROS 2 distribution for ros2-p1/ros2-p2, ros_control for ros1 (txtool.lint.target_check).

An error of validate's rules for those readers that the input did not have is a loss: exit 1,
nothing written, unless --allow-lossy; so is one the input had, where the reader refuses the
whole robot for it (the written file would not load).
"""

from __future__ import annotations

import pytest

import txtool

JOINTS = """\
  <link name="base"/><link name="l1"/><link name="l2"/>
  <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/>
    <limit effort="1" velocity="1" lower="-1" upper="1"/></joint>
  <joint name="j2" type="revolute"><parent link="base"/><child link="l2"/><mimic joint="j1"/>
    <limit effort="1" velocity="1" lower="-1" upper="1"/></joint>
"""


def _simple(name: str, joint: str) -> str:
    return f"""\
  <transmission name="{name}">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="{joint}">
      <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
    </joint>
    <actuator name="{name}_motor"><mechanicalReduction>20</mechanicalReduction></actuator>
  </transmission>
"""


CLEAN = f'<?xml version="1.0"?>\n<robot name="arm">\n{JOINTS}{_simple("t1", "j1")}</robot>\n'
# An offset that underflows a double: Humble's parser reads it as 0, Jazzy's from_chars
# refuses it and ros2_control silently uses 0.0 (ros_control's std::stod throws on it too).
UNDERFLOW = CLEAN.replace("</joint>\n    <actuator",
                          "<offset>1e-400</offset></joint>\n    <actuator", 1)
TX105 = ("error: line {line}: TX105 invalid-number for ros2_control (jazzy, kilted, rolling): "
         "offset of joint 'j1' of transmission 't1' is '1e-400', not a finite number: "
         "ros2_control silently uses 0.0\n")
REFUSED = "txtool: 1 item(s) would be lost; nothing written (use --allow-lossy to accept)\n"


@pytest.fixture
def here(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    return tmp_path


def _line_of(text: str, needle: str) -> int:
    return next(n for n, line in enumerate(text.splitlines(), 1) if needle in line)


def test_a_conversion_ros2_control_refuses_exits_1_and_names_the_loader(run, here):
    (here / "arm.urdf").write_text(UNDERFLOW)
    code, out, err = run("convert", "arm.urdf", "--to", "ros2-p2", "-o", "out.urdf")
    assert code == 1 and out == "" and not (here / "out.urdf").exists()
    code, out, lossy = run("convert", "arm.urdf", "--to", "ros2-p2", "--allow-lossy")
    assert code == 0
    line = _line_of(out, "<offset>1e-400</offset>")
    assert err.endswith(TX105.format(line=line) + REFUSED)
    assert TX105.format(line=line).replace("error:", "warning:") in lossy


def test_ros_distro_narrows_the_distributions_checked(run, here):
    (here / "arm.urdf").write_text(UNDERFLOW)
    # Humble's parser reads the offset as 0 (TX105 is for the other distributions)
    code, out, err = run("convert", "arm.urdf", "--to", "ros2-p2", "--ros-distro", "humble",
                         "--hardware-plugin", "arm/Hardware")
    assert code == 0 and "TX105" not in err
    code, out, err = run("convert", "arm.urdf", "--to", "ros2-p2", "--ros-distro", "jazzy")
    assert code == 1 and "TX105 invalid-number for ros2_control (jazzy):" in err
    code, out, err = run("convert", "arm.urdf", "--to", "ros2-p2", "--ros-distro", "noetic")
    assert (code, out, err) == (2, "", "txtool: --ros-distro noetic does not read --to ros2-p2: "
                                       "ros2_control does\n")


def test_an_error_the_input_had_for_the_same_reader_is_not_the_conversions(run, here):
    # t0 already spells its reduction in ROS 1 form inside <ros2_control> (TX303): converting
    # t1 leaves it as it was; the conversion says so, and is not refused for it.
    existing = CLEAN.replace("</robot>", """\
  <ros2_control name="Arm" type="system">
    <hardware><plugin>arm_driver/ArmHardware</plugin></hardware>
    <joint name="j2"><state_interface name="position"/></joint>
    <transmission name="t0">
      <plugin>transmission_interface/SimpleTransmission</plugin>
      <joint name="j2" role="joint1"><mechanicalReduction>50</mechanicalReduction></joint>
      <actuator name="m0" role="actuator1"/>
    </transmission>
  </ros2_control>
</robot>""")
    (here / "arm.urdf").write_text(existing)
    code, out, err = run("validate", "arm.urdf", "--ros-distro", "jazzy")
    assert code == 1 and "TX303" in out
    code, out, err = run("convert", "arm.urdf", "--to", "ros2-p2")
    (said,) = [line for line in err.splitlines() if "TX303" in line]
    assert code == 0 and said.startswith("warning: line ")
    assert said.endswith("ros2_control reads only <mechanical_reduction>, so the reduction "
                         "silently becomes 1.0: write <mechanical_reduction>50"
                         "</mechanical_reduction> (the input has it already)")


def test_a_robot_left_without_ros2_control_is_refused_whole(run, here):
    (here / "hand.urdf").write_text(CLEAN.replace("transmission_interface/SimpleTransmission",
                                                  "vendor/SimpleTransmission"))
    code, out, err = run("convert", "hand.urdf", "--to", "ros2-p2")
    assert code == 1 and out == ""
    assert ("error: ros2_control refuses this robot whole: it throws \"no 'ros2_control' tag "
            "found in the URDF\"") in err


def test_ros2_p1_is_held_to_ros2_control_but_for_its_role_elements(run, here):
    (here / "arm.urdf").write_text(CLEAN)
    code, out, err = run("convert", "arm.urdf", "--to", "ros2-p1", "--hardware-plugin",
                         "arm/Hardware")
    line = _line_of(out, "<role>")
    assert (code, err) == (0, "warning: ros2-p1 is not what ros2_control reads: it throws \"no "
                              "attribute 'role' in 'joint' tag\" on its <role> elements (TX303, "
                              f"first at line {line}); the rest is checked as ros2_control "
                              "reads it (--to ros2-p2 writes that)\n")
    (here / "bad.urdf").write_text(UNDERFLOW)
    code, out, err = run("convert", "bad.urdf", "--to", "ros2-p1")
    assert code == 1 and "TX105 invalid-number" in err


P1_ALREADY = CLEAN.replace("</robot>", """\
  <ros2_control name="Arm" type="system">
    <hardware><plugin>arm/Hardware</plugin></hardware>
    <joint name="j2"><command_interface name="effort"/></joint>
    <transmission name="t2">
      <plugin>transmission_interface/SimpleTransmission</plugin>
      <joint name="j2"><role>joint1</role><mechanical_reduction>5</mechanical_reduction></joint>
      <actuator name="m2"><role>actuator1</role></actuator>
    </transmission>
  </ros2_control>
</robot>""")


def test_ros2_p1_role_elements_the_input_had_are_said_as_the_inputs(run, here):
    """The input's own Proposal 1 transmission keeps its two findings, said as the input's;
    the <role> elements the conversion wrote are the form asked for."""
    (here / "arm.urdf").write_text(P1_ALREADY.replace("command_interface", "state_interface"))
    code, out, err = run("convert", "arm.urdf", "--to", "ros2-p1")
    joint, actuator, form = err.splitlines()[:3]
    kept = _line_of(out, '<joint name="j2"><role>')
    assert code == 0 and _line_of(out, '<actuator name="m2"><role>') == kept + 1
    assert joint.startswith(f"warning: line {kept}: TX303 wrong-dialect-tag for ros2_control "
                            "(humble, jazzy, kilted, rolling): joint 'j2' of transmission 't2' "
                            "gives its role as a <role> element")
    assert actuator.startswith(f"warning: line {kept + 1}: TX303 wrong-dialect-tag for "
                               "ros2_control (humble, jazzy, kilted, rolling): actuator 'm2' of "
                               "transmission 't2' gives its role as a <role> element")
    assert joint.endswith("(the input has it already)")
    assert actuator.endswith("(the input has it already)")
    written = _line_of(out, "<role>")
    assert written != kept
    assert form.startswith("warning: ros2-p1 is not what ros2_control reads: it throws \"no "
                           "attribute 'role' in 'joint' tag\" on its <role> elements (TX303, "
                           f"first at line {written});")


def test_migrate_refuses_to_write_what_the_target_refuses(run, here):
    (here / "arm.urdf").write_text(UNDERFLOW)
    code, out, err = run("migrate", "--write", "--to", "ros2-p2", "arm.urdf")
    assert code == 1 and (here / "arm.urdf").read_text() == UNDERFLOW
    assert err.endswith("refused arm.urdf: 1 item(s) would be lost; not changed (use "
                        "--allow-lossy to accept)\n1 file(s) refused (losses; see "
                        "--allow-lossy)\n")
    assert "error: arm.urdf: line " in err and "TX105 invalid-number" in err
    code, out, err = run("migrate", "--write", "--to", "ros2-p2", "--allow-lossy", "arm.urdf")
    assert code == 0 and "<ros2_control" in (here / "arm.urdf").read_text()


MACRO_IN_BLOCK = """\
<?xml version="1.0"?>
<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="trans" params="j">
    <transmission name="${j}_trans">
      <plugin>transmission_interface/SimpleTransmission</plugin>
      <joint name="${j}" role="joint1"><mechanical_reduction>50</mechanical_reduction></joint>
      <actuator name="${j}_motor" role="actuator1"/>
    </transmission>
  </xacro:macro>
  <link name="base"/><link name="a"/>
  <joint name="j1" type="revolute"><parent link="base"/><child link="a"/>
    <limit effort="1" velocity="1" lower="-1" upper="1"/></joint>
  <ros2_control name="HW" type="system">
    <hardware><plugin>mock_components/GenericSystem</plugin></hardware>
    <joint name="j1"><command_interface name="position"/></joint>
    <xacro:trans j="j1"/>
  </ros2_control>
</robot>
"""


def test_back_to_ros1_is_held_to_what_still_reads_the_file(run, here):
    """A ROS 2 transmission in a macro called inside <ros2_control>: rewritten in ROS 1 form
    where it is, ros_control never reads it and ros2_control, which still reads the block,
    throws. The expansion of the written source says so."""
    (here / "robot.urdf.xacro").write_text(MACRO_IN_BLOCK)
    code, out, err = run("migrate", "--write", "--to", "ros1", "robot.urdf.xacro")
    assert code == 1 and (here / "robot.urdf.xacro").read_text() == MACRO_IN_BLOCK
    assert ("error: robot.urdf.xacro: line 4: TX101 missing-type for ros2_control (humble, "
            "jazzy, kilted, rolling): transmission 'j1_trans' has no <plugin>: ros2_control "
            "throws \"Missing <plugin> tag of <transmission> element\"\n") in err


def test_the_library_reports_the_same_losses():
    assert txtool.convert(CLEAN, to="ros2-p2").losses == []
    (loss,) = txtool.convert(UNDERFLOW, to="ros2-p2").losses
    assert loss.startswith("line ") and "TX105 invalid-number for ros2_control " \
        "(jazzy, kilted, rolling)" in loss
    assert txtool.convert(UNDERFLOW, to="ros2-p2", ros_distro="humble").losses == []


ROBOT_INCLUDING = """\
<?xml version="1.0"?>
<robot name="gripper" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <link name="base"/><link name="l1"/><link name="l2"/>
  <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/>
    <limit effort="1" velocity="1" lower="-1" upper="1"/></joint>
  <joint name="j2" type="revolute"><parent link="base"/><child link="l2"/><mimic joint="j1"/>
    <limit effort="1" velocity="1" lower="-1" upper="1"/></joint>
  <xacro:include filename="gripper.transmission.xacro"/>
</robot>
"""


def test_a_fragment_is_judged_in_the_robot_that_includes_it(run, here):
    """Alone, the fragment has no joints to say that j2 is a mimic joint; the robot that
    includes it, expanded with what would be written, does."""
    fragment = ('<?xml version="1.0"?>\n<robot xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                f'{_simple("t1", "j1")}{_simple("t2", "j2")}</robot>\n')
    (here / "robot.urdf.xacro").write_text(ROBOT_INCLUDING)
    (here / "gripper.transmission.xacro").write_text(fragment)
    code, out, err = run("migrate", "--write", "--to", "ros2-p2", ".")
    assert code == 1 and (here / "gripper.transmission.xacro").read_text() == fragment
    assert ("error: ./gripper.transmission.xacro: as ./robot.urdf.xacro includes it (lines of "
            "its expansion): line ") in err
    assert "TX206 mimic-command-interface for ros2_control (jazzy, kilted, rolling): joint " \
        "'j2' mimics 'j1'" in err
    assert err.endswith("1 file(s) refused (losses; see --allow-lossy)\n")
    code, out, err = run("migrate", "--write", "--to", "ros2-p2", "--ros-distro", "humble", ".")
    assert code == 0 and "<ros2_control" in (here / "gripper.transmission.xacro").read_text()


# A joint whose parent link the robot lacks (PAL's REEM-C head, expanded, has one): urdfdom
# refuses to build the model and ros2_control's parser throws "Failed to parse URDF file".
ORPHAN = CLEAN.replace("</robot>", """\
  <link name="stereo_frame"/>
  <joint name="stereo_frame_joint" type="fixed"><parent link="head_2_link"/>
    <child link="stereo_frame"/></joint>
</robot>""")
URDFDOM = ("TX210 urdf-refused for ros2_control (humble, jazzy, kilted, rolling): urdfdom "
           "refuses the robot (\"Failed to build tree: parent link [head_2_link] of joint "
           "[stereo_frame_joint] not found\")")
LOADERS = ("so do the readers of the robot built on it (ros2_control throws \"Failed to parse "
           "URDF file\")")
ALREADY = "(the input has it already: the target refuses the written file whole all the same)"


def test_a_robot_the_target_refuses_whole_is_refused_though_the_input_was_too(run, here):
    """The input's own error, carried over, is no loss of the conversion; but the file written
    would not load at all, so the conversion fails all the same and says why."""
    (here / "head.urdf").write_text(ORPHAN)
    code, out, err = run("validate", "head.urdf")
    assert code == 1 and "TX210" in out
    code, out, err = run("convert", "head.urdf", "--to", "ros2-p2", "-o", "out.urdf")
    assert code == 1 and out == "" and not (here / "out.urdf").exists()
    assert err.endswith(REFUSED)
    (refused,) = [each for each in err.splitlines() if "TX210" in each]
    code, out, err = run("convert", "head.urdf", "--to", "ros2-p2", "--allow-lossy",
                         "-o", "out.urdf")
    written = (here / "out.urdf").read_text()
    assert code == 0 and "<ros2_control" in written
    (warned,) = [each for each in err.splitlines() if "TX210" in each]
    line = _line_of(written, "head_2_link")
    assert refused == f"error: line {line}: {URDFDOM}: {LOADERS} {ALREADY}"
    assert warned == refused.replace("error:", "warning:", 1)


def test_migrate_does_not_write_a_robot_the_target_refuses_whole(run, here):
    (here / "head.urdf").write_text(ORPHAN)
    code, out, err = run("migrate", "--write", "--to", "ros2-p2", "head.urdf")
    assert code == 1 and (here / "head.urdf").read_text() == ORPHAN
    assert URDFDOM in err and ALREADY in err


def test_a_fixed_joint_an_existing_block_declares_stays_a_loss(run, here):
    """The parser throws on the fixed joint of the block the input had: whatever the
    conversion adds beside it, no hardware of the written robot loads (TX201)."""
    existing = CLEAN.replace("</robot>", """\
  <link name="tool"/>
  <joint name="jf" type="fixed"><parent link="base"/><child link="tool"/></joint>
  <ros2_control name="Tool" type="system">
    <hardware><plugin>tool_driver/Tool</plugin></hardware>
    <joint name="jf"><state_interface name="position"/></joint>
    <transmission name="t0">
      <plugin>transmission_interface/SimpleTransmission</plugin>
      <joint name="jf" role="joint1"><mechanical_reduction>50</mechanical_reduction></joint>
      <actuator name="m0" role="actuator1"/>
    </transmission>
  </ros2_control>
</robot>""")
    (here / "arm.urdf").write_text(existing)
    code, out, err = run("convert", "arm.urdf", "--to", "ros2-p2")
    assert code == 1 and out == "" and err.endswith(REFUSED)
    (said,) = [each for each in err.splitlines() if "TX201" in each]
    assert said.startswith("error: line ") and said.endswith(
        "ros2_control throws \"Fixed joints do not make sense in ros2_control\" " + ALREADY)
