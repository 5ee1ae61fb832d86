"""Conversions that respect what the readers require: every ``<ros2_control>`` has a name of
its own, a transmission stays in the xacro conditional or macro it was written in, a block
declaring more than the transmissions goes there and back without a false loss, and a
placeholder hardware plugin is said to be one."""

from __future__ import annotations

import pytest
from lxml import etree

XACRO = "http://www.ros.org/wiki/xacro"

TRANSMISSION = """\
  <transmission name="{name}">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="{joint}">
      <hardwareInterface>hardware_interface/{interface}JointInterface</hardwareInterface>
    </joint>
    <actuator name="{joint}_motor">
      <mechanicalReduction>50</mechanicalReduction>
    </actuator>
  </transmission>
"""


def _transmission(name: str, joint: str, interface: str = "Position", depth: int = 0) -> str:
    text = TRANSMISSION.format(name=name, joint=joint, interface=interface)
    return "".join("  " * depth + line for line in text.splitlines(keepends=True))


def _blocks(text: str) -> list[str]:
    root = etree.fromstring(text.encode())
    return [block.get("name") for block in root.iter("ros2_control")]


# 1. One name per <ros2_control> ------------------------------------------------------------
# ros2_control's resource manager refuses a robot description with two hardware components of
# one name (ros-controls/ros2_control hardware_interface/src/resource_manager.cpp,
# ResourceManager::load_and_initialize_components: "Hardware name %s is duplicated. Please
# provide a unique 'name' in the URDF."); component_parser.cpp, parse_resource_from_xml, reads
# that name with get_attribute_value, which strips the whitespace around it.

SENSOR_NAMED_LIKE_THE_ROBOT = f"""\
<?xml version="1.0"?>
<robot name="arm">
  <link name="base"/>
  <ros2_control name="{{block}}" type="sensor">
    <hardware>
      <plugin>arm_driver/ForceTorque</plugin>
    </hardware>
    <sensor name="ft"/>
  </ros2_control>
{_transmission("elbow_trans", "elbow")}</robot>
"""


@pytest.mark.parametrize("block", ["arm", " arm "])
def test_a_generated_block_takes_a_name_no_other_block_has(run, tmp_path, block):
    path = tmp_path / "arm.urdf"
    path.write_text(SENSOR_NAMED_LIKE_THE_ROBOT.format(block=block))
    code, out, err = run("convert", str(path), "--to", "ros2-p2")
    assert (code, err) == (0, "note: the <ros2_control> generated for the document is named "
                              "'arm_2': another <ros2_control> is named 'arm' (ros2_control "
                              "refuses two hardware components of one name)\n"
                              + PLACEHOLDER.replace('name="arm"', 'name="arm_2"'))
    assert _blocks(out) == [block, "arm_2"]
    converted = tmp_path / "arm.ros2.urdf"
    converted.write_text(out)
    code, back, err = run("convert", str(converted), "--to", "ros1")
    assert (code, back) == (0, path.read_text())
    assert err == ('note: <ros2_control name="arm_2"> is what txtool generates for its '
                   "transmissions; replaced by them\n")


SPLIT = f"""\
<?xml version="1.0"?>
<robot name="arm" xmlns:xacro="{XACRO}">
  <xacro:arg name="sim" default="false"/>
  <xacro:if value="$(arg sim)">
{_transmission("elbow_trans", "elbow", "Effort", 1)}  </xacro:if>
  <xacro:unless value="$(arg sim)">
{_transmission("elbow_trans", "elbow", "Position", 1)}  </xacro:unless>
{_transmission("arm", "wrist")}</robot>
"""


def test_blocks_made_in_several_places_take_names_of_their_own(run, tmp_path):
    # Each conditional's transmission gets a block of its own, in place; the third, named like
    # the robot, goes into the block generated for the document.
    path = tmp_path / "arm.urdf.xacro"
    path.write_text(SPLIT)
    code, out, err = run("convert", "--no-xacro", str(path), "--to", "ros2-p2")
    assert code == 0
    assert _blocks(out) == ["elbow_trans", "elbow_trans_2", "arm"]
    assert "is named 'elbow_trans_2': another <ros2_control> is named 'elbow_trans'" in err
    converted = tmp_path / "arm.ros2.urdf.xacro"
    converted.write_text(out)
    code, back, _ = run("convert", "--no-xacro", str(converted), "--to", "ros1")
    assert (code, back) == (0, SPLIT)


# 2. A transmission stays in its conditional or macro ---------------------------------------


def test_a_transmission_in_a_conditional_or_macro_is_converted_there(run, tmp_path):
    path = tmp_path / "arm.urdf.xacro"
    path.write_text(f"""\
<robot name="arm" xmlns:xacro="{XACRO}">
  <xacro:macro name="wrist" params="prefix">
{_transmission("${prefix}wrist_trans", "${prefix}wrist", depth=1)}  </xacro:macro>
  <xacro:wrist prefix="left_"/>
  <xacro:unless value="$(arg sim)">
{_transmission("elbow_trans", "elbow", depth=1)}  </xacro:unless>
</robot>
""")
    code, out, _ = run("convert", "--no-xacro", str(path), "--to", "ros2-p2")
    assert code == 0
    root = etree.fromstring(out.encode())
    scopes = {t.get("name"): (t.getparent().getparent().tag, t.getparent().getparent().attrib)
              for t in root.iter("transmission")}
    assert scopes == {"${prefix}wrist_trans": (f"{{{XACRO}}}macro", {"name": "wrist",
                                                                      "params": "prefix"}),
                      "elbow_trans": (f"{{{XACRO}}}unless", {"value": "$(arg sim)"})}
    assert [e.tag for e in root] == [f"{{{XACRO}}}{tag}" for tag in ("macro", "wrist", "unless")]


CONDITIONAL_BLOCK = f"""\
<robot name="arm" xmlns:xacro="{XACRO}">
  <xacro:arg name="sim" default="false"/>
  <xacro:if value="$(arg sim)">
    <ros2_control name="GazeboSystem" type="system">
      <hardware>
        <plugin>gazebo_ros2_control/GazeboSystem</plugin>
      </hardware>
      <joint name="elbow">
        <command_interface name="position"/>
        <state_interface name="position"/>
      </joint>
    </ros2_control>
  </xacro:if>
{_transmission("elbow_trans", "elbow")}</robot>
"""


def test_a_transmission_is_not_moved_into_a_block_that_stands_in_a_conditional(run, tmp_path):
    # Moved in, the robot would have no transmission when sim is false; in a block of its own,
    # the joint would be declared twice when sim is true.
    path = tmp_path / "arm.urdf.xacro"
    path.write_text(CONDITIONAL_BLOCK)
    code, out, err = run("convert", "--no-xacro", str(path), "--to", "ros2-p2")
    assert (code, out) == (1, "")
    assert err == (
        "error: transmission 'elbow_trans': <ros2_control name=\"GazeboSystem\"> declares its "
        "joints but stands inside <xacro:if value=\"$(arg sim)\">: the transmission is not moved "
        "in there (the robot would lose it for other arguments), and the block generated for it "
        "declares them again; place it by hand\n"
        "txtool: 1 item(s) would be lost; nothing written (use --allow-lossy to accept)\n")


CONDITIONAL_IN_BLOCK = f"""\
<robot name="arm" xmlns:xacro="{XACRO}">
  <xacro:arg name="sim" default="false"/>
  <ros2_control name="ArmSystem" type="system">
    <hardware>
      <plugin>arm_driver/ArmHardware</plugin>
    </hardware>
    <joint name="elbow">
      <command_interface name="position"/>
      <state_interface name="position"/>
    </joint>
    <xacro:{{condition}} value="$(arg sim)">
      <transmission name="elbow_trans">
        <plugin>transmission_interface/SimpleTransmission</plugin>
        <actuator name="elbow_motor" role="actuator1"/>
        <joint name="elbow" role="joint1">
          <mechanical_reduction>50</mechanical_reduction>
        </joint>
      </transmission>
    </xacro:{{condition}}>
  </ros2_control>
</robot>
"""


@pytest.mark.parametrize("condition", ["if", "unless"])
def test_back_to_ros1_a_transmission_keeps_its_conditional(run, tmp_path, condition):
    path = tmp_path / "arm.urdf.xacro"
    path.write_text(CONDITIONAL_IN_BLOCK.format(condition=condition))
    code, out, err = run("convert", "--no-xacro", str(path), "--to", "ros1")
    assert (code, err) == (0, "")
    assert out == f"""\
<robot name="arm" xmlns:xacro="{XACRO}">
  <xacro:arg name="sim" default="false"/>
  <xacro:{condition} value="$(arg sim)">
    <transmission name="elbow_trans">
      <type>transmission_interface/SimpleTransmission</type>
      <joint name="elbow">
        <hardwareInterface>hardware_interface/PositionJointInterface</hardwareInterface>
      </joint>
      <actuator name="elbow_motor">
        <mechanicalReduction>50</mechanicalReduction>
      </actuator>
    </transmission>
  </xacro:{condition}>
  <ros2_control name="ArmSystem" type="system">
    <hardware>
      <plugin>arm_driver/ArmHardware</plugin>
    </hardware>
    <joint name="elbow">
      <command_interface name="position"/>
      <state_interface name="position"/>
    </joint>
  </ros2_control>
</robot>
"""


def test_a_transmission_in_a_macro_inside_a_block_is_refused_not_hoisted(run, tmp_path):
    path = tmp_path / "arm.urdf.xacro"
    text = CONDITIONAL_IN_BLOCK.format(condition="macro").replace('value="$(arg sim)"',
                                                                  'name="elbow" params=""')
    path.write_text(text)
    code, out, err = run("convert", "--no-xacro", str(path), "--to", "ros1")
    assert (code, out) == (1, "")
    assert err.splitlines()[0] == (
        "error: transmission 'elbow_trans': stands inside <xacro:macro name=\"elbow\"> within "
        "<ros2_control name=\"ArmSystem\">: a ROS 1 transmission must stand outside the block, "
        "and it cannot leave that element; left as written")


# 3. A block that declares more than the transmissions name ---------------------------------

BLOCK = """\
  <ros2_control name="ArmSystem" type="system">
    <hardware>
      <plugin>arm_driver/ArmHardware</plugin>
    </hardware>
    <joint name="shoulder">
      <command_interface name="position"/>
      <command_interface name="velocity"/>
      <state_interface name="position"/>
      <state_interface name="velocity"/>
      <state_interface name="effort"/>
    </joint>
    <joint name="elbow">
      <command_interface name="effort"/>
      <state_interface name="position"/>
    </joint>
  </ros2_control>
"""
TRANSMISSIONS = _transmission("shoulder_trans", "shoulder") + _transmission(
    "elbow_trans", "elbow", "Effort")


@pytest.mark.parametrize("order", ["block first", "transmissions first"])
@pytest.mark.parametrize("target", ["ros2-p1", "ros2-p2"])
def test_a_ros1_file_with_a_richer_block_goes_there_and_back(run, tmp_path, order, target):
    body = BLOCK + TRANSMISSIONS if order == "block first" else TRANSMISSIONS + BLOCK
    original = f'<?xml version="1.0"?>\n<robot name="arm">\n  <link name="base"/>\n{body}</robot>\n'
    path = tmp_path / "arm.urdf"
    path.write_text(original)
    kept = ("note: joint 'shoulder': its <ros2_control> declaration also commands {velocity}, "
            "which transmission 'shoulder_trans' does not name; kept\n")
    for reversible in ([], ["--reversible"]):
        code, out, err = run("convert", str(path), "--to", target, *reversible)
        # ros2_control never adopted Proposal 1's <role> elements: said once (target_check)
        p1 = err.startswith("warning: ros2-p1 is not what ros2_control reads: it throws")
        assert (code, err.split("\n", 1)[1] if p1 else err) == (0, kept)
        assert p1 == (target == "ros2-p1")
        converted = tmp_path / "arm.ros2.urdf"
        converted.write_text(out)
        code, back, err = run("convert", str(converted), "--to", "ros1")
        assert code == 0 and "error" not in err and "warning" not in err
    assert back == original  # --reversible: byte for byte
    assert err == ("note: 2 transmissions: the original bytes carried by --reversible are put "
                   "back\n"
                   "note: joint 'shoulder': <ros2_control name=\"ArmSystem\"> also commands "
                   "{velocity}, which transmission 'shoulder_trans' does not name in ros1; the "
                   "block stays\n")


# 4. A placeholder hardware plugin is said to be one ----------------------------------------

LOSSY = f"""\
<robot name="arm">
{_transmission("elbow_trans", "elbow").replace("</joint>", "</joint><offset>1</offset>")}\
</robot>
"""
PLACEHOLDER = (
    "warning: <ros2_control name=\"arm\"> generated with the placeholder hardware plugin "
    "'mock_components/GenericSystem' (ros2_control's mock hardware: it copies commands to "
    "states and drives no robot); replace it with the robot's hardware plugin, or convert "
    "with --hardware-plugin PLUGIN\n")


def test_allow_lossy_says_which_placeholder_plugin_it_wrote(run, tmp_path):
    path = tmp_path / "arm.urdf"
    path.write_text(LOSSY)
    code, out, err = run("convert", str(path), "--to", "ros2-p2", "--allow-lossy")
    assert code == 0 and "<plugin>mock_components/GenericSystem</plugin>" in out
    assert err.endswith(PLACEHOLDER) and err.count("\n") == 2  # after the loss itself
    code, out, err = run("convert", str(path), "--to", "ros2-p2", "--allow-lossy",
                         "--hardware-plugin", "arm_driver/ArmHardware")
    assert code == 0 and "<plugin>arm_driver/ArmHardware</plugin>" in out
    assert "placeholder" not in err


def test_migrate_allow_lossy_says_so_too(run, tmp_path):
    path = tmp_path / "arm.urdf"
    path.write_text(LOSSY)
    code, _, err = run("migrate", "--write", "--to", "ros2-p2", "--allow-lossy", str(path))
    assert code == 0
    assert f"warning: {path}: {PLACEHOLDER[len('warning: '):]}" in err


def test_every_transmission_of_a_repeated_shape_is_checked_for_its_scope(run, tmp_path):
    # The second is the first under other names: each is checked on its own.
    path = tmp_path / "arm.urdf.xacro"
    path.write_text(CONDITIONAL_BLOCK.replace(
        "    </ros2_control>",
        '      <joint name="wrist">\n        <command_interface name="position"/>\n'
        "      </joint>\n    </ros2_control>").replace(
        "</robot>", _transmission("wrist_trans", "wrist") + "</robot>"))
    code, out, err = run("convert", "--no-xacro", str(path), "--to", "ros2-p2")
    assert (code, out) == (1, "")
    assert [line.split(":")[0] for line in err.splitlines()] == [
        "error", "error", "txtool"]
    assert "transmission 'wrist_trans': <ros2_control name=\"GazeboSystem\">" in err
