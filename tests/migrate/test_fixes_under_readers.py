"""One set of fixes: ``validate --fix`` and ``migrate`` change the same things under the same
readers (``--ros-distro``, the configuration's ``ros-distro``): what validate reports for them,
nothing where it reports nothing (exit code and output asserted together)."""

from __future__ import annotations

import pytest

ROBOT = """
<robot name="r">
  <link name="a"/><link name="b"/>
  <joint name="j" type="revolute"><parent link="a"/><child link="b"/>
    <limit effort="1" velocity="1" lower="-1" upper="1"/></joint>
  <transmission name="t" type="SimpleTransmission">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="j"><hardwareInterface>PositionJointInterface</hardwareInterface></joint>
    <actuator name="m"><mechanicalReduction>50</mechanicalReduction></actuator>
  </transmission>
</robot>
"""
FIXED = ROBOT.replace(' type="SimpleTransmission"', "").replace(
    "<hardwareInterface>Position", "<hardwareInterface>hardware_interface/Position")[1:]


@pytest.mark.parametrize("stated", [["--ros-distro", "humble"], ["config"]])
def test_a_ros2_distribution_fixes_nothing_in_either_command(run, write, tmp_path, stated):
    """ros2_control reads no top-level transmission: validate reports TX305 alone, and
    neither it nor migrate (the pre-commit hook) rewrites the ROS 1 one."""
    robot = write("r.urdf", ROBOT)
    args = stated
    if stated == ["config"]:
        write(".txtool.toml", 'ros-distro = "humble"\n')
        args = []
    code, out, err = run("migrate", "--write", str(robot), *args)
    assert (code, out, err) == (0, "", "nothing to do (1 file(s) checked)\n")
    code, out, err = run("validate", "--fix", str(robot), *args)
    assert (code, [line.split()[2] for line in out.splitlines()[:-1]]) == (0, ["TX305"])
    assert robot.read_text() == ROBOT[1:]


@pytest.mark.parametrize("distro", [[], ["--ros-distro", "noetic"]])
def test_a_ros1_reader_gets_the_same_fixes_from_both(run, write, tmp_path, distro):
    robot = write("r.urdf", ROBOT)
    code, out, err = run("migrate", "--write", str(robot), *distro)
    assert (code, out) == (0, "") and err.startswith(f"changed {robot} (TX300 x1, TX302 x1)\n")
    assert robot.read_text() == FIXED
    robot.write_text(ROBOT[1:])
    code, out, err = run("validate", "--fix", str(robot), *distro)
    assert err == f"txtool: fixed {robot} (TX300 x1, TX302 x1)\n"
    assert (code, robot.read_text()) == (0, FIXED)  # the report is of the fixed file
