"""``$(find pkg)`` as the real xacro resolves it: in a sourced ROS 2 workspace through the
ament index of the install space (ros/xacro ros2 substitution_args._eval_find ->
ament_index_python get_package_share_directory), in ROS 1 through ROS_PACKAGE_PATH as rospkg
crawls it, and with --pkg-dir by package.xml <name>, never by a folder's name."""

from __future__ import annotations

import json
import os
from pathlib import Path

import pytest
from click.testing import CliRunner

from txtool.cli import cli
from txtool.io.packages import PackageNotFound, find_package, folder_package_name, packages_below

ROS_VARIABLES = ("AMENT_PREFIX_PATH", "ROS_PACKAGE_PATH", "CMAKE_PREFIX_PATH")

ROBOT = """<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="$(find arm_description)/urdf/ratio.xacro"/>
  <transmission name="t">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="j"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>
    <actuator name="m"><mechanicalReduction>${ratio}</mechanicalReduction></actuator>
  </transmission>
</robot>
"""


@pytest.fixture(autouse=True)
def no_ros_environment(monkeypatch):
    for variable in ROS_VARIABLES:
        monkeypatch.delenv(variable, raising=False)


def package(folder: Path, name: str, ratio: str | None = None) -> Path:
    """A package in ``folder`` named ``name`` by its package.xml; with ``ratio``, it holds
    urdf/ratio.xacro defining the property the robot above reads."""
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "package.xml").write_text(
        f'<?xml version="1.0"?>\n<!-- <name>not_this</name> -->\n<package format="3">\n'
        f"  <name>{name}</name>\n  <version>1.0.0</version>\n</package>\n")
    if ratio is not None:
        (folder / "urdf").mkdir(exist_ok=True)
        (folder / "urdf" / "ratio.xacro").write_text(
            '<robot xmlns:xacro="http://www.ros.org/wiki/xacro">'
            f'<xacro:property name="ratio" value="{ratio}"/></robot>')
    return folder


def install(prefix: Path, name: str, ratio: str) -> Path:
    """``name`` installed into ``prefix`` as colcon leaves it: share/NAME and the marker
    share/ament_index/resource_index/packages/NAME (ament_cmake's ament_package())."""
    share = package(prefix / "share" / name, name, ratio)
    index = prefix / "share" / "ament_index" / "resource_index" / "packages"
    index.mkdir(parents=True, exist_ok=True)
    (index / name).write_text("")
    return share


def run(*args: str, cwd: Path, monkeypatch) -> tuple[int, str, str]:
    monkeypatch.chdir(cwd)
    result = CliRunner().invoke(cli, list(args))
    if result.exception and not isinstance(result.exception, SystemExit):
        raise result.exception
    return result.exit_code, result.stdout, result.stderr


def reduction(out: str) -> str:
    (transmission,) = json.loads(out)["transmissions"]
    return transmission["actuators"][0]["mechanical_reduction"]["text"]


@pytest.fixture
def workspace(tmp_path) -> Path:
    """A colcon workspace: arm_description in src/ (ratio 50) and, built, in install/ (ratio
    80, say a value its CMakeLists generates); the robot in src/ beside it."""
    ws = tmp_path / "ws"
    package(ws / "src" / "arm" / "arm_description", "arm_description", "50")
    robot_pkg = package(ws / "src" / "arm" / "arm_bringup", "arm_bringup")
    (robot_pkg / "robot.urdf.xacro").write_text(ROBOT)
    install(ws / "install", "arm_description", "80")
    for folder in ("build", "install", "log"):
        (ws / folder / "COLCON_IGNORE").parent.mkdir(exist_ok=True)
        (ws / folder / "COLCON_IGNORE").write_text("")
    return ws


def test_a_sourced_workspace_resolves_to_the_install_space(workspace, monkeypatch):
    robot = "src/arm/arm_bringup/robot.urdf.xacro"
    code, out, err = run("show", "--format", "json", robot, cwd=workspace,
                         monkeypatch=monkeypatch)
    assert (code, err, reduction(out)) == (0, "", "50")  # nothing sourced: the sources
    install(workspace.parent / "opt_ros", "other_pkg", "1")
    monkeypatch.setenv("AMENT_PREFIX_PATH", str(workspace.parent / "opt_ros"))
    code, out, err = run("show", "--format", "json", robot, cwd=workspace,
                         monkeypatch=monkeypatch)
    assert (code, err, reduction(out)) == (0, "", "50")  # only ROS sourced: the sources
    monkeypatch.setenv("AMENT_PREFIX_PATH", f"{workspace / 'install'}{os.pathsep}/opt/ros/x")
    code, out, err = run("show", "--format", "json", robot, cwd=workspace,
                         monkeypatch=monkeypatch)
    assert (code, err, reduction(out)) == (0, "", "80")  # as xacro at launch: the install


def test_a_file_only_installed_is_found_in_a_sourced_workspace(workspace, monkeypatch):
    (workspace / "src" / "arm" / "arm_description" / "urdf" / "ratio.xacro").unlink()
    robot = "src/arm/arm_bringup/robot.urdf.xacro"
    code, out, err = run("show", robot, cwd=workspace, monkeypatch=monkeypatch)
    assert code == 2 and "ratio.xacro" in err and out == ""
    monkeypatch.setenv("AMENT_PREFIX_PATH", str(workspace / "install"))
    code, out, err = run("validate", robot, "--format", "json", cwd=workspace,
                         monkeypatch=monkeypatch)
    assert (code, err, json.loads(out)["problems"]) == (0, "", [])


def test_the_ament_index_marker_decides_and_the_first_prefix_wins(tmp_path, monkeypatch):
    first, second = tmp_path / "overlay", tmp_path / "underlay"
    install(second, "arm_description", "2")
    near = str(tmp_path / "elsewhere" / "robot.urdf.xacro")
    # share/NAME without the marker is no package for ament_index (get_resource)
    package(first / "share" / "arm_description", "arm_description", "1")
    monkeypatch.setenv("AMENT_PREFIX_PATH", f"{first}{os.pathsep}{second}")
    assert find_package("arm_description", near=near) == str(second / "share" / "arm_description")
    install(first, "arm_description", "1")
    assert find_package("arm_description", near=near) == str(first / "share" / "arm_description")


def test_explicit_options_come_before_the_sourced_workspace(workspace, tmp_path, monkeypatch):
    monkeypatch.setenv("AMENT_PREFIX_PATH", str(workspace / "install"))
    mine = package(tmp_path / "mine" / "arm_desc_fork", "arm_description", "7")
    robot = "src/arm/arm_bringup/robot.urdf.xacro"
    for option in (["--pkg-dir", str(mine.parent)], ["--pkg-path", f"arm_description:={mine}"]):
        code, out, err = run("show", "--format", "json", *option, robot, cwd=workspace,
                             monkeypatch=monkeypatch)
        assert (code, err, reduction(out)) == (0, "", "7")


def test_pkg_dir_takes_a_package_by_its_package_xml_name(tmp_path):
    deps = tmp_path / "deps"
    (deps / "arm_description" / "urdf").mkdir(parents=True)  # no package.xml: not a package
    package(deps / "impostor" / "arm_description", "other_description")
    near = str(tmp_path / "robot.urdf.xacro")
    with pytest.raises(PackageNotFound) as caught:
        find_package("arm_description", near=near, pkg_dirs=(str(deps),))
    assert str(caught.value).startswith(
        f"package 'arm_description' not found (looked in: --pkg-dir {deps} (its folder "
        "'arm_description' holds no package.xml);")
    package(deps / "arm_description", "arm_description_v2")
    packages_below.cache_clear()  # crawls are cached per process
    with pytest.raises(PackageNotFound, match="its folder 'arm_description' is package "
                                              "'arm_description_v2'"):
        find_package("arm_description", near=near, pkg_dirs=(str(deps),))
    real = package(deps / "vendor" / "arm-description-1.2", "arm_description")
    packages_below.cache_clear()
    assert find_package("arm_description", near=near, pkg_dirs=(str(deps),)) == str(real)
    with pytest.raises(PackageNotFound, match=f"--pkg-dir {tmp_path / 'dpes'} "
                                              r"\(no such folder\);"):
        find_package("arm_description", near=near, pkg_dirs=(str(tmp_path / "dpes"),))
    # DIR may be the package itself, and may carry COLCON_IGNORE (an install/ folder, say)
    (real / "COLCON_IGNORE").write_text("")
    assert find_package("arm_description", near=near, pkg_dirs=(str(real),)) == str(real)


def test_pkg_dir_on_the_command_line_for_a_folder_that_is_not_the_package(tmp_path,
                                                                         monkeypatch):
    (tmp_path / "deps" / "arm_description" / "urdf").mkdir(parents=True)
    (tmp_path / "robot.urdf.xacro").write_text(ROBOT)
    code, out, err = run("show", "--pkg-dir", "deps", "robot.urdf.xacro", cwd=tmp_path,
                         monkeypatch=monkeypatch)
    assert (code, out) == (2, "")
    assert err == (
        "txtool: robot.urdf.xacro:1: xacro: package 'arm_description' not found (looked in: "
        f"--pkg-dir {tmp_path / 'deps'} (its folder 'arm_description' holds no package.xml); "
        "AMENT_PREFIX_PATH (unset); ROS_PACKAGE_PATH (unset); CMAKE_PREFIX_PATH (unset)); "
        "give --pkg-dir DIR or --pkg-path arm_description:=DIR\n")


def test_ros_package_path_is_crawled_as_rospkg_does(tmp_path, monkeypatch):
    first, second = tmp_path / "catkin_ws" / "src", tmp_path / "opt" / "share"
    near = str(tmp_path / "elsewhere" / "robot.xacro")
    theirs = package(second / "arm_description", "arm_description")
    ours = package(first / "repo" / "description", "arm_description")
    monkeypatch.setenv("ROS_PACKAGE_PATH", f"{first}{os.pathsep}{second}")
    assert find_package("arm_description", near=near) == str(ours)  # the first folder wins
    (first / "repo" / "CATKIN_IGNORE").write_text("")
    packages_below.cache_clear()  # crawls are cached per process
    assert find_package("arm_description", near=near) == str(theirs)
    # nested in another package: rospkg does not descend into a package
    package(first / "outer", "outer")
    package(first / "outer" / "inner", "inner_pkg")
    with pytest.raises(PackageNotFound):
        find_package("inner_pkg", near=near)


def test_ros_package_path_follows_a_symbolic_link(tmp_path, monkeypatch):
    checkout = package(tmp_path / "repos" / "arm", "arm_description")
    src = tmp_path / "catkin_ws" / "src"
    src.mkdir(parents=True)
    (src / "arm").symlink_to(checkout)
    (src / "loop").symlink_to(src)  # a link back up is crawled once
    monkeypatch.setenv("ROS_PACKAGE_PATH", str(src))
    assert find_package("arm_description", near=None) == str(src / "arm")


@pytest.mark.parametrize(("configured", "option"), [
    ('pkg-dirs = ["configured"]\n', ["--pkg-dir", "cli"]),
    ('[pkg-paths]\narm_description = "configured/arm_description"\n',
     ["--pkg-path", "arm_description:=cli/arm_description"]),
])
def test_the_command_line_wins_over_the_configuration(tmp_path, monkeypatch, configured, option):
    """The configuration's pkg-dirs (pkg-paths) come after --pkg-dir (--pkg-path): the first
    match wins (lint/config.py puts the command line's first)."""
    package(tmp_path / "configured" / "arm_description", "arm_description", "0")
    package(tmp_path / "cli" / "arm_description", "arm_description", "10")
    (tmp_path / "robot.urdf.xacro").write_text(ROBOT)
    (tmp_path / ".txtool.toml").write_text(configured)
    code, out, _ = run("validate", "robot.urdf.xacro", "--format", "json", cwd=tmp_path,
                       monkeypatch=monkeypatch)
    assert code == 1 and [p["code"] for p in json.loads(out)["problems"]] == ["TX106"]
    code, out, err = run("validate", "robot.urdf.xacro", "--format", "json", *option,
                         cwd=tmp_path, monkeypatch=monkeypatch)
    assert (code, err, json.loads(out)["problems"]) == (0, "", [])


def test_folder_package_name_reads_the_manifest_not_the_folder(tmp_path):
    assert folder_package_name(package(tmp_path / "x", "arm_description")) == "arm_description"
    assert folder_package_name(tmp_path) is None


def reduction_read_by(command: str, out: str) -> str:
    """The reduction each command shows of ROBOT's transmission."""
    if command == "show":
        return reduction(out)
    if command == "map":
        return format(json.loads(out)["position"][0], "g")
    return out.split("<mechanical_reduction>")[1].split("<")[0]  # convert


COMMANDS = {
    "show": ["show", "robot.urdf.xacro", "--format", "json"],
    "convert": ["convert", "robot.urdf.xacro", "--to", "ros2-p2",
                "--hardware-plugin", "arm_driver/ArmHardware"],  # (not the placeholder)
    "map": ["map", "robot.urdf.xacro", "-t", "t", "--to", "actuator", "--position", "1",
            "--format", "json"],
}


@pytest.fixture
def configured_repo(tmp_path) -> Path:
    """A repository whose configuration names a package folder in it (ratio 7; a folder the
    crawl of the repository passes over, COLCON_IGNORE); a folder outside it holds the same
    package with ratio 10. (A configuration cannot make a folder outside readable: see
    tests/hardening/test_xacro_confinement.py.)"""
    repo = tmp_path / "repo"
    (repo / ".git").mkdir(parents=True)
    package(repo / "configured" / "arm_description", "arm_description", "7")
    (repo / "configured" / "COLCON_IGNORE").write_text("")
    package(tmp_path / "cli" / "arm_description", "arm_description", "10")
    (repo / "robot.urdf.xacro").write_text(ROBOT)
    (repo / ".txtool.toml").write_text('pkg-dirs = ["configured"]\n')
    return repo


@pytest.mark.parametrize("command", sorted(COMMANDS))
def test_every_command_reads_the_configured_package_folders_after_the_command_lines(
        configured_repo, monkeypatch, command):
    """docs/configuration.md: pkg-dirs come after --pkg-dir, for every command that takes a
    configuration (not validate alone)."""
    code, out, err = run(*COMMANDS[command], cwd=configured_repo, monkeypatch=monkeypatch)
    assert (code, err, reduction_read_by(command, out)) == (0, "", "7")
    code, out, err = run(*COMMANDS[command], "--pkg-dir", "../cli", cwd=configured_repo,
                         monkeypatch=monkeypatch)
    assert (code, err, reduction_read_by(command, out)) == (0, "", "10")


def test_roundtrip_reads_the_configured_package_folders_and_config_names_the_file(
        configured_repo, monkeypatch):
    code, out, _ = run("roundtrip", "robot.urdf.xacro", "--format", "json",
                       cwd=configured_repo, monkeypatch=monkeypatch)
    assert code == 0 and json.loads(out)
    (configured_repo / ".txtool.toml").write_text("")
    elsewhere = configured_repo.parent / "other.toml"
    elsewhere.write_text('pkg-dirs = ["repo/configured"]\n')
    code, out, err = run("show", "robot.urdf.xacro", "--format", "json", "--config",
                         str(elsewhere), cwd=configured_repo, monkeypatch=monkeypatch)
    assert (code, err, reduction(out)) == (0, "", "7")
    code, out, err = run("show", "robot.urdf.xacro", cwd=configured_repo,
                         monkeypatch=monkeypatch)
    assert code == 2 and out == "" and "package 'arm_description' not found" in err
