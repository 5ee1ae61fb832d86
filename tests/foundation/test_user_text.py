"""The text tables users read: ``show --actuator-limits`` and ``roundtrip``, column by column."""

from __future__ import annotations

import json

import pytest

from tests.text_tables import table_rows

LIMITS = "Actuator-space limits"

# fixtures/demo_robot.urdf, worked out by hand from its URDF limits and transmissions:
# shoulder: n = -100, offset 0.1, limits [-2, 2] rad, 2 rad/s, 40 Nm: (x - 0.1) * -100.
# wrist: differential ar (30, 30), jr (1, 1), roll offset 0.25; pitch [-1.5, 1.5], roll
# [-2.5, 2.5], 3 rad/s, 20 Nm each: x_a = 30 * (p0 +- p1), v_a = 30 * (3 + 3),
# e_a = (20 + 20) / (2 * 30).
DEMO_LIMITS = [
    {"transmission": "shoulder_trans", "actuator": "shoulder_motor",
     "position": "[-190, 210]", "velocity": "200", "effort": "0.4"},
    {"transmission": "wrist_trans", "actuator": "wrist_left_motor",
     "position": "[-127.5, 112.5]", "velocity": "180", "effort": "0.666667"},
    {"transmission": "wrist_trans", "actuator": "wrist_right_motor",
     "position": "[-112.5, 127.5]", "velocity": "180", "effort": "0.666667"},
]


def test_show_actuator_limits_table_puts_each_value_under_its_header(run, fixtures):
    code, out, err = run("show", str(fixtures / "demo_robot.urdf"), "--actuator-limits")
    assert (code, err) == (0, "")
    assert table_rows(out, LIMITS) == DEMO_LIMITS


def test_show_actuator_limits_text_and_json_agree(run, fixtures):
    path = str(fixtures / "demo_robot.urdf")
    _, text, _ = run("show", path, "--actuator-limits")
    code, out, _ = run("show", path, "--actuator-limits", "--format", "json")
    assert code == 0
    as_text = [
        {"transmission": lim["transmission"], "actuator": lim["actuator"],
         "position": "[{:.6g}, {:.6g}]".format(*lim["position"]),
         "velocity": f"{lim['velocity']:.6g}", "effort": f"{lim['effort']:.6g}"}
        for lim in json.loads(out)["actuator_limits"]
    ]
    assert table_rows(text, LIMITS) == as_text


# A continuous joint has no position limit; a joint without <limit> has none at all.
PARTIAL_LIMITS = """<robot name="r">
  <link name="a"/><link name="b"/><link name="c"/>
  <joint name="spin" type="continuous"><parent link="a"/><child link="b"/>
    <limit effort="12" velocity="5"/></joint>
  <joint name="free" type="revolute"><parent link="b"/><child link="c"/></joint>
  <transmission name="spin_trans">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="spin"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>
    <actuator name="spin_motor"><mechanicalReduction>4</mechanicalReduction></actuator>
  </transmission>
  <transmission name="free_trans">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="free"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>
    <actuator name="free_motor"><mechanicalReduction>4</mechanicalReduction></actuator>
  </transmission>
</robot>
"""


def test_show_actuator_limits_marks_missing_limits_in_their_own_columns(run, tmp_path):
    robot = tmp_path / "partial.urdf"
    robot.write_text(PARTIAL_LIMITS)
    code, out, err = run("show", str(robot), "--actuator-limits")
    assert (code, err) == (0, "")
    assert table_rows(out, LIMITS) == [
        {"transmission": "spin_trans", "actuator": "spin_motor",
         "position": "-", "velocity": "20", "effort": "3"},
        {"transmission": "free_trans", "actuator": "free_motor",
         "position": "-", "velocity": "-", "effort": "-"},
    ]


# --- roundtrip ------------------------------------------------------------------------------

FIELDS = ("reduction", "offset", "direction", "roles", "interfaces")
ROS1_CYCLES = [
    "ros1 → ros2-p1 → ros1",
    "ros1 → ros2-p2 → ros1",
    "ros1 → ros2-p1 → ros2-p2 → ros1",
    "ros1 → ros2-p2 → ros2-p1 → ros1",
]


def test_roundtrip_table_of_a_lossless_robot(run, fixtures):
    path = str(fixtures / "demo_robot.urdf")
    code, out, err = run("roundtrip", path)
    assert (code, err) == (0, "")
    rows = table_rows(out, f"{path}: round trips")
    assert [(r["transmission"], r["cycle"]) for r in rows] == [
        (name, cycle) for cycle in ROS1_CYCLES for name in ("shoulder_trans", "wrist_trans")
    ]
    for row in rows:
        assert [row[f] for f in FIELDS] == ["✓"] * 5 and row["equivalent"] == "yes"
    assert out.rstrip().endswith("all cycles keep every field")


# ros2_control binds reductions in XML order (m10 first), ros_control by role (m2 first).
ROLE_ORDER = """<robot name="r">
  <ros2_control name="hw" type="system">
    <joint name="elbow"><command_interface name="position"/></joint>
    <joint name="wrist"><command_interface name="position"/></joint>
    <transmission name="t">
      <plugin>transmission_interface/DifferentialTransmission</plugin>
      <actuator name="m10" role="actuator2"><mechanical_reduction>10</mechanical_reduction></actuator>
      <actuator name="m2" role="actuator1"><mechanical_reduction>20</mechanical_reduction></actuator>
      <joint name="elbow" role="joint1"/>
      <joint name="wrist" role="joint2"/>
    </transmission>
  </ros2_control>
</robot>
"""


MACROS_ONLY = """\
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="wrist_transmission" params="prefix">
    <transmission name="${prefix}_wrist_trans">
      <type>transmission_interface/SimpleTransmission</type>
      <joint name="${prefix}_wrist">
        <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
      </joint>
      <actuator name="${prefix}_wrist_motor"><mechanicalReduction>50</mechanicalReduction></actuator>
    </transmission>
  </xacro:macro>
</robot>
"""


@pytest.mark.parametrize("force_color", ["", "1"], ids=["plain", "rich"])
def test_roundtrip_of_a_file_of_macros_says_that_nothing_was_cycled(
        run, tmp_path, monkeypatch, force_color):
    # Expanded, a file that only defines a macro holds no transmission: no cycle ran, which is
    # said, not passed as "all cycles keep every field"; as written, the macro's is cycled.
    monkeypatch.setenv("FORCE_COLOR", force_color)
    path = tmp_path / "wrist.transmission.xacro"
    path.write_text(MACROS_ONLY)
    code, out, err = run("roundtrip", str(path))
    assert (code, err) == (0, "")
    assert "all cycles keep every field" not in out
    assert out.rstrip().endswith(
        "nothing cycled: no transmission of a standard type in the document as xacro expands "
        "it (transmissions inside macros are cycled as written with --no-xacro)")
    code, out, err = run("roundtrip", "--no-xacro", str(path))
    assert (code, err) == (0, "") and out.rstrip().endswith("all cycles keep every field")
    assert "${prefix}_wrist_trans" in out


def test_roundtrip_of_custom_types_alone_passes_them_through_and_cycles_nothing(run, tmp_path):
    path = tmp_path / "hand.urdf"
    path.write_text('<robot name="hand"><transmission name="t"><type>acme/Tendon</type>'
                    '<joint name="j"/><actuator name="m"/></transmission></robot>')
    code, out, _ = run("roundtrip", str(path))
    assert code == 0
    assert out.rstrip().splitlines()[-2:] == [
        "passed through untouched: t: custom type 'acme/Tendon'",
        "nothing cycled: no transmission of a standard type in the document"]


def test_roundtrip_table_marks_the_cycles_that_change_behaviour(run, tmp_path):
    robot = tmp_path / "role_order.urdf"
    robot.write_text(ROLE_ORDER)
    code, out, err = run("roundtrip", str(robot))
    assert (code, err) == (1, "")
    rows = table_rows(out, f"{robot}: round trips")
    assert {r["cycle"]: r["equivalent"] for r in rows} == {
        "ros2-p2 → ros1 → ros2-p2": "no",
        "ros2-p2 → ros2-p1 → ros2-p2": "yes",
        "ros2-p2 → ros1 → ros2-p1 → ros2-p2": "no",
        "ros2-p2 → ros2-p1 → ros1 → ros2-p2": "yes",
    }
    assert all([r[f] for f in FIELDS] == ["✓"] * 5 for r in rows)
    assert "t (ros2-p2 → ros1 → ros2-p2): actuator 'm2' position differs by" in out
    assert out.rstrip().endswith("some cycles lose data or change behaviour")


@pytest.mark.parametrize("name", ["demo_robot.urdf", "four_bar.ros1.urdf",
                                  "rrbot_differential.ros2-p1.urdf"])
def test_roundtrip_text_and_json_agree(run, fixtures, name):
    path = str(fixtures / name)
    code, text, _ = run("roundtrip", path)
    json_code, out, _ = run("roundtrip", path, "--format", "json")
    assert code == json_code
    expected = [
        {"transmission": c["transmission"], "cycle": " → ".join(c["cycle"]),
         **{f: "✓" if c[f] else "✗" for f in FIELDS},
         "equivalent": c["equivalent"].split(":", 1)[0]}
        for c in json.loads(out)["cycles"]
    ]
    assert table_rows(text, f"{path}: round trips") == expected
