"""A pull request names the files in its tree: outputs keep off what it plants there.

A workflow runs ``txtool validate . --output report.txt`` on a checkout of the pull
request; the request may hold ``report.txt`` as a symbolic link to a file of the runner, or make
an output's name one of the robot descriptions read. A report, table or plot is written only to
a regular file or a new name, never over an input; an input rewritten in place is replaced only
if nobody changed it meanwhile; what a killed run left behind is cleaned up.
"""

from __future__ import annotations

import os
import time
from collections.abc import Callable
from pathlib import Path

import pytest

from tests.hardening.test_atomic_writes import DEMO, ROBOT

# Named, not the default placeholder (which a written conversion points out): what these
# tests check is elsewhere.
MOCK = "mock_components/GenericSystem"

Run = Callable[..., tuple[int, str, str]]
SECRET = b"export TOKEN=runner-secret\n"
LINK_REFUSED = ("is a symbolic link; txtool writes a new output only to a regular file or a new "
                "name, never through a link (remove the link or name another file)")
INPUT_REFUSED = "is an input of this command; its output is not written over it"




WRITERS = {
    "validate --output": ["validate", "robot.urdf", "--output"],
    "convert -o": ["convert", "robot.urdf", "--to", "ros2-p2", "--hardware-plugin", MOCK, "-o"],
    "convert --to bb -o": ["convert", "robot.urdf", "--to", "bb", "--allow-lossy", "-o"],
    "schema -o": ["schema", "-o"],
}


@pytest.mark.parametrize("writer", WRITERS)
def test_a_planted_link_at_the_output_is_not_written_through(run, tmp_path, writer):
    (tmp_path / "robot.urdf").write_bytes(DEMO)
    victim = tmp_path / "home" / ".bashrc"
    victim.parent.mkdir()
    victim.write_bytes(SECRET)
    (tmp_path / "report.txt").symlink_to(victim)
    code, _, err = run(*WRITERS[writer], "report.txt")
    assert (code, err.splitlines()[-1]) == (2, f"txtool: report.txt: {LINK_REFUSED}")
    assert victim.read_bytes() == SECRET
    assert os.readlink(tmp_path / "report.txt") == str(victim)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["home", "report.txt", "robot.urdf"]


def _hard_link(folder: Path) -> str:
    os.link(folder / "robot.urdf", folder / "hard.urdf")
    return "hard.urdf"


SPELLINGS = {
    "the same name": lambda folder: "robot.urdf",
    "a detour": lambda folder: "sub/../robot.urdf",
    "an absolute path": lambda folder: str(folder / "robot.urdf"),
    "a hard link": _hard_link,
}


@pytest.mark.parametrize("spelling", SPELLINGS)
def test_a_report_never_replaces_the_robot_it_checks(run, tmp_path, spelling):
    (tmp_path / "robot.urdf").write_bytes(DEMO)
    (tmp_path / "sub").mkdir()
    output = SPELLINGS[spelling](tmp_path)
    assert run("validate", "robot.urdf", "--output", output) == (
        2, "", f"txtool: {output}: {INPUT_REFUSED}\n")
    assert (tmp_path / "robot.urdf").read_bytes() == DEMO


def test_a_report_never_replaces_a_robot_found_in_a_folder(run, tmp_path):
    (tmp_path / "urdf").mkdir()
    (tmp_path / "urdf" / "arm.urdf").write_bytes(ROBOT)
    (tmp_path / "urdf" / "old.urdf").write_bytes(DEMO)  # found too: any robot is kept
    for name, reason in (("urdf/arm.urdf", INPUT_REFUSED), ("urdf/old.urdf", INPUT_REFUSED)):
        assert run("validate", ".", "--output", name) == (2, "", f"txtool: {name}: {reason}\n")
    assert (tmp_path / "urdf" / "arm.urdf").read_bytes() == ROBOT
    assert (tmp_path / "urdf" / "old.urdf").read_bytes() == DEMO
    findings = run("validate", ".")[0]
    assert run("validate", ".", "--format", "sarif", "--output", "report.sarif") == (
        findings, "", "")
    assert (tmp_path / "report.sarif").read_bytes().startswith(b"{")


def test_a_report_is_not_written_over_another_robot_description(run, tmp_path):
    (tmp_path / "robot.urdf").write_bytes(DEMO)
    (tmp_path / "other.xacro").write_bytes(ROBOT)
    assert run("schema", "-o", "other.xacro") == (2, "", (
        "txtool: other.xacro: is a robot description (.xacro); txtool writes a report, table or "
        "plot only to a file of another kind\n"))
    assert (tmp_path / "other.xacro").read_bytes() == ROBOT


def test_simulate_does_not_write_its_table_over_the_robot(run, tmp_path):
    (tmp_path / "robot.urdf").write_bytes(DEMO)
    code, _, err = run("simulate", "robot.urdf", "--duration", "0.1", "--csv", "robot.urdf")
    assert (code, err) == (2, f"txtool: robot.urdf: {INPUT_REFUSED}\n")
    assert (tmp_path / "robot.urdf").read_bytes() == DEMO


def test_convert_does_not_overwrite_a_file_its_xacro_input_includes(run, tmp_path):
    (tmp_path / "arm.xacro").write_bytes(ROBOT.replace(
        b"<robot name='arm'>", b"<robot name='arm' xmlns:xacro='http://www.ros.org/wiki/xacro'>"))
    (tmp_path / "top.urdf.xacro").write_bytes(
        b"<robot name='top' xmlns:xacro='http://www.ros.org/wiki/xacro'>"
        b"<xacro:include filename='arm.xacro'/></robot>\n")
    code, out, err = run("convert", "top.urdf.xacro", "--to", "ros2-p2", "--hardware-plugin", MOCK, "-o", "arm.xacro")
    if code == 2 and "xacro" in err and INPUT_REFUSED not in err:
        pytest.skip(f"xacro is not expanded here: {err.strip()}")
    assert (code, out, err.splitlines()[-1]) == (2, "", f"txtool: arm.xacro: {INPUT_REFUSED}")
    assert (tmp_path / "arm.xacro").read_bytes().startswith(b"<?xml")


EDITED = b"<!-- an edit saved while txtool wrote -->\n"


@pytest.mark.parametrize(("args", "during"), [
    (["migrate", "--write", "--to", "ros2-p2", "--hardware-plugin", MOCK, "robot.urdf"], "migration"),
    (["convert", "robot.urdf", "--to", "ros2-p2", "--hardware-plugin", MOCK, "-o", "robot.urdf", "--write"], "conversion"),
])
def test_an_edit_saved_while_the_new_text_is_written_is_kept(run, tmp_path, monkeypatch, args,
                                                             during):
    """The file is compared with what was read, then the new text is written and flushed
    (which can take a while); an editor saving in that window must not lose its edit."""
    robot = tmp_path / "robot.urdf"
    robot.write_bytes(DEMO)
    real_fsync = os.fsync

    def save_meanwhile(handle: int) -> None:
        real_fsync(handle)
        if robot.read_bytes() == DEMO:  # the temporary file is being flushed: save now
            robot.write_bytes(EDITED + DEMO)

    monkeypatch.setattr(os, "fsync", save_meanwhile)
    code, out, err = run(*args)
    assert code == 2 and out == ""
    assert f"txtool: robot.urdf: changed on disk during the {during}; not written\n" in err
    assert robot.read_bytes() == EDITED + DEMO
    assert [p.name for p in tmp_path.iterdir()] == ["robot.urdf"]  # no temporary file left


def _age(path: Path, seconds: float) -> None:
    then = time.time() - seconds
    os.utime(path, (then, then), follow_symlinks=False)


def test_temporaries_a_killed_run_left_are_removed_and_nothing_else(run, tmp_path):
    (tmp_path / "robot.urdf").write_bytes(DEMO)
    left = tmp_path / ".txtool-k1ll3d_x.tmp"  # as tempfile.mkstemp names them
    fresh = tmp_path / ".txtool-runningx.tmp"  # another run, still writing
    kept = {
        ".txtool-notours.txt": b"x", ".txtool-short.tmp": b"x", "txtool-abcdefgh.tmp": b"x",
        "robot.urdf.bak": b"x",
    }
    left.write_bytes(b"half a robot")
    fresh.write_bytes(b"half a robot")
    for name, data in kept.items():
        (tmp_path / name).write_bytes(data)
    (tmp_path / ".txtool-linkedxx.tmp").symlink_to("robot.urdf")
    (tmp_path / "sub").mkdir()
    deeper = tmp_path / "sub" / ".txtool-deeperxx.tmp"
    deeper.write_bytes(b"x")
    for path in [left, *(tmp_path / name for name in kept), tmp_path / ".txtool-linkedxx.tmp",
                 deeper]:
        _age(path, 2 * 3600)
    _age(fresh, 60)
    assert run("convert", "robot.urdf", "--to", "ros2-p2", "--hardware-plugin", MOCK, "-o", "new.urdf") == (0, "", "")
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted([
        "robot.urdf", "new.urdf", fresh.name, *kept, ".txtool-linkedxx.tmp", "sub"])
    assert deeper.exists() and (tmp_path / "robot.urdf").read_bytes() == DEMO


@pytest.mark.parametrize(("output", "link"), [("reports/report.txt", "reports"),
                                              ("./reports/report.txt", "./reports"),
                                              ("reports/../report.txt", "reports")])
def test_a_planted_folder_link_in_a_relative_output_path_is_not_followed(run, tmp_path,
                                                                         output, link):
    """``reports -> /home/runner/.config`` in the checkout: the report is not written there
    (nor in its parent, where ``reports/..`` leads)."""
    (tmp_path / "robot.urdf").write_bytes(DEMO)
    home = tmp_path / "home"
    (home / ".config").mkdir(parents=True)
    (home / "report.txt").write_bytes(SECRET)
    (home / ".config" / "report.txt").write_bytes(SECRET)
    (tmp_path / "reports").symlink_to(home / ".config")
    code, out, err = run("validate", "robot.urdf", "--output", output)
    assert (code, out, err) == (2, "", (
        f"txtool: {output}: passes through the symbolic link {link}; txtool "
        "writes a new output named by a relative path only inside real folders (name a folder "
        "outside the checkout, or an absolute path)\n"))
    assert (home / "report.txt").read_bytes() == SECRET
    assert (home / ".config" / "report.txt").read_bytes() == SECRET
    assert not (tmp_path / "report.txt").exists()
