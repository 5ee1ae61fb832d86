"""The read-back check and roundtrip judge every transmission: what they find is said for each
transmission it concerns, also where others differ from it only in their names."""

from __future__ import annotations

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


DIFFERENTIAL = """  <transmission name="{name}">
    <type>transmission_interface/DifferentialTransmission</type>
    <joint name="{j1}"><role>joint1</role><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>
    <joint name="{j2}"><role>joint2</role><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>
    <actuator name="{a1}"><role>actuator1</role><mechanicalReduction>2</mechanicalReduction></actuator>
    <actuator name="{a2}"><role>actuator2</role><mechanicalReduction>3</mechanicalReduction></actuator>
  </transmission>"""


def test_roundtrip_judges_again_a_pair_whose_names_sort_otherwise(run, tmp_path):
    """t1 and t2 differ only in their names, but t2's joint1 sorts after its joint2:
    ros2_control, which orders handles by name, binds them the other way. The verdict found
    for t1 must not be taken for t2."""
    import json

    path = tmp_path / "robot.urdf"
    path.write_text('<robot name="r">\n  <link name="base"/>\n'
                    + DIFFERENTIAL.format(name="t1", j1="a", j2="b", a1="m1", a2="m2") + "\n"
                    + DIFFERENTIAL.format(name="t2", j1="d", j2="c", a1="m3", a2="m4") + "\n"
                    + DIFFERENTIAL.format(name="t3", j1="e", j2="f", a1="m5", a2="m6")
                    + "\n</robot>\n")
    code, out, _ = run("roundtrip", "--format", "json", str(path))
    assert code == 1
    verdicts = {(c["transmission"], tuple(c["cycle"])): c["equivalent"]
                for c in json.loads(out)["cycles"]}
    assert len(verdicts) == 12
    for (name, _cycle), verdict in verdicts.items():
        if name == "t2":
            assert verdict == ("no: actuator 'm4' position differs by 37.6991 at joint values "
                               "(c=3.14159, d=-3.14159)")
        else:
            assert verdict == "yes"
