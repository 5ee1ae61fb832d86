"""Back to ROS 1, a ``<ros2_control>`` block is replaced by its transmissions only where it is
exactly what txtool generates for them, its layout aside: a block someone changed by hand (an
attribute, a text, a comment, a transmission put in a xacro conditional) is kept, and its
transmissions move out to stand before it, so that nothing written there is lost. A comment
inside a transmission is carried with it, as a conversion carries it."""

from __future__ import annotations

import pytest
from lxml import etree

XACRO = "http://www.ros.org/wiki/xacro"
REPLACED = '<ros2_control name="arm"> is what txtool generates for its transmissions; replaced'


def _transmission(name: str) -> str:
    return f"""\
  <transmission name="{name}_trans">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="{name}">
      <hardwareInterface>hardware_interface/PositionJointInterface</hardwareInterface>
    </joint>
    <actuator name="{name}_motor">
      <mechanicalReduction>50</mechanicalReduction>
    </actuator>
  </transmission>
"""


ROBOT = f"""\
<?xml version="1.0"?>
<robot name="arm" xmlns:xacro="{XACRO}">
  <link name="base"/>
  <link name="upper"/>
  <link name="fore"/>
  <joint name="shoulder" type="revolute">
    <parent link="base"/><child link="upper"/>
    <limit lower="-1" upper="1" effort="10" velocity="1"/>
  </joint>
  <joint name="elbow" type="revolute">
    <parent link="upper"/><child link="fore"/>
    <limit lower="-1" upper="1" effort="10" velocity="1"/>
  </joint>
{_transmission("shoulder")}{_transmission("elbow")}</robot>
"""

# What a hand changes in the generated block: (what it wrote, what it writes instead).
CHANGES = {
    "an attribute": ('<joint name="elbow">\n      <command_interface',
                     '<joint name="elbow" note="tuned">\n      <command_interface'),
    "a text": ("<hardware>\n", "<hardware>tuned\n"),
    "a comment": ('    <joint name="shoulder">\n      <command_interface',
                  '    <!-- tuned by hand -->\n    <joint name="shoulder">\n'
                  "      <command_interface"),
    "a conditional": ('    <transmission name="elbow_trans">',
                      '    <xacro:if value="1">\n    <transmission name="elbow_trans">'),
}


@pytest.fixture
def generated(run, tmp_path) -> str:
    """The robot converted to ros2-p2: one block generated for both transmissions."""
    path = tmp_path / "arm.urdf"
    path.write_text(ROBOT)
    code, out, _ = run("convert", "--no-xacro", str(path), "--to", "ros2-p2")
    assert code == 0 and out.count("<ros2_control") == 1
    return out


def test_the_block_as_generated_is_replaced_by_its_transmissions(run, tmp_path, generated):
    path = tmp_path / "arm.ros2.urdf"
    path.write_text(generated)
    code, out, err = run("convert", "--no-xacro", str(path), "--to", "ros1")
    assert (code, out) == (0, ROBOT) and REPLACED in err


def test_a_comment_inside_a_transmission_goes_with_it(run, tmp_path, generated):
    """Not something txtool generates, but carried: the block is still replaced."""
    path = tmp_path / "arm.ros2.urdf"
    path.write_text(generated.replace('      <actuator name="elbow_motor"',
                                      '      <!-- geared -->\n      <actuator name="elbow_motor"'))
    code, out, err = run("convert", "--no-xacro", str(path), "--to", "ros1")
    assert code == 0 and REPLACED in err and "<ros2_control" not in out
    (comment,) = etree.fromstring(out.encode()).find("transmission[@name='elbow_trans']").iter(
        etree.Comment)
    assert comment.text == " geared "


@pytest.mark.parametrize("change", CHANGES, ids=list(CHANGES))
def test_a_block_changed_by_hand_is_kept(run, tmp_path, generated, change):
    was, now = CHANGES[change]
    assert generated.count(was) == 1
    text = generated.replace(was, now)
    if change == "a conditional":
        text = text.replace("    </transmission>\n  </ros2_control>",
                            "    </transmission>\n    </xacro:if>\n  </ros2_control>")
    path = tmp_path / "arm.ros2.urdf.xacro"
    path.write_text(text)
    code, out, err = run("convert", "--no-xacro", str(path), "--to", "ros1")
    assert code == 0 and REPLACED not in err
    root = etree.fromstring(out.encode())
    (block,) = root.findall("ros2_control")
    assert block.get("name") == "arm" and not block.findall(".//transmission")
    # The transmissions stand before the block, in ROS 1 form (the one in a conditional in a
    # copy of it), and what the hand wrote is still there.
    moved = [t for t in root.iter("transmission")]
    assert [t.get("name") for t in moved] == ["shoulder_trans", "elbow_trans"]
    assert all(t.findtext("type") == "transmission_interface/SimpleTransmission" for t in moved)
    if change == "an attribute":
        assert block.find("joint[@name='elbow']").get("note") == "tuned"
    elif change == "a text":
        assert block.find("hardware").text.strip() == "tuned"
    elif change == "a comment":
        assert "<!-- tuned by hand -->" in out
    else:
        assert moved[1].getparent().tag == f"{{{XACRO}}}if"
