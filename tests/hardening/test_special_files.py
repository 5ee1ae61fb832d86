"""Devices, FIFOs and sockets are refused before anything reads or replaces them.

``/dev/zero`` never ends and a FIFO blocks its reader until someone writes: read, either would
eat memory or hang the run. Given directly, through a symbolic link, found in a folder walk or
included by xacro, such a path is one line and exit 2; ``-o`` onto one leaves it as it was.
Each run has a timeout: a regression hangs no CI job.
"""

from __future__ import annotations

import os
import socket
import stat
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path

import pytest
from click.testing import CliRunner

from txtool.cli import cli
from txtool.io import xacro as xacro_support

ROOT = Path(__file__).resolve().parents[2]
DEMO = (ROOT / "fixtures" / "demo_robot.urdf").read_bytes()
CHARACTER = "is a character device, not a regular file; txtool reads only regular files (or '-')"
FIFO = "is a named pipe (FIFO), not a regular file; txtool reads only regular files (or '-')"
SOCKET = "is a socket, not a regular file; txtool reads only regular files (or '-')"


def txtool(*args: str, cwd: Path) -> tuple[int, str, str]:
    """The real command in a fresh process, given 60 s (today's hang would time out)."""
    result = subprocess.run([sys.executable, "-m", "txtool", *args], capture_output=True,
                            text=True, timeout=60, cwd=cwd,
                            env={**os.environ, "PYTHONPATH": str(ROOT)})
    return result.returncode, result.stdout, result.stderr


@pytest.fixture
def specials(tmp_path: Path) -> Iterator[Path]:
    """A folder with a robot, a FIFO, a socket and links to /dev/zero and /dev/urandom."""
    folder = tmp_path / "urdf"
    folder.mkdir()
    (folder / "arm.urdf").write_bytes(DEMO)
    os.mkfifo(folder / "pipe.urdf")
    (folder / "zero.urdf").symlink_to("/dev/zero")
    (folder / "noise.urdf.xacro").symlink_to("/dev/urandom")
    server = socket.socket(socket.AF_UNIX)
    server.bind(str(folder / "sock.urdf"))
    yield folder
    server.close()


@pytest.mark.parametrize(("name", "reason"), [
    ("pipe.urdf", FIFO), ("zero.urdf", CHARACTER), ("noise.urdf.xacro", CHARACTER),
    ("sock.urdf", SOCKET),
])
@pytest.mark.parametrize("command", [["show"], ["convert", "--to", "ros1"], ["roundtrip"],
                                     ["migrate", "--check"],
                                     ["map", "-t", "arm_trans", "--to", "actuator",
                                      "--position", "1"]])
def test_a_special_file_is_one_line_and_exit_2(specials, name, reason, command):
    code, out, err = txtool(*command, f"urdf/{name}", cwd=specials.parent)
    assert (code, out) == (2, "")
    assert err.splitlines()[0] == f"txtool: urdf/{name}: {reason}"


def test_dev_zero_itself_is_refused(tmp_path):
    assert txtool("show", "/dev/zero", cwd=tmp_path) == (2, "", f"txtool: /dev/zero: {CHARACTER}\n")


def test_a_folder_walk_refuses_the_special_files_it_finds(specials):
    os.mkfifo(specials / "pipe.xml")  # an .xml is opened to read its root: never a FIFO
    code, out, err = txtool("validate", "urdf", cwd=specials.parent)
    assert code == 2
    assert out == "4 files could not be read; no findings in the 1 file read.\n"
    assert sorted(err.splitlines()) == sorted([
        f"txtool: urdf/noise.urdf.xacro: {CHARACTER}",
        f"txtool: urdf/pipe.urdf: {FIFO}",
        f"txtool: urdf/sock.urdf: {SOCKET}",
        f"txtool: urdf/zero.urdf: {CHARACTER}",
    ])


def test_a_xacro_include_of_a_special_file_is_refused(specials):
    (specials / "robot.urdf.xacro").write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:include filename="pipe.urdf"/>\n</robot>\n')
    code, out, err = txtool("show", "urdf/robot.urdf.xacro", cwd=specials.parent)
    assert (code, out) == (2, "")
    assert err == (f"txtool: urdf/robot.urdf.xacro:1: xacro: {specials / 'pipe.urdf'}:1: "
                   f"{FIFO}\n")


def test_what_a_xacro_expansion_reads_is_bounded_in_all(tmp_path, monkeypatch):
    """Each file is under the limit; the same one included again and again is not."""
    part = tmp_path / "part.xacro"
    part.write_text('<robot xmlns:xacro="http://www.ros.org/wiki/xacro">'
                    + "<link name='x'/>" * 400 + "</robot>\n")  # 6.4 KB
    top = tmp_path / "robot.urdf.xacro"
    top.write_text('<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                   + '  <xacro:include filename="part.xacro"/>\n' * 4 + "</robot>\n")
    monkeypatch.setattr(xacro_support, "MAX_READ", 20_000)
    monkeypatch.delenv("TXTOOL_NO_XACRO", raising=False)
    result = CliRunner().invoke(cli, ["show", str(top)], catch_exceptions=False)
    assert (result.exit_code, result.stdout) == (2, "")
    assert result.stderr == (
        f"txtool: {top}:1: xacro: {part}:1: xacro would read more than 20000 bytes in all "
        "(the top file and its includes; a safety limit)\n")
    monkeypatch.setattr(xacro_support, "MAX_READ", 40_000)
    assert CliRunner().invoke(cli, ["show", str(top)]).exit_code == 0


# Never a link to a real device here: were the refusal broken, a root run would replace it.
@pytest.mark.parametrize(("target", "kind"), [
    ("pipe.urdf", "a named pipe (FIFO)"), ("sock.urdf", "a socket"),
])
@pytest.mark.parametrize("writer", ["convert", "schema"])
def test_output_onto_a_special_file_is_refused_and_leaves_it(specials, target, kind, writer):
    path = specials / target
    before = (os.lstat(path), os.stat(path))
    args = (["convert", "urdf/arm.urdf", "--to", "ros2-p2"] if writer == "convert"
            else ["schema"])
    code, out, err = txtool(*args, "-o", f"urdf/{target}", cwd=specials.parent)
    assert (code, out, err) == (2, "", f"txtool: urdf/{target}: is {kind}, not a regular "
                                       "file; txtool writes only regular files\n")
    assert (os.lstat(path), os.stat(path)) == before
    assert not [p for p in specials.iterdir() if p.name.startswith(".txtool-")]


@pytest.mark.skipif(os.geteuid() != 0, reason="making a device node needs root")
@pytest.mark.parametrize("name", ["null", "link.urdf"])
@pytest.mark.parametrize("writer", [["convert", "arm.urdf", "--to", "ros2-p2"], ["schema"]])
def test_output_onto_a_device_node_keeps_the_node(tmp_path, writer, name):
    """As root, a rename would replace the node with a regular file (a private copy of
    /dev/null: never the real one, which a broken refusal would destroy)."""
    (tmp_path / "arm.urdf").write_bytes(DEMO)
    node = tmp_path / "null"
    os.mknod(node, stat.S_IFCHR | 0o666, os.makedev(1, 3))
    (tmp_path / "link.urdf").symlink_to("null")
    reason = ("is a symbolic link; txtool writes a new output only to a regular file or a new "
              "name, never through a link (remove the link or name another file)"
              if name == "link.urdf" else
              "is a character device, not a regular file; txtool writes only regular files")
    assert txtool(*writer, "-o", name, cwd=tmp_path) == (2, "", f"txtool: {name}: {reason}\n")
    assert stat.S_ISCHR(os.lstat(node).st_mode) and os.path.islink(tmp_path / "link.urdf")
