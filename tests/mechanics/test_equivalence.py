"""Behavioural equivalence of two configs, per joint and actuator name."""

from __future__ import annotations

from pathlib import Path

import pytest

from txtool.dialects.read import read_source
from txtool.io.load import load
from txtool.mechanics.equivalence import compare
from txtool.model.core import Transmission
from txtool.model.robot import JointInfo


def read(tmp_path: Path, name: str, body: str) -> list[Transmission]:
    path = tmp_path / name
    path.write_text(f'<robot name="r">{body}</robot>')
    return [f.transmission for f in read_source(load(str(path)))]


def ros1_simple(reduction: str = "50", offset: str = "0.5") -> str:
    return f"""<transmission name="t1"><type>transmission_interface/SimpleTransmission</type>
      <joint name="elbow"><hardwareInterface>hardware_interface/EffortJointInterface
      </hardwareInterface><offset>{offset}</offset></joint>
      <actuator name="elbow_motor"><mechanicalReduction>{reduction}</mechanicalReduction>
      </actuator></transmission>"""


def ros2(members: str, plugin: str = "SimpleTransmission") -> str:
    return f"""<ros2_control name="hw" type="system"><hardware><plugin>x/Y</plugin></hardware>
      <transmission name="t1"><plugin>transmission_interface/{plugin}</plugin>{members}
      </transmission></ros2_control>"""


def r2_member(tag: str, name: str, role: str, reduction: str | None = None,
              offset: str | None = None) -> str:
    inner = ""
    if reduction is not None:
        inner += f"<mechanical_reduction>{reduction}</mechanical_reduction>"
    if offset is not None:
        inner += f"<offset>{offset}</offset>"
    return f'<{tag} name="{name}" role="{role}">{inner}</{tag}>'


def test_correct_simple_conversion_is_equivalent(tmp_path: Path) -> None:
    a = read(tmp_path, "a.urdf", ros1_simple())
    b = read(tmp_path, "b.urdf", ros2(
        r2_member("actuator", "elbow_motor", "actuator1")
        + r2_member("joint", "elbow", "joint1", "50", "0.5")))
    report = compare(a, b)
    assert report.equivalent
    (row,) = report.rows
    assert (row.status, row.a, row.b, row.joints) == ("equivalent", "t1", "t1", ("elbow",))
    assert set(row.differences) == {"position", "velocity", "effort"}
    assert max(row.differences.values()) < 1e-9 and row.reason == ""


def test_reduction_left_on_the_ros2_actuator_differs(tmp_path: Path) -> None:
    a = read(tmp_path, "a.urdf", ros1_simple(offset="0"))
    # ros2_control's simple loader reads the JOINT reduction: this one silently runs 1:1.
    b = read(tmp_path, "b.urdf", ros2(
        r2_member("actuator", "elbow_motor", "actuator1", "50")
        + r2_member("joint", "elbow", "joint1")))
    joints = {"elbow": JointInfo("elbow", "revolute", -1.0, 1.0, 2.0, 10.0)}
    report = compare(a, b, joints)
    (row,) = report.rows
    assert row.status == "differs" and not report.equivalent
    # Position: 50 * 1 vs 1 * 1 at the upper limit.
    assert row.differences["position"] == pytest.approx(49.0)
    assert row.differences["effort"] == pytest.approx(10.0 - 10.0 / 50)
    assert row.reason == ("actuator 'elbow_motor' position differs by 49 at joint values "
                          "(elbow=-1)")


FOUR_BAR_ROS1 = """<transmission name="t1">
  <type>transmission_interface/FourBarLinkageTransmission</type>
  <actuator name="{a2}"><role>actuator2</role><mechanicalReduction>-50</mechanicalReduction>
  </actuator>
  <actuator name="{a1}"><role>actuator1</role><mechanicalReduction>50</mechanicalReduction>
  </actuator>
  <joint name="{j2}"><role>joint2</role><mechanicalReduction>-2</mechanicalReduction>
    <offset>-0.5</offset><hardwareInterface>hardware_interface/EffortJointInterface
    </hardwareInterface></joint>
  <joint name="{j1}"><role>joint1</role><mechanicalReduction>2</mechanicalReduction>
    <offset>0.5</offset><hardwareInterface>hardware_interface/EffortJointInterface
    </hardwareInterface></joint>
</transmission>"""


def four_bar_ros2(first: tuple[str, str], second: tuple[str, str]) -> str:
    """ROS 2 four-bar listing the role-1 members (``first``) then the role-2 ones."""
    return ros2(
        r2_member("actuator", first[1], "actuator1", "50")
        + r2_member("actuator", second[1], "actuator2", "-50")
        + r2_member("joint", first[0], "joint1", "2", "0.5")
        + r2_member("joint", second[0], "joint2", "-2", "-0.5"),
        plugin="FourBarLinkageTransmission",
    )


def test_four_bar_is_not_equivalent_when_name_order_differs_from_roles(tmp_path: Path) -> None:
    # ROS 1 sorts by role (foo = joint1); ros2_control sorts handles by name (bar < foo), so
    # foo's parameters, listed first, are bound to bar.
    names = {"j1": "foo", "j2": "bar", "a1": "foo_actuator", "a2": "bar_actuator"}
    a = read(tmp_path, "a.urdf", FOUR_BAR_ROS1.format(**names))
    b = read(tmp_path, "b.urdf", four_bar_ros2(("foo", "foo_actuator"), ("bar", "bar_actuator")))
    (row,) = compare(a, b).rows
    assert row.status == "differs"
    assert row.joints == ("bar", "foo")
    assert row.reason.startswith("actuator 'bar_actuator' position differs by ")
    assert "(bar=" in row.reason and ", foo=" in row.reason


def test_four_bar_is_equivalent_when_name_order_matches_roles(tmp_path: Path) -> None:
    names = {"j1": "a_joint", "j2": "b_joint", "a1": "a_motor", "a2": "b_motor"}
    a = read(tmp_path, "a.urdf", FOUR_BAR_ROS1.format(**names))
    b = read(tmp_path, "b.urdf", four_bar_ros2(("a_joint", "a_motor"), ("b_joint", "b_motor")))
    assert compare(a, b, convention="ros2").equivalent
    assert compare(a, b, convention="ros1").equivalent
    # By default each side runs its own loader's four-bar effort map, and ros_control's is
    # another formula (four_bar_linkage_transmission.h, actuatorToJointEffort).
    (row,) = compare(a, b).rows
    assert row.status == "differs"
    assert row.differences["position"] == 0.0
    # At joint efforts (-1, -1): ros2_control gives b_motor -1/(-50*-2) = -0.01, ros_control
    # (-1 + -1/-2)/-50 = 0.01.
    assert row.differences["effort"] == pytest.approx(0.02)
    assert row.reason == ("actuator 'b_motor' effort differs by 0.02 at joint values "
                          "(a_joint=-1, b_joint=-1)")


def test_missing_and_not_loadable_rows(tmp_path: Path) -> None:
    a = read(tmp_path, "a.urdf", ros1_simple(reduction="0"))
    b = read(tmp_path, "b.urdf", ros2(r2_member("joint", "wrist", "joint1", "3")))
    report = compare(a, b)
    assert [(r.status, r.a, r.b) for r in report.rows] == [
        ("missing", "t1", None), ("missing", None, "t1")]
    c = read(tmp_path, "c.urdf", ros2(r2_member("joint", "elbow", "joint1", "3")))
    (row,) = compare(a, c).rows
    assert row.status == "not loadable"
    assert row.reason == "first: transmission 't1': reduction ratio cannot be zero"
    assert compare(a, c).row_for("t1") == row


def test_renamed_actuator_differs(tmp_path: Path) -> None:
    a = read(tmp_path, "a.urdf", ros1_simple())
    b = read(tmp_path, "b.urdf", ros2(
        r2_member("actuator", "motor", "actuator1")
        + r2_member("joint", "elbow", "joint1", "50", "0.5")))
    (row,) = compare(a, b).rows
    assert row.status == "differs"
    assert row.reason == "loaded actuators differ: 'elbow_motor' vs 'motor'"
