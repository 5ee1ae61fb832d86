"""``$(find pkg)/...`` from a checkout whose package installs its folders elsewhere: the path
is read through the package's CMake ``install()`` rules, as the installed package lays it out
(ros2_control_demos: ``install(DIRECTORY description/ros2_control DESTINATION
share/${PROJECT_NAME})``, included as ``$(find pkg)/ros2_control/...``)."""

from __future__ import annotations

from pathlib import Path

import pytest
from click.testing import CliRunner

from txtool.cli import cli

ROBOT = """<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <link name="a"/><link name="b"/>
  <joint name="j" type="revolute"><parent link="a"/><child link="b"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <xacro:include filename="$(find demo_pkg)/INCLUDED"/>
  <transmission name="t">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="j"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>
    <actuator name="m"><mechanicalReduction>${ratio}</mechanicalReduction></actuator>
  </transmission>
</robot>
"""
RATIO = ('<robot xmlns:xacro="http://www.ros.org/wiki/xacro">'
         '<xacro:property name="ratio" value="42.5"/></robot>')


@pytest.fixture(autouse=True)
def no_ros_environment(monkeypatch):
    for variable in ("AMENT_PREFIX_PATH", "ROS_PACKAGE_PATH", "CMAKE_PREFIX_PATH"):
        monkeypatch.delenv(variable, raising=False)


def checkout(tmp_path: Path, cmake: str, included: str, source: str) -> Path:
    """A git checkout holding package demo_pkg: its robot includes ``$(find demo_pkg)/
    {included}``, the file lies at ``source`` and ``cmake`` is its CMakeLists.txt."""
    (tmp_path / ".git").mkdir()
    pkg = tmp_path / "demo_pkg"
    (pkg / "description" / "urdf").mkdir(parents=True)
    (pkg / "package.xml").write_text('<package format="3"><name>demo_pkg</name></package>')
    (pkg / "CMakeLists.txt").write_text(cmake)
    (pkg / source).parent.mkdir(parents=True, exist_ok=True)
    (pkg / source).write_text(RATIO)
    robot = pkg / "description" / "urdf" / "robot.urdf.xacro"
    robot.write_text(ROBOT.replace("INCLUDED", included))
    return robot


def convert(robot: Path) -> tuple[int, str, str]:
    result = CliRunner().invoke(cli, ["convert", "--to", "ros2-p2", str(robot)])
    return result.exit_code, result.stdout, result.stderr


@pytest.mark.parametrize(("cmake", "included", "source"), [
    # a folder installed whole, under its own name
    ("project(demo_pkg)\ninstall(\n  DIRECTORY description/launch description/ros2_control\n"
     "  DESTINATION share/${PROJECT_NAME}\n)\n", "ros2_control/r.xacro",
     "description/ros2_control/r.xacro"),
    # a folder's contents (trailing slash), into a subfolder, the package named literally
    ('install(DIRECTORY "description/parts/" DESTINATION share/demo_pkg/urdf/parts)\n',
     "urdf/parts/r.xacro", "description/parts/r.xacro"),
    # one file, the rule spread over lines with a comment
    ("install(FILES  # the ratio\n  config/ratio.xacro\n  DESTINATION share/${PROJECT_NAME}/"
     "params)\n", "params/ratio.xacro", "config/ratio.xacro"),
])
def test_a_file_of_the_installed_layout_is_read_from_the_checkout(tmp_path, cmake, included,
                                                                   source):
    code, out, err = convert(checkout(tmp_path, cmake, included, source))
    assert code == 0, err
    assert "<mechanical_reduction>42.5</mechanical_reduction>" in out


@pytest.mark.parametrize("cmake", [
    "",  # no rule
    "install(DIRECTORY description/ros2_control DESTINATION include/${PROJECT_NAME})\n",
    "install(DIRECTORY ${SOMEWHERE}/ros2_control DESTINATION share/${PROJECT_NAME})\n",
    "install(DIRECTORY ../../ros2_control DESTINATION share/${PROJECT_NAME})\n",
    "install(TARGETS description/ros2_control DESTINATION share/${PROJECT_NAME})\n",
    "# install(DIRECTORY description/ros2_control DESTINATION share/${PROJECT_NAME})\n",
])
def test_a_path_no_rule_installs_stays_missing(tmp_path, cmake):
    code, out, err = convert(checkout(tmp_path, cmake, "ros2_control/r.xacro",
                                      "description/ros2_control/r.xacro"))
    assert (code, out) == (2, "")
    assert "No such file or directory" in err and err.count("\n") == 1


def test_a_rule_cannot_lead_out_of_the_checkout(tmp_path):
    """A source folder that is a link out of the checkout is refused like any include."""
    outside = tmp_path / "outside"
    (outside / "ros2_control").mkdir(parents=True)
    (outside / "ros2_control" / "r.xacro").write_text(RATIO)
    repo = tmp_path / "repo"
    repo.mkdir()
    robot = checkout(repo, "install(DIRECTORY description/ros2_control DESTINATION "
                     "share/${PROJECT_NAME})\n", "elsewhere/x.xacro", "elsewhere/x.xacro")
    (robot.parent.parent / "ros2_control").symlink_to(outside / "ros2_control")
    robot.write_text(ROBOT.replace("INCLUDED", "ros2_control/r.xacro"))
    code, out, err = convert(robot)
    assert (code, out) == (2, "")
    assert "is outside the repository" in err and "outside/" not in err


def test_load_yaml_reads_the_installed_layout_too(tmp_path):
    robot = checkout(tmp_path, "install(DIRECTORY bringup/config DESTINATION "
                     "share/${PROJECT_NAME})\n", "config/ratio.xacro", "elsewhere/unused.xacro")
    (robot.parents[2] / "bringup" / "config").mkdir(parents=True)
    (robot.parents[2] / "bringup" / "config" / "ratio.yaml").write_text("ratio: 42.5\n")
    robot.write_text(ROBOT.replace(
        '<xacro:include filename="$(find demo_pkg)/INCLUDED"/>',
        '<xacro:property name="ratio" value="${xacro.load_yaml(\'$(find demo_pkg)/config/'
        'ratio.yaml\')[\'ratio\']}"/>'))
    code, out, err = convert(robot)
    assert code == 0, err
    assert "<mechanical_reduction>42.5</mechanical_reduction>" in out


@pytest.mark.parametrize(("cmake", "asked", "found"), [
    ("install(DIRECTORY description/ros2_control description/urdf\n"
     "        DESTINATION share/${PROJECT_NAME})", "ros2_control/r.xacro",
     "description/ros2_control/r.xacro"),
    ('install(DIRECTORY "description/parts/" DESTINATION share/demo_pkg/urdf/parts)',
     "urdf/parts/r.xacro", "description/parts/r.xacro"),
    ("install(FILES config/ratio.xacro DESTINATION share/${PROJECT_NAME}/params)",
     "params/ratio.xacro", "config/ratio.xacro"),
    ("install(DIRECTORY description/ DESTINATION share/${PROJECT_NAME})",
     "ros2_control/r.xacro", "description/ros2_control/r.xacro"),
    ("install(DIRECTORY description/ros2_control DESTINATION include/${PROJECT_NAME})",
     "ros2_control/r.xacro", None),
    ("install(DIRECTORY ${X}/ros2_control ../ros2_control /ros2_control\n"
     "        DESTINATION share/${PROJECT_NAME})", "ros2_control/r.xacro", None),
    ("install(DIRECTORY description/ros2_control DESTINATION)", "ros2_control/r.xacro", None),
    ("# install(DIRECTORY description/ros2_control DESTINATION share/${PROJECT_NAME})",
     "ros2_control/r.xacro", None),
    ("install(DIRECTORY description/ros2_control DESTINATION share/${PROJECT_NAME})",
     "ros2_control/absent.xacro", None),
])
def test_the_installed_path_and_its_source_in_the_checkout(tmp_path, cmake, asked, found):
    """The rules read in-process, as the expansion's worker reads them."""
    from txtool.io.install_layout import installed_source

    robot = checkout(tmp_path, cmake + "\n", "unused.xacro", "description/ros2_control/r.xacro")
    pkg = robot.parents[2]
    for source in ("description/parts/r.xacro", "config/ratio.xacro"):
        (pkg / source).parent.mkdir(parents=True, exist_ok=True)
        (pkg / source).write_text(RATIO)
    expected = None if found is None else str(pkg / found)
    assert installed_source(str(pkg / asked)) == expected


def test_no_package_or_no_cmake_file_installs_nothing(tmp_path):
    from txtool.io.install_layout import installed_source

    assert installed_source(str(tmp_path / "nowhere" / "r.xacro")) is None
    robot = checkout(tmp_path, "", "unused.xacro", "description/ros2_control/r.xacro")
    (robot.parents[2] / "CMakeLists.txt").unlink()
    assert installed_source(str(robot.parents[2] / "ros2_control" / "r.xacro")) is None
