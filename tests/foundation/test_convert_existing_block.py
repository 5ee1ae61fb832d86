"""ROS 1 -> ROS 2 where the robot already declares its joints in a <ros2_control> block: the
declaration is kept and the conversion is judged on what the transmission itself defines."""

from __future__ import annotations

import json

from lxml import etree

from tests.corpus import corpus_file

ARM = """<robot name="arm">
  <ros2_control name="ArmSystem" type="system">
    <hardware><plugin>arm_driver/ArmHardware</plugin></hardware>
    <joint name="shoulder">
      <command_interface name="position"/>
      <command_interface name="velocity"/>
      <state_interface name="position"/>
    </joint>
  </ros2_control>
  <transmission name="shoulder_trans">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="shoulder">
      <hardwareInterface>hardware_interface/{interface}JointInterface</hardwareInterface>
    </joint>
    <actuator name="shoulder_motor"><mechanicalReduction>100</mechanicalReduction></actuator>
  </transmission>
</robot>
"""


def test_interfaces_the_block_adds_are_kept_and_said(run, tmp_path):
    path = tmp_path / "arm.urdf"
    path.write_text(ARM.format(interface="Position"))
    code, out, err = run("convert", str(path), "--to", "ros2-p2")
    assert (code, err) == (0, "note: joint 'shoulder': its <ros2_control> declaration also "
                              "commands {velocity}, which transmission 'shoulder_trans' does not "
                              "name; kept\n")
    root = etree.fromstring(out.encode())
    (block,) = root.iter("ros2_control")
    assert [c.get("name") for c in block.iter("command_interface")] == ["position", "velocity"]
    assert [t.get("name") for t in block.iter("transmission")] == ["shoulder_trans"]


def test_an_interface_the_block_does_not_command_is_a_loss(run, tmp_path):
    path = tmp_path / "arm.urdf"
    path.write_text(ARM.format(interface="Effort"))
    code, out, err = run("convert", str(path), "--to", "ros2-p2")
    assert (code, out) == (1, "")
    assert err == (
        "error: joint 'shoulder': transmission 'shoulder_trans' names {effort} but the "
        "<ros2_control> that declares the joint commands {position, velocity}; add the missing "
        "command interface there (txtool does not change a hardware declaration)\n"
        "txtool: 1 item(s) would be lost; nothing written (use --allow-lossy to accept)\n")


def test_the_real_arm_that_carries_both_forms_converts_without_loss(run):
    # ROBOTIS OMY-F3M: ROS 1 transmissions beside the <ros2_control> blocks of its hardware.
    # (Humble's parser: from Jazzy on, the generated block's command interfaces on its mimic
    # gripper joints are refused, TX206, and the conversion with them.)
    path = corpus_file("open_manipulator__omy_f3m.urdf")
    code, out, err = run("convert", str(path), "--to", "ros2-p2", "--ros-distro", "humble")
    assert code == 0, err
    # The one warning: the block generated for the three mimic joints no block declares
    # names the placeholder plugin.
    warnings = [line for line in err.splitlines() if not line.startswith("note: ")]
    assert warnings == ['warning: <ros2_control name="omy_f3m"> generated with the placeholder '
                        "hardware plugin 'mock_components/GenericSystem' (ros2_control's mock "
                        "hardware: it copies commands to states and drives no robot); replace "
                        "it with the robot's hardware plugin, or convert with --hardware-plugin "
                        "PLUGIN"]
    original = etree.parse(str(path)).getroot()
    converted = etree.fromstring(out.encode())
    assert converted.findall("transmission") == []
    for name in ("OMYF3MSystem", "OMYF3MEndUnitSystem"):
        before = original.find(f"ros2_control[@name='{name}']")
        after = converted.find(f"ros2_control[@name='{name}']")
        declared = [etree.tostring(j) for j in before.findall("joint")]
        assert [etree.tostring(j) for j in after.findall("joint")] == declared
        for t in after.findall("transmission"):
            assert before.find(f"joint[@name='{t.find('joint').get('name')}']") is not None


def test_tiago_has_nothing_to_convert_and_loses_nothing(run):
    # TIAGo's 7-DoF arm is in ros2_control already; its hand's Hey5Reducer transmissions are a
    # custom ROS 1 type, left as written: a warning each, not a loss.
    path = corpus_file("tiago_robot__tiago_pal-hey5.urdf")
    code, out, err = run("convert", str(path), "--to", "ros2-p2")
    assert code == 0
    assert out.encode() == path.read_bytes()
    *lines, last = err.splitlines()
    assert len(lines) == 33 and all(
        line.startswith("warning: transmission 'hand_") and "'hey5_transmissions/Hey5Reducer'"
        " is not converted" in line for line in lines)
    assert last == (f"txtool: {path}: 0 transmissions converted (47 found, 14 already ros2-p2; "
                    "the document is unchanged)")


def test_following_the_refusals_advice_makes_the_four_bar_convert(run, fixtures, tmp_path):
    code, _, err = run("convert", str(fixtures / "four_bar.ros1.urdf"), "--to", "ros2-p2")
    assert code == 1 and "list them in role order first" in err
    # 1. List the joints in role order (ros_control then binds the values where the roles say).
    text = (fixtures / "four_bar.ros1.urdf").read_text()
    bar = text[text.index('    <joint name="bar_joint">'):text.index('    <joint name="foo_joint">')]
    foo = text[text.index('    <joint name="foo_joint">'):text.index('    <actuator')]
    in_order = text.replace(bar + foo, foo + bar)
    reordered = tmp_path / "four_bar.urdf"
    reordered.write_text(in_order)
    code, _, err = run("validate", str(reordered), "--select", "TX404")
    assert code == 0
    # 2. The names now sort against the roles: ros2_control would bind them the other way.
    code, _, err = run("convert", str(reordered), "--to", "ros2-p2")
    assert code == 1
    assert "rename the members so that the joint1 name sorts before the joint2 name" in err
    # 3. Renamed as the message says, it converts.
    reordered.write_text(in_order.replace("bar_joint", "z_bar_joint")
                         .replace("bar_actuator", "z_bar_actuator"))
    code, out, err = run("convert", str(reordered), "--to", "ros2-p2",
                         "--hardware-plugin", "four_bar/Hardware")
    assert (code, err) == (0, "")
    joints = etree.fromstring(out.encode()).find("ros2_control/transmission").findall("joint")
    assert [(j.get("name"), j.get("role")) for j in joints] == [
        ("foo_joint", "joint1"), ("z_bar_joint", "joint2")]


def test_roundtrip_judges_what_the_transmission_defines(run):
    # diffbot's legacy transmissions name no interface; its <ros2_control> declares velocity.
    # YuMi's grippers name a misspelt interface: they come back state-only, as they loaded.
    # ros_control's invalid simple fixture holds four transmissions of one name.
    for name in ("ros2_control_test_assets__diffbot_urdf.urdf", "yumi__yumi.urdf",
                 "ros_control__simple_transmission_loader_invalid.urdf"):
        code, out, _ = run("roundtrip", str(corpus_file(name)))
        assert code == 0 and out.rstrip().endswith("all cycles keep every field"), name
    # A real loss is still one: the four-bar's names sort against its roles.
    code, out, _ = run("roundtrip", str(corpus_file(
        "ros_control__four_bar_linkage_transmission_loader_full.urdf")))
    assert code == 1 and out.rstrip().endswith("some cycles lose data or change behaviour")


def test_roundtrip_names_the_members_listed_against_their_roles(run):
    code, out, _ = run("roundtrip", "--format", "json", str(corpus_file(
        "ros_control__differential_transmission_loader_full.urdf")))
    assert code == 1
    rows = json.loads(out)["cycles"]
    assert rows and all(row["equivalent"].startswith("no: ") for row in rows)
    assert all("the original lists its members against their roles (TX404): ros_control binds "
               "their data in XML order, ros2_control by name" in row["details"] for row in rows)
