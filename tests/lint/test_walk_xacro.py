"""``txtool validate <package>``: what a folder walk expands, and what a failed expansion means.

Modelled on robot packages as they are published: a top-level robot whose argument the launch
file gives, fragments it includes that use its properties, a sensor from a dependency that is
not installed, and MoveIt's semantic description.
"""

from __future__ import annotations

import json

import pytest

from txtool.io.xmlio import XacroOptions
from txtool.lint.fragments import fragments

XACRO_NS = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'
MANIFEST = """<package format="3"><name>my_robot</name><version>0.1.0</version>
  <description>d</description><maintainer email="m@example.com">m</maintainer>
  <license>BSD</license><buildtool_depend>catkin</buildtool_depend>
  <exec_depend>vendor_sensors</exec_depend></package>
"""
# The launch file runs `xacro robot.urdf.xacro prefix:=left_`: no default in the file.
ROBOT = f"""<robot name="r" {XACRO_NS}>
  <xacro:property name="side" value="left"/>
  <link name="$(arg prefix)base"/>
  <xacro:include filename="$(find my_robot)/urdf/${{side}}_arm.transmission.xacro"/>
  <xacro:include filename="wheels.xacro"/>
  <joint name="${{side}}_joint" type="continuous">
    <parent link="$(arg prefix)base"/><child link="${{side}}_wheel"/>
  </joint>
</robot>
"""
ARM = f"""<robot {XACRO_NS}>
  <transmission name="${{side}}_trans">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="${{side}}_joint"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>
    <actuator name="${{side}}_motor"><mechanicalReduction>0</mechanicalReduction></actuator>
  </transmission>
</robot>
"""
WHEELS = f"""<robot {XACRO_NS}>
  <link name="${{side}}_wheel"/>
</robot>
"""
SENSORS = f"""<robot name="s" {XACRO_NS}>
  <xacro:include filename="$(find vendor_sensors)/urdf/lidar.xacro"/>
</robot>
"""
SRDF = f"""<robot name="r" {XACRO_NS}>
  <group name="$(arg robot_name)_arm"/>
</robot>
"""


def write(path, text):
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text)
    return path


@pytest.fixture
def package(tmp_path, monkeypatch):
    for variable in ("AMENT_PREFIX_PATH", "ROS_PACKAGE_PATH", "CMAKE_PREFIX_PATH"):
        monkeypatch.delenv(variable, raising=False)
    monkeypatch.chdir(tmp_path)
    write(tmp_path / "my_robot/package.xml", MANIFEST)
    write(tmp_path / "my_robot/urdf/robot.urdf.xacro", ROBOT)
    write(tmp_path / "my_robot/urdf/left_arm.transmission.xacro", ARM)
    write(tmp_path / "my_robot/urdf/wheels.xacro", WHEELS)
    write(tmp_path / "my_robot/urdf/sensors.urdf.xacro", SENSORS)
    write(tmp_path / "my_robot/config/my_robot.srdf.xacro", SRDF)
    return tmp_path


def not_found(root, name):
    return (f"package '{name}' not found (looked in: AMENT_PREFIX_PATH (unset); "
            f"ROS_PACKAGE_PATH (unset); the enclosing package 'my_robot' "
            f"({root}/my_robot/package.xml); the packages below {root}; CMAKE_PREFIX_PATH "
            f"(unset)); give --pkg-dir DIR or --pkg-path {name}:=DIR")


ZERO = ("my_robot/urdf/left_arm.transmission.xacro:5:36: error TX106 zero-reduction: reduction of "
        "actuator '${side}_motor' of transmission '${side}_trans' is zero: ros_control refuses it "
        "(\"Transmission reduction ratio cannot be zero\")")


def test_a_package_walk_expands_what_it_can_and_says_what_it_could_not(validate, package):
    code, out, _ = validate("my_robot")
    assert (code, out.splitlines()) == (1, [
        # an included fragment: checked as written (its zero reduction), never expanded alone
        ZERO,
        "my_robot/urdf/robot.urdf.xacro:3:15: info TX002 xacro-failed: not expanded, checked "
        "as written only: xacro: missing argument 'prefix' (give --xacro-arg prefix:=VALUE)",
        "my_robot/urdf/sensors.urdf.xacro:2:28: info TX002 xacro-failed: not expanded, checked "
        f"as written only: xacro: {not_found(package, 'vendor_sensors')}",
        # my_robot.srdf.xacro is not read: no transmission loader reads an SRDF
        "Found 1 error, 2 infos in 4 files; 2 files not expanded (TX002).",
    ])


def test_with_the_argument_the_robot_is_checked_through_its_expansion(validate, package):
    code, out, _ = validate("--xacro-arg", "prefix:=left_", "--ignore", "TX106", "my_robot")
    assert (code, out.splitlines()) == (0, [
        "my_robot/urdf/sensors.urdf.xacro:2:28: info TX002 xacro-failed: not expanded, checked "
        f"as written only: xacro: {not_found(package, 'vendor_sensors')}",
        "Found 1 info in 4 files; 1 file not expanded (TX002).",
    ])


def test_a_fragment_named_on_the_command_line_is_expanded_alone(validate, package):
    code, out, _ = validate("--select", "TX002", "my_robot/urdf/wheels.xacro")
    assert (code, out.splitlines()) == (1, [
        "my_robot/urdf/wheels.xacro:2:15: error TX002 xacro-failed: xacro: name 'side' is not "
        "defined",
        "Found 1 error in 1 file; 1 file not expanded (TX002).",
    ])


def test_an_error_in_a_file_nobody_includes_stays_an_error(validate, package):
    write(package / "my_robot/urdf/old_robot.urdf.xacro", WHEELS.replace("<robot", '<robot name="o"'))
    code, out, _ = validate("--select", "TX002", "--format", "json", "my_robot")
    report = json.loads(out)
    assert code == 1
    assert [(p["path"], p["severity"], p["message"]) for p in report["problems"]] == [
        ("my_robot/urdf/old_robot.urdf.xacro", "error", "xacro: name 'side' is not defined"),
        ("my_robot/urdf/robot.urdf.xacro", "info", "not expanded, checked as written only: "
         "xacro: missing argument 'prefix' (give --xacro-arg prefix:=VALUE)"),
        ("my_robot/urdf/sensors.urdf.xacro", "info", "not expanded, checked as written only: "
         f"xacro: {not_found(package, 'vendor_sensors')}"),
    ]
    assert report["summary"] == {"files": 5, "errors": 1, "warnings": 0, "infos": 2,
                                 "not_expanded": 3}


def test_a_missing_include_of_the_package_itself_stays_an_error(validate, package):
    write(package / "my_robot/urdf/robot.urdf.xacro",
          ROBOT.replace("wheels.xacro", "castor.xacro").replace("$(arg prefix)", ""))
    code, out, _ = validate("--select", "TX002", "my_robot/urdf/robot.urdf.xacro")
    robot = package / "my_robot/urdf"
    assert (code, out.splitlines()) == (1, [
        "my_robot/urdf/robot.urdf.xacro:5:3: error TX002 xacro-failed: xacro: [Errno 2] No such "
        f"file or directory: '{robot}/castor.xacro'",
        "Found 1 error in 1 file; 1 file not expanded (TX002).",
    ])


def test_a_semantic_description_named_on_the_command_line_is_checked(validate, package):
    code, out, _ = validate("--select", "TX002", "my_robot/config/my_robot.srdf.xacro")
    assert code == 0 and out.splitlines()[-1] == "Found 1 info in 1 file; 1 file not expanded (TX002)."


def included(tmp_path, includer: str, *others: str) -> list[str]:
    write(tmp_path / "pkg/package.xml", "<package><name>pkg</name></package>")
    top = write(tmp_path / "pkg/urdf/top.urdf.xacro", f"<robot {XACRO_NS}>{includer}</robot>")
    walked = [str(write(tmp_path / "pkg" / name, "<robot/>")) for name in others]
    found = fragments([(str(top), XacroOptions()), *((p, XacroOptions()) for p in walked)],
                      [str(top), *walked])
    return sorted(str(path).removeprefix(f"{tmp_path}/pkg/") for path in found)


@pytest.mark.parametrize(("include", "expected"), [
    ('<xacro:include filename="parts/arm.xacro"/>', ["urdf/parts/arm.xacro"]),
    ('<xacro:include filename="../macros/arm.xacro"/>', ["macros/arm.xacro"]),
    ('<xacro:include filename="$(find pkg)/macros/arm.xacro"/>', ["macros/arm.xacro"]),
    ('<xacro:include filename="$(dirname)/parts/arm.xacro"/>', ["urdf/parts/arm.xacro"]),
    ("<include filename='parts/arm.xacro'/>", ["urdf/parts/arm.xacro"]),
    # a name built from properties or arguments: every walked file it can name
    ('<xacro:include filename="$(find pkg)/macros/${side}_arm.xacro"/>', ["macros/left_arm.xacro"]),
    ('<xacro:include filename="$(find pkg)/$(arg kind)/arm.xacro"/>', ["macros/arm.xacro"]),
    # a name that could be any file marks none; an unknown package, a comment neither
    ('<xacro:include filename="$(arg extras)"/>', []),
    ('<xacro:include filename="$(find pkg)/macros/${robot}.xacro"/>', []),
    ('<xacro:include filename="$(find other)/macros/arm.xacro"/>', []),
    ('<!-- <xacro:include filename="parts/arm.xacro"/> -->', []),
])
def test_fragments_are_the_walked_files_an_include_names(tmp_path, include, expected):
    assert included(tmp_path, include, "urdf/parts/arm.xacro", "macros/arm.xacro",
                    "macros/left_arm.xacro") == expected


def test_a_package_the_package_xml_does_not_declare_is_named_so(validate, package):
    write(package / "my_robot/urdf/sensors.urdf.xacro", SENSORS.replace("vendor_sensors", "old_sensors"))
    code, out, _ = validate("--select", "TX002", "my_robot/urdf/sensors.urdf.xacro")
    assert (code, out.splitlines()) == (0, [
        "my_robot/urdf/sensors.urdf.xacro:2:28: info TX002 xacro-failed: not expanded, checked "
        f"as written only: xacro: {not_found(package, 'old_sensors')}; the package.xml of "
        "'my_robot' does not declare it: a dependency to declare, or a package that was renamed",
        "Found 1 info in 1 file; 1 file not expanded (TX002).",
    ])
