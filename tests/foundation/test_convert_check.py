"""The read-back check judges each shape of transmission once: thousands of transmissions that
differ only in their names are not judged thousands of times, and what it finds is still said
for every transmission it concerns."""

from __future__ import annotations

from txtool.model.core import Member, Number, Transmission
from txtool.transform.shapes import shape

BLOCK = """<robot name="r">
  <ros2_control name="hw" type="system">
    <hardware><plugin>mock_components/GenericSystem</plugin></hardware>
    <joint name="j1"><command_interface name="position"/></joint>
    <joint name="j2"><command_interface name="position"/></joint>
  </ros2_control>
{transmissions}
</robot>
"""
SIMPLE = """  <transmission name="t{i}">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="j{i}"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>
    <actuator name="m{i}"><mechanicalReduction>2</mechanicalReduction></actuator>
  </transmission>"""


def test_a_loss_the_check_finds_is_said_for_every_transmission_of_that_shape(run, tmp_path):
    path = tmp_path / "robot.urdf"
    path.write_text(BLOCK.format(transmissions="\n".join(SIMPLE.format(i=i) for i in (1, 2, 3))))
    code, out, err = run("convert", str(path), "--to", "ros2-p2")
    assert code == 1
    assert out == ""
    assert err == "".join(
        f"error: joint 'j{i}': transmission 't{i}' names {{effort}} but the <ros2_control> that "
        "declares the joint commands {position}; add the missing command interface there "
        "(txtool does not change a hardware declaration)\n" for i in (1, 2)
    ) + "txtool: 2 item(s) would be lost; nothing written (use --allow-lossy to accept)\n"


def _differential(name: str, joints: tuple[str, str], actuators: tuple[str, str]) -> Transmission:
    def member(member_name: str, role: str) -> Member:
        return Member(name=member_name, role=role, mechanical_reduction=Number(value=2.0, text="2"))

    return Transmission(
        name=name, type="transmission_interface/DifferentialTransmission", kind="differential",
        joints=tuple(member(n, f"joint{i}") for i, n in enumerate(joints, 1)),
        actuators=tuple(member(n, f"actuator{i}") for i, n in enumerate(actuators, 1)),
        dialect="ros1",
    )


def test_a_shape_is_the_transmission_up_to_its_names():
    first = _differential("t1", ("a", "b"), ("m", "n"))
    assert shape(first) == shape(_differential("t2", ("x", "y"), ("p", "q")))
    assert shape(first) == shape(_differential("t2", ("y", "x"), ("q", "p")))  # order is not read
    # Which names are equal is kept: the check keys values by member name.
    assert shape(first) != shape(_differential("t2", ("x", "y"), ("x", "q")))
    assert shape(first, first) != shape(first, _differential("t2", ("a", "b"), ("m", "n")))
    # A name the check's own code writes keeps its spelling.
    assert shape(first) != shape(_differential("t2", ("x", "y"), ("actuator1", "q")))
    # Everything but the names counts, the text of a number as written too.
    other = Member(name="m", role="actuator1", mechanical_reduction=Number(value=2.0, text="2.0"))
    assert shape(first) != shape(Transmission(
        name="t1", type=first.type, kind=first.kind, joints=first.joints,
        actuators=(other, first.actuators[1]), dialect="ros1"))
