"""Behavioural equivalence of two configs, per joint and actuator name."""

from __future__ import annotations

from pathlib import Path

import pytest

from txtool.dialects.read import read_source
from txtool.io.load import load
from txtool.mechanics.equivalence import compare
from txtool.model.core import Transmission
from txtool.model.robot import JointInfo
from txtool.model.semantics import effective


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


ROS1_JOINT = """<joint name="{name}"><role>{role}</role><mechanicalReduction>{reduction}
    </mechanicalReduction><offset>{offset}</offset><hardwareInterface>
    hardware_interface/EffortJointInterface</hardwareInterface></joint>"""
ROS1_ACTUATOR = """<actuator name="{name}"><role>{role}</role><mechanicalReduction>{reduction}
    </mechanicalReduction></actuator>"""


def four_bar_ros1(j1: str, j2: str, a1: str, a2: str, against_roles: bool = False) -> str:
    """ROS 1 four-bar; ``against_roles`` lists the role-2 members first, as ros_control's
    own four-bar test robot does."""
    joints = [ROS1_JOINT.format(name=j1, role="joint1", reduction="2", offset="0.5"),
              ROS1_JOINT.format(name=j2, role="joint2", reduction="-2", offset="-0.5")]
    actuators = [ROS1_ACTUATOR.format(name=a1, role="actuator1", reduction="50"),
                 ROS1_ACTUATOR.format(name=a2, role="actuator2", reduction="-50")]
    if against_roles:
        joints.reverse()
        actuators.reverse()
    return ('<transmission name="t1"><type>transmission_interface/FourBarLinkageTransmission'
            "</type>" + "".join(actuators + joints) + "</transmission>")


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
    # ROS 1 in role order binds foo = joint1; ros2_control sorts handles by name (bar < foo),
    # so foo's values, listed first, are bound to bar.
    a = read(tmp_path, "a.urdf", four_bar_ros1("foo", "bar", "foo_actuator", "bar_actuator"))
    b = read(tmp_path, "b.urdf", four_bar_ros2(("foo", "foo_actuator"), ("bar", "bar_actuator")))
    (row,) = compare(a, b).rows
    assert row.status == "differs"
    assert row.joints == ("bar", "foo")
    assert row.reason.startswith("actuator 'bar_actuator' position differs by ")
    assert "(bar=" in row.reason and ", foo=" in row.reason


def test_four_bar_is_equivalent_when_name_order_matches_roles(tmp_path: Path) -> None:
    a = read(tmp_path, "a.urdf", four_bar_ros1("a_joint", "b_joint", "a_motor", "b_motor"))
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


def test_ros1_members_listed_against_roles_take_the_other_members_values(tmp_path: Path):
    # ros_control: values by role, data in XML order (joint_state_interface_provider.cpp:132
    # @133d768): b_joint, listed first, is driven with a_joint's reduction 2 and offset 0.5.
    a = read(tmp_path, "a.urdf", four_bar_ros1("a_joint", "b_joint", "a_motor", "b_motor",
                                               against_roles=True))
    as_written = read(tmp_path, "b.urdf", four_bar_ros2(("a_joint", "a_motor"),
                                                        ("b_joint", "b_motor")))
    assert not compare(a, as_written, convention="ros2").equivalent
    (loaded,) = [effective(t) for t in a]
    assert loaded.joints == ("b_joint", "a_joint")
    assert (loaded.joint_reduction, loaded.joint_offset) == ((2.0, -2.0), (0.5, -0.5))
    assert (loaded.actuators, loaded.actuator_reduction) == (("b_motor", "a_motor"),
                                                             (50.0, -50.0))


def test_ros1_against_roles_can_coincide_with_ros2_name_order(tmp_path: Path):
    # ros_control's four-bar test robot: bar_joint (joint2) before foo_joint (joint1). Its XML
    # order is also the name order, so the ROS 1 data binding and ros2_control's name-sorted
    # handles agree on the joints.
    a = read(tmp_path, "a.urdf", four_bar_ros1("foo", "bar", "foo_actuator", "bar_actuator",
                                               against_roles=True))
    b = read(tmp_path, "b.urdf", four_bar_ros2(("foo", "foo_actuator"), ("bar", "bar_actuator")))
    assert compare(a, b, convention="ros2").equivalent


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


def test_maps_that_overflow_to_nan_alike_are_equivalent(tmp_path: Path) -> None:
    """A differential whose huge reductions make both maps inf - inf (nan) at the same
    samples: the same value on both sides, a difference of 0 (a nan is never equal to
    itself: a plain subtraction would report the worst difference as unknown)."""
    members = (r2_member("actuator", "m1", "actuator1", "1e308")
               + r2_member("actuator", "m2", "actuator2", "1e308")
               + r2_member("joint", "j1", "joint1", "1e308")
               + r2_member("joint", "j2", "joint2", "1e308"))
    a = read(tmp_path, "a.urdf", ros2(members, "DifferentialTransmission"))
    b = read(tmp_path, "b.urdf", ros2(members, "DifferentialTransmission"))
    report = compare(a, b)
    (row,) = report.rows
    assert row.status == "equivalent" and report.equivalent, row.reason
    assert row.differences == {"position": 0.0, "velocity": 0.0, "effort": 0.0}
