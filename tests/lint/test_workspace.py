"""In a real ROS workspace: ``$(find pkg)`` resolves without flags, and folder walks check each
source file once, passing over colcon's build/install/log, .gitignore and excluded paths."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest
from click.testing import CliRunner

from tests.corpus import workspace_dir
from txtool.cli import cli
from txtool.io.packages import PackageNotFound, find_package

PACKAGE = "rrbot_description"
ROS_VARIABLES = ("AMENT_PREFIX_PATH", "ROS_PACKAGE_PATH", "CMAKE_PREFIX_PATH")


@pytest.fixture(autouse=True)
def no_ros_environment(monkeypatch):
    for variable in ROS_VARIABLES:
        monkeypatch.delenv(variable, raising=False)


@pytest.fixture
def workspace(tmp_path) -> Path:
    """A copy of the shared workspace as colcon leaves it after a build: the package in
    src/, again in build/ and install/share/ (registered in the install's ament index), each
    of those marked with COLCON_IGNORE."""
    ws = tmp_path / "ws"
    shutil.copytree(workspace_dir(), ws)
    source = ws / "src" / PACKAGE
    shutil.copytree(source, ws / "build" / PACKAGE)
    shutil.copytree(source, ws / "install" / "share" / PACKAGE)
    index = ws / "install" / "share" / "ament_index" / "resource_index" / "packages"
    index.mkdir(parents=True)
    (index / PACKAGE).write_text("")
    for folder in ("build", "install", "log"):
        (ws / folder).mkdir(exist_ok=True)
        (ws / folder / "COLCON_IGNORE").write_text("")
    return ws


def run(*args: str, cwd: Path, monkeypatch) -> tuple[int, str, str]:
    monkeypatch.chdir(cwd)
    result = CliRunner().invoke(cli, list(args))
    if result.exception and not isinstance(result.exception, SystemExit):
        raise result.exception
    return result.exit_code, result.stdout, result.stderr


def checked_paths(out: str) -> list[str]:
    return sorted({p["path"] for p in json.loads(out)["problems"]})


def test_validate_from_the_workspace_root_checks_each_source_file_once(workspace, monkeypatch):
    code, out, err = run("validate", ".", "--format", "json", cwd=workspace,
                         monkeypatch=monkeypatch)
    report = json.loads(out)
    assert err == ""
    # rrbot.xacro (expanded: its own package found), materials.xacro and the stale rrbot.xml;
    # none of the copies in build/ and install/.
    assert report["summary"]["files"] == 3
    assert all(p["path"].startswith("src/") for p in report["problems"])
    # The stale rrbot.xml names interfaces only on its actuators: ros_control skips such joints,
    # but its loader is gazebo_ros_control (libgazebo_ros_control.so), which takes the
    # actuator's interface with a warning (default_robot_hw_sim.cpp initSim): warnings only.
    assert [(p["code"], p["severity"]) for p in report["problems"]] == [
        ("TX301", "warning"), ("TX301", "warning")]
    assert code == 0


def test_the_package_finds_itself_without_flags(workspace, monkeypatch):
    xacro = workspace / "src" / PACKAGE / "urdf" / "rrbot.xacro"
    code, out, err = run("show", "--format", "json", str(xacro), cwd=workspace.parent,
                         monkeypatch=monkeypatch)
    assert (code, err) == (0, "")
    assert [t["name"] for t in json.loads(out)["transmissions"]] == ["tran1", "tran2"]


def test_a_package_only_installed_is_found_through_ament_prefix_path(tmp_path, workspace,
                                                                    monkeypatch):
    shutil.rmtree(workspace / "src")
    user = tmp_path / "elsewhere" / "robot.urdf.xacro"
    user.parent.mkdir()
    user.write_text(f"""<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="$(find {PACKAGE})/urdf/materials.xacro"/>
  <transmission name="t">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="j"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>
    <actuator name="m"><mechanicalReduction>10</mechanicalReduction></actuator>
  </transmission>
</robot>
""")
    code, _, err = run("show", str(user), cwd=tmp_path, monkeypatch=monkeypatch)
    assert code == 2
    assert f"package '{PACKAGE}' not found (looked in: AMENT_PREFIX_PATH (unset);" in err
    monkeypatch.setenv("AMENT_PREFIX_PATH", str(workspace / "install"))
    code, out, err = run("show", "--format", "json", str(user), cwd=tmp_path,
                         monkeypatch=monkeypatch)
    assert (code, err) == (0, "")
    assert [t["name"] for t in json.loads(out)["transmissions"]] == ["t"]


def test_ros_package_path_and_cmake_prefix_path(workspace):
    elsewhere = str(workspace.parent / "nowhere.xacro")
    with pytest.MonkeyPatch.context() as mp:
        mp.setenv("ROS_PACKAGE_PATH", str(workspace / "src"))
        assert find_package(PACKAGE, near=elsewhere) == str(workspace / "src" / PACKAGE)
    with pytest.MonkeyPatch.context() as mp:
        mp.setenv("CMAKE_PREFIX_PATH", str(workspace / "install"))
        assert find_package(PACKAGE, near=elsewhere) == str(
            workspace / "install" / "share" / PACKAGE)


def test_not_found_lists_where_it_looked(workspace):
    near = str(workspace / "src" / PACKAGE / "urdf" / "rrbot.xacro")
    with pytest.raises(PackageNotFound) as caught:
        find_package("missing_pkg", near=near, pkg_dirs=(str(workspace / "install"),))
    message = str(caught.value)
    assert message.startswith("package 'missing_pkg' not found (looked in: --pkg-dir ")
    assert f"the enclosing package '{PACKAGE}'" in message
    assert f"the packages below {workspace / 'src'}" in message
    assert message.endswith("give --pkg-dir DIR or --pkg-path missing_pkg:=DIR")


def test_a_neighbour_package_of_the_workspace_is_found(workspace):
    other = workspace / "src" / "other_robot"
    (other / "urdf").mkdir(parents=True)
    (other / "package.xml").write_text("<package><name>other_robot</name></package>")
    near = str(other / "urdf" / "robot.xacro")
    assert find_package(PACKAGE, near=near) == str(workspace / "src" / PACKAGE)


def test_relative_pkg_dir_is_taken_from_the_current_folder(tmp_path, workspace, monkeypatch):
    user = tmp_path / "deep" / "down" / "robot.urdf.xacro"
    user.parent.mkdir(parents=True)
    user.write_text(f"""<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="$(find {PACKAGE})/urdf/materials.xacro"/>
</robot>
""")
    code, _, err = run("show", "--pkg-dir", "ws/src", str(user), cwd=tmp_path,
                       monkeypatch=monkeypatch)
    assert (code, err) == (0, "")
    code, _, err = run("show", "--pkg-path", f"{PACKAGE}:=ws/install/share/{PACKAGE}",
                       str(user), cwd=tmp_path, monkeypatch=monkeypatch)
    assert (code, err) == (0, "")


ROBOT = """<robot name="r">
  <transmission name="t">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="j"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>
    <actuator name="m"><mechanicalReduction>0</mechanicalReduction></actuator>
  </transmission>
</robot>
"""


@pytest.fixture
def repo(tmp_path) -> Path:
    """A repository with robots in several places and a .gitignore."""
    (tmp_path / ".git").mkdir()
    for relative in ("robots/a.urdf", "robots/generated/b.urdf", "vendor/c.urdf",
                     "robots/tmp.urdf", "test/d.urdf"):
        path = tmp_path / relative
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(ROBOT)
    (tmp_path / ".gitignore").write_text("vendor/\n")
    (tmp_path / "robots" / ".gitignore").write_text("tmp.urdf\n")
    return tmp_path


def files_checked(*args: str, cwd: Path, monkeypatch) -> list[str]:
    code, out, err = run("validate", "--format", "json", *args, cwd=cwd, monkeypatch=monkeypatch)
    assert err == ""
    return checked_paths(out)


def test_gitignore_is_respected_in_folder_walks(repo, monkeypatch):
    assert files_checked(".", cwd=repo, monkeypatch=monkeypatch) == [
        "robots/a.urdf", "robots/generated/b.urdf", "test/d.urdf"]
    assert files_checked(".", "--no-respect-gitignore", cwd=repo, monkeypatch=monkeypatch) == [
        "robots/a.urdf", "robots/generated/b.urdf", "robots/tmp.urdf", "test/d.urdf",
        "vendor/c.urdf"]


def test_a_file_named_on_the_command_line_is_always_checked(repo, monkeypatch):
    assert files_checked("vendor/c.urdf", "--exclude", "vendor/", cwd=repo,
                         monkeypatch=monkeypatch) == ["vendor/c.urdf"]


def test_exclude_patterns_from_the_command_line_and_the_configuration(repo, monkeypatch):
    (repo / ".txtool.toml").write_text('exclude = ["generated/"]\nextend-exclude = ["test/"]\n')
    assert files_checked(".", cwd=repo, monkeypatch=monkeypatch) == ["robots/a.urdf"]
    # --exclude replaces the configuration's exclude; its extend-exclude stays
    assert files_checked(".", "--exclude", "a.urdf", cwd=repo, monkeypatch=monkeypatch) == [
        "robots/generated/b.urdf"]
    code, out, err = run("validate", ".", "--extend-exclude", "robots/", cwd=repo,
                         monkeypatch=monkeypatch)
    assert (code, out) == (2, "")  # everything excluded: a CI step must not pass silently
    assert "leaving out ignored and excluded ones" in err


def test_per_file_ignores(repo, monkeypatch):
    (repo / ".txtool.toml").write_text('[per-file-ignores]\n"test/*.urdf" = ["TX106"]\n')
    assert files_checked(".", cwd=repo, monkeypatch=monkeypatch) == [
        "robots/a.urdf", "robots/generated/b.urdf"]


def test_per_file_ignores_with_an_unknown_code_is_a_configuration_error(repo, monkeypatch):
    (repo / ".txtool.toml").write_text('[per-file-ignores]\n"test/*.urdf" = ["TX999"]\n')
    code, out, err = run("validate", ".", cwd=repo, monkeypatch=monkeypatch)
    assert (code, out) == (2, "")
    assert "key 'per-file-ignores.test/*.urdf'" in err and "TX999" in err


def test_per_file_xacro_args(tmp_path, monkeypatch):
    for name in ("left.urdf.xacro", "right.urdf.xacro"):
        (tmp_path / name).write_text("""<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:arg name="ratio" default="1"/>
  <transmission name="t">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="j"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>
    <actuator name="m"><mechanicalReduction>$(arg ratio)</mechanicalReduction></actuator>
  </transmission>
</robot>
""")
    (tmp_path / ".txtool.toml").write_text(
        '[per-file-xacro-args."left.urdf.xacro"]\nratio = "0"\n')
    assert files_checked(".", cwd=tmp_path, monkeypatch=monkeypatch) == ["left.urdf.xacro"]
