"""``validate --diff`` and ``--fix``: a finding marked fixable only where migrate fixes its code,
and the exit status where one of the files named cannot be read (2: an input error outranks
findings), the others still shown."""

from __future__ import annotations

import json

from tests.lint.test_validate_fix import LEGACY, XACRO, robots, run  # noqa: F401 - the fixture

LEGACY_T2 = """  <joint name="k" type="revolute"><limit effort="1" velocity="1" lower="-1" upper="1"/></joint>
  <transmission name="t2" type="transmission_interface/SimpleTransmission">
    <joint name="k"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>
    <actuator name="m2"><mechanicalReduction>50</mechanicalReduction></actuator>
  </transmission>
"""
MISSING = "txtool: urdf/missing.urdf: no such file"


def test_diff_shows_the_fixable_file_and_exits_2_for_the_missing_one(robots):  # noqa: F811
    code, out, err = run("validate", "--diff", "urdf/legacy.urdf", "urdf/missing.urdf")
    assert code == 2
    assert out == run("migrate", "--diff", "urdf/legacy.urdf")[1]
    assert err.splitlines() == [MISSING, "would change urdf/legacy.urdf (TX300 x1, TX301 x1, "
                                "TX302 x1)", "1 file(s) would be changed"]


def test_diff_with_nothing_to_fix_exits_2_for_the_missing_one(robots):  # noqa: F811
    code, out, err = run("validate", "--diff", "urdf/zero.urdf", "urdf/missing.urdf")
    assert (code, out) == (2, "")
    assert err.splitlines() == [MISSING, "txtool: nothing to fix"]


def test_a_finding_is_fixable_only_where_its_own_code_is_fixed(robots):  # noqa: F811
    """migrate rewrites the file for the legacy type attribute (TX302); the unprefixed
    interface is a xacro expression it cannot prefix (TX300), so that finding stays unmarked."""
    (robots / "m.urdf.xacro").write_text(XACRO.replace("</robot>", LEGACY_T2 + "</robot>"))
    code, out, _ = run("validate", "--format", "json", "urdf/m.urdf.xacro")
    assert code == 1
    assert sorted((p["code"], p["fixable"]) for p in json.loads(out)["problems"]) == [
        ("TX300", False), ("TX302", True)]


def test_fix_rewrites_as_the_distribution_said_reads_the_file(tmp_path, monkeypatch):
    """An ament package's ROS 1 robot is read by ros2_control, which reads none of its
    transmissions: nothing to fix. Said to be read by Noetic, its fixes are made."""
    from tests.migrate.test_fixes_under_readers import FIXED, ROBOT

    monkeypatch.chdir(tmp_path)
    (tmp_path / "package.xml").write_text(
        '<package format="3"><name>arm</name><buildtool_depend>ament_cmake</buildtool_depend>'
        "<export><build_type>ament_cmake</build_type></export></package>\n")
    (tmp_path / "r.urdf").write_text(ROBOT[1:])
    code, out, err = run("validate", "--fix", "r.urdf")
    assert (code, err, (tmp_path / "r.urdf").read_text()) == (0, "", ROBOT[1:])
    code, out, err = run("validate", "--fix", "--ros-distro", "noetic", "r.urdf")
    assert err == "txtool: fixed r.urdf (TX300 x1, TX302 x1)\n"
    assert (code, (tmp_path / "r.urdf").read_text()) == (0, FIXED)


def test_standard_input_gets_no_fixes_from_the_file_its_name_gives(robots):  # noqa: F811
    """--stdin-filename names the text read, not the file on disk of that name: SARIF offers
    no fixes computed from that file (which may hold anything)."""
    code, out, _ = run("validate", "--format", "sarif", "--stdin-filename", "urdf/legacy.urdf",
                       "-", input=LEGACY)
    results = json.loads(out)["runs"][0]["results"]
    assert code == 1 and len(results) == 4
    assert [r for r in results if "fixes" in r] == []
