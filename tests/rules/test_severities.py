"""Every rule reports the severity it is registered with, and the registry says what we promise.

Severity is a promise (README, "Severities"): ``error`` where the loader refuses the file or
silently changes what it means, ``warning`` where it loads but is risky, ``info`` for notes.
The table pins each rule's severity; each snippet makes the rule fire.
"""

from __future__ import annotations

import pytest

from tests.rules.helpers import problems
from txtool.rules import all_rules

SIMPLE = "transmission_interface/SimpleTransmission"
EFFORT = "<hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>"
ROBOT = """<robot name="r">
  <link name="a"/><link name="b"/><link name="c"/>
  <joint name="j" type="revolute"><parent link="a"/><child link="b"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="k" type="revolute"><parent link="b"/><child link="c"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
{body}
</robot>
"""


def ros1(joint: str = EFFORT, actuator: str = "<mechanicalReduction>50</mechanicalReduction>",
         type_: str = SIMPLE, name: str = "t", joint_name: str = "j") -> str:
    return (f'<transmission name="{name}"><type>{type_}</type>'
            f'<joint name="{joint_name}">{joint}</joint><actuator name="m_{name}">{actuator}'
            "</actuator></transmission>")


def coupled(type_: str, joint2: str = EFFORT, reduction2: str = "50") -> str:
    return (f'<transmission name="c"><type>transmission_interface/{type_}</type>'
            f"<joint name=\"j\"><role>joint1</role>{EFFORT}</joint>"
            f"<joint name=\"k\"><role>joint2</role>{joint2}</joint>"
            "<actuator name=\"m1\"><role>actuator1</role><mechanicalReduction>50"
            "</mechanicalReduction></actuator>"
            f"<actuator name=\"m2\"><role>actuator2</role><mechanicalReduction>{reduction2}"
            "</mechanicalReduction></actuator></transmission>")


def ros2(transmission: str, interfaces: str = '<command_interface name="position"/>') -> str:
    return (f'<ros2_control name="hw" type="system"><joint name="j">{interfaces}</joint>'
            f'<joint name="k">{interfaces}</joint>{transmission}</ros2_control>')


def ros2_simple(member: str = 'role="joint1"', joint_inner: str = "") -> str:
    return (f'<transmission name="t"><plugin>{SIMPLE}</plugin>'
            f'<joint name="j" {member}>{joint_inner}</joint></transmission>')


# A ros2_control joint 'j' commanded and read by position only.
POSITION_ONLY = ('<ros2_control name="s" type="system"><hardware><plugin>mock_components/'
                 'GenericSystem</plugin></hardware><joint name="j"><command_interface '
                 'name="position"/><state_interface name="position"/></joint></ros2_control>')


def robot(body: str) -> str:
    return ROBOT.format(body=body)


# An undefined property in a file nobody includes: a fault of the file (a missing argument
# is an info, see tests/rules/test_tx002_xacro_failed.py).
XACRO = ('<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
         '<link name="${prefix}base"/>' + ros1() + "</robot>")
DIFF_ROS2 = ('<transmission name="d"><plugin>transmission_interface/DifferentialTransmission'
             '</plugin><actuator name="m1" role="actuator1"/><actuator name="m2" '
             'role="actuator2"/><joint name="k" role="joint1"/><joint name="j" role="joint2"/>'
             "</transmission>")

GAZEBO2 = '<gazebo><plugin filename="libgazebo_ros2_control.so" name="gazebo_ros2_control"/></gazebo>'
GAZEBO1 = '<gazebo><plugin filename="libgazebo_ros_control.so" name="gazebo_ros_control"/></gazebo>'
GZ = '<gazebo><plugin filename="gz_ros2_control-system" name="gz_ros2_control"/></gazebo>'

# code: (severity, document, file name)
TABLE: dict[str, tuple[str, str, str]] = {
    "TX001": ("error", "<robot>", "r.urdf"),
    "TX002": ("error", XACRO, "r.urdf.xacro"),
    "TX003": ("info", robot("<!-- txtool: disable-next-line TX106 -->\n" + ros1()), "r.urdf"),
    "TX004": ("warning", " <?xml version='1.0'?>" + robot(ros1()), "r.urdf"),
    "TX005": ("warning", robot("<!-- txtool: disable-nextline TX106 -->\n" + ros1()), "r.urdf"),
    # reported only for a file named on the command line: see the test below
    "TX006": ("info", robot(""), "named.urdf"),
    "TX007": ("error", robot(ros1() + GAZEBO2), "r.urdf"),
    "TX100": ("error", robot(ros1(name="")), "r.urdf"),
    "TX101": ("error", robot(ros1().replace(f"<type>{SIMPLE}</type>", "")), "r.urdf"),
    "TX102": ("warning", robot(ros1(type_="my_hw/Reducer")), "r.urdf"),
    "TX103": ("error", robot(ros1().replace("</joint>", f'</joint><joint name="k">{EFFORT}'
                                           "</joint>", 1)), "r.urdf"),
    "TX104": ("error", robot(ros1(actuator="")), "r.urdf"),
    "TX105": ("error", robot(ros1(actuator="<mechanicalReduction>fifty</mechanicalReduction>")),
              "r.urdf"),
    "TX106": ("error", robot(ros1(actuator="<mechanicalReduction>0</mechanicalReduction>")),
              "r.urdf"),
    "TX107": ("error", robot(coupled("DifferentialTransmission").replace("<role>joint2</role>",
                                                                         "")), "r.urdf"),
    "TX108": ("warning", robot(ros1() + ros1(joint_name="k")), "r.urdf"),
    "TX109": ("warning", robot(ros1() + ros1(name="u")), "r.urdf"),
    "TX110": ("error", robot(ros1(joint="")), "r.urdf"),
    "TX111": ("warning", robot(ros1(actuator="<mechanicalReduction>50abc</mechanicalReduction>")),
              "r.urdf"),
    "TX112": ("error", robot(ros2(ros2_simple('role="joint1" read_only="yes"'))), "r.urdf"),
    # a near-miss of a standard name (another name may be a vendor's plugin: a warning)
    "TX113": ("error", robot(ros1(type_="transmission_interface/SimpleTransmision")), "r.urdf"),
    "TX200": ("error", robot(ros1(joint_name="nowhere")), "r.urdf"),
    "TX201": ("error", robot(ros1()).replace('name="j" type="revolute"', 'name="j" type="fixed"'),
              "r.urdf"),
    "TX202": ("warning", robot(ros1()).replace('<child link="b"/>',
                                               '<child link="b"/><mimic joint="k"/>'), "r.urdf"),
    "TX203": ("error", robot(coupled("DifferentialTransmission", joint2="<hardwareInterface>"
                                     "hardware_interface/PositionJointInterface"
                                     "</hardwareInterface>")), "r.urdf"),
    "TX204": ("warning", robot(ros1(joint=EFFORT + "<hardwareInterface>my/Iface"
                                    "</hardwareInterface>")), "r.urdf"),
    # a misspelt name (an unprefixed one is TX300's finding, at this severity)
    "TX205": ("error", robot(ros1(joint="<hardwareInterface>PositionInterface"
                                  "</hardwareInterface>")), "r.urdf"),
    # from Jazzy on (a Humble reader as well would make it a warning: see OPTIONS)
    "TX206": ("error", robot('<ros2_control name="s" type="system"><joint name="k">'
                             '<command_interface name="position"/></joint></ros2_control>')
              .replace('<child link="c"/>', '<child link="c"/><mimic joint="j"/>'), "r.urdf"),
    "TX207": ("error", robot(ros2(DIFF_ROS2).replace('type="system"', 'type="actuator"')),
              "r.urdf"),
    "TX208": ("error", robot(ros2("") + ros2("").replace('name="j"', 'name="x"')
                             .replace('name="k"', 'name="y"')), "r.urdf"),
    "TX209": ("error", robot(ros2("") + ros2("").replace('name="hw"', 'name="hw2"')), "r.urdf"),
    # a joint whose parent link the robot lacks: urdfdom refuses to build the model
    "TX210": ("error", robot(ros1()).replace('<parent link="b"/>', '<parent link="x"/>'),
              "r.urdf"),
    # beside a registered interface: alone, the transmission is refused (TX205's severity)
    "TX300": ("warning", robot(ros1(joint=EFFORT + "<hardwareInterface>PositionJointInterface"
                                    "</hardwareInterface>")), "r.urdf"),
    "TX301": ("warning", robot(ros1(joint="", actuator=EFFORT + "<mechanicalReduction>1"
                                    "</mechanicalReduction>")), "r.urdf"),
    # the legacy form (the attribute alone); beside a <type> element nothing reads it: info
    "TX302": ("warning", robot(ros1().replace('name="t"', 'name="t" type="SimpleTransmission"')
                               .replace(f"<type>{SIMPLE}</type>", "")), "r.urdf"),
    "TX303": ("error", robot(ros2(ros2_simple(joint_inner="<mechanicalReduction>2"
                                              "</mechanicalReduction>"))), "r.urdf"),
    "TX304": ("warning", robot(ros1() + ros2("")), "r.urdf"),
    # a ROS 1 leftover beside the <ros2_control> block of a robot gz_ros2_control loads
    "TX305": ("info", robot(ros1() + ros2("") + GZ), "r.urdf"),
    # a robot only ROS 2 reads (see OPTIONS) that still names the ROS 1 Gazebo plugin
    "TX306": ("warning", robot(ros2("") + GAZEBO1), "r.urdf"),
    "TX400": ("warning", robot(ros1(joint=EFFORT + "<mechanicalReduction>2"
                                    "</mechanicalReduction>")), "r.urdf"),
    "TX401": ("error", robot(ros2(DIFF_ROS2)), "r.urdf"),
    "TX402": ("info", robot(coupled("FourBarLinkageTransmission")), "r.urdf"),
    "TX403": ("error", robot(coupled("DifferentialTransmission", reduction2="1e-13")), "r.urdf"),
    "TX404": ("error", robot(coupled("DifferentialTransmission")
                             .replace("<role>joint1</role>", "<role>joint0</role>")
                             .replace("<role>joint2</role>", "<role>joint1</role>")
                             .replace("<role>joint0</role>", "<role>joint2</role>")), "r.urdf"),
    # A robot with a controller configuration (``txtool validate r.urdf --controllers c.yaml``).
    "TX500": ("error", (robot(ros1()), "c:\n  type: effort_controllers/JointEffortController\n"
                        "  joint: k\n"), "controllers.yaml"),
    "TX501": ("error", (robot(ros1()), "c:\n  type: position_controllers/JointPositionController"
                        "\n  joint: j\n"), "controllers.yaml"),
    "TX502": ("error", (robot(POSITION_ONLY),
                        "controller_manager:\n  ros__parameters:\n    c:\n      type: "
                        "parallel_gripper_action_controller/GripperActionController\n"
                        "c:\n  ros__parameters:\n    joint: j\n"), "controllers.yaml"),
    "TX503": ("warning", (robot(ros1()), "c:\n  type: effort_controllers/JointEfortController\n"
                          "  joint: j\n"), "controllers.yaml"),
    # ... and a launch file of its package starting two of them (launch/bringup.launch).
    "TX504": ("error", (robot(ros1()), "a:\n  type: effort_controllers/JointEffortController\n"
                        "  joint: j\nb:\n  type: effort_controllers/JointPositionController\n"
                        "  joint: j\n", '<launch><node pkg="controller_manager" type="spawner" '
                        'name="s" args="a b"/></launch>'), "controllers.yaml"),
}


# Settings a row needs to fire at its registered severity.
OPTIONS: dict[str, dict[str, str]] = {"TX206": {"ros-distro": "jazzy"},
                                      "TX306": {"ros-distro": "jazzy"}}


def test_the_table_covers_every_registered_rule_with_its_registered_severity():
    registered = {code: rule.severity for code, rule in all_rules().items()}
    assert registered == {code: row[0] for code, row in TABLE.items()}


@pytest.mark.parametrize("code", sorted(TABLE))
def test_each_rule_reports_its_registered_severity(code, tmp_path):
    severity, document, filename = TABLE[code]
    if filename == "controllers.yaml":
        import txtool

        (tmp_path / "r.urdf").write_text(document[0])
        (tmp_path / filename).write_text(document[1])
        if len(document) > 2:
            (tmp_path / "package.xml").write_text('<package format="3"><name>p</name></package>')
            (tmp_path / "launch").mkdir()
            (tmp_path / "launch" / "bringup.launch").write_text(document[2])
        found = [p for p in txtool.validate([str(tmp_path / "r.urdf")],
                                            controllers=[str(tmp_path / filename)])
                 if p.code == code]
    elif filename == "named.urdf":
        import txtool

        (tmp_path / filename).write_text(document)
        found = [p for p in txtool.validate([str(tmp_path / filename)]) if p.code == code]
    else:
        found = [p for p in problems("\n" + document, filename=filename,
                                     **OPTIONS.get(code, {})) if p.code == code]
    assert found, f"{code} did not fire on its table snippet"
    assert {p.severity for p in found} == {severity}
    assert {p.severity for p in found} == {all_rules()[code].severity}


def test_a_configured_severity_wins_over_the_registered_one():
    document = TABLE["TX108"][1]
    found = [p for p in problems("\n" + document, severity={"TX108": "error"})
             if p.code == "TX108"]
    assert [p.severity for p in found] == ["error"]
