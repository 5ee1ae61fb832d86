"""Nothing lost: ``convert -o``, ``convert -o INPUT --write``, ``migrate --write`` and
``schema -o`` replace a file atomically, or leave it byte for byte as it was."""

from __future__ import annotations

import errno
import os
import shutil
import stat
import tempfile
from collections.abc import Callable
from pathlib import Path

import pytest
from click.testing import CliRunner

from tests.corpus import corpus_files
from txtool.cli import cli
from txtool.io.xmlio import write_atomic

# Named, not the default placeholder (which a written conversion points out): what these
# tests check is elsewhere.
MOCK = "mock_components/GenericSystem"

FIXTURES = Path(__file__).resolve().parents[2] / "fixtures"
DEMO = (FIXTURES / "demo_robot.urdf").read_bytes()
ROBOT = b"""\
<?xml version="1.0"?>
<robot name='arm'>
  <link name='base' />
  <transmission name="elbow_trans" type="SimpleTransmission">
    <joint name="elbow"/>
    <actuator name="elbow_motor">
      <hardwareInterface>EffortJointInterface</hardwareInterface>
      <mechanicalReduction>50</mechanicalReduction>
    </actuator>
  </transmission>
</robot>
"""
XACRO = b"""\
<?xml version="1.0"?>
<robot name="arm" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="ratio" value="50"/>
  <link name="base"/>
  <transmission name="elbow_trans">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="elbow">
      <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
    </joint>
    <actuator name="elbow_motor"><mechanicalReduction>${ratio}</mechanicalReduction></actuator>
  </transmission>
</robot>
"""
OLD_OUTPUT = b"<robot name='previous output'/>\n"

Run = Callable[..., tuple[int, str, str]]


@pytest.fixture
def run(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Run:
    """Run ``txtool ARGS`` in ``tmp_path``; (exit code, stdout, stderr)."""
    monkeypatch.chdir(tmp_path)
    monkeypatch.delenv("TXTOOL_NO_XACRO", raising=False)

    def invoke(*args: str) -> tuple[int, str, str]:
        result = CliRunner().invoke(cli, list(args), catch_exceptions=False)
        return result.exit_code, result.stdout, result.stderr

    return invoke


def _convert_to_other(folder: Path) -> tuple[list[str], Path]:
    (folder / "demo.urdf").write_bytes(DEMO)
    (folder / "out.urdf").write_bytes(OLD_OUTPUT)
    return ["convert", "demo.urdf", "--to", "ros2-p2", "--hardware-plugin", MOCK, "-o", "out.urdf"], folder / "out.urdf"


def _convert_in_place(folder: Path) -> tuple[list[str], Path]:
    (folder / "demo.urdf").write_bytes(DEMO)
    return (["convert", "demo.urdf", "--to", "ros2-p2", "--hardware-plugin", MOCK, "-o", "demo.urdf", "--write"],
            folder / "demo.urdf")


def _migrate(folder: Path) -> tuple[list[str], Path]:
    (folder / "robot.urdf").write_bytes(ROBOT)
    return ["migrate", "--write", "robot.urdf"], folder / "robot.urdf"


def _schema(folder: Path) -> tuple[list[str], Path]:
    (folder / "schema.json").write_bytes(b"{}\n")
    return ["schema", "-o", "schema.json"], folder / "schema.json"


WRITERS = {
    "convert -o": _convert_to_other,
    "convert --write": _convert_in_place,
    "migrate --write": _migrate,
    "schema -o": _schema,
}


def _failure(writer: str, target: Path, reason: str) -> str:
    """What stderr says when ``target`` could not be written."""
    line = f"txtool: {target.name}: cannot write: {reason}\n"
    return line + "1 file(s) could not be read or written\n" if writer == "migrate --write" else line


def _snapshot(folder: Path) -> dict[str, bytes]:
    return {p.name: p.read_bytes() for p in sorted(folder.iterdir())}


@pytest.mark.parametrize("writer", WRITERS)
@pytest.mark.parametrize("mode", [0o640, 0o755])
def test_a_replaced_file_keeps_its_mode(run, tmp_path, writer, mode):
    args, target = WRITERS[writer](tmp_path)
    before = target.read_bytes()
    target.chmod(mode)
    code, _, err = run(*args)
    assert code == 0, err
    assert target.read_bytes() != before
    assert stat.S_IMODE(target.stat().st_mode) == mode
    assert not [p.name for p in tmp_path.iterdir() if p.name.startswith(".txtool-")]


@pytest.mark.parametrize("writer", WRITERS)
@pytest.mark.parametrize("broken", ["replace", "fsync"])
def test_a_failure_before_the_rename_leaves_the_original_intact(run, tmp_path, monkeypatch,
                                                                writer, broken):
    args, target = WRITERS[writer](tmp_path)
    before = _snapshot(tmp_path)

    def fail(*_: object) -> None:
        raise OSError(errno.EIO, "Input/output error")

    monkeypatch.setattr(os, broken, fail)
    assert run(*args) == (2, "", _failure(writer, target, "Input/output error"))
    assert _snapshot(tmp_path) == before  # same bytes, and no temporary file left


@pytest.mark.parametrize("writer", WRITERS)
def test_no_temporary_file_is_a_one_line_error(run, tmp_path, monkeypatch, writer):
    args, target = WRITERS[writer](tmp_path)
    before = _snapshot(tmp_path)

    def full(*_: object, **__: object) -> None:
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(tempfile, "mkstemp", full)
    assert run(*args) == (2, "", _failure(writer, target, "No space left on device"))
    assert _snapshot(tmp_path) == before


@pytest.mark.parametrize("writer", WRITERS)
@pytest.mark.parametrize("step", ["create the temporary file", "rename it over the target"])
def test_a_read_only_folder_is_a_one_line_error(run, tmp_path, monkeypatch, writer, step):
    """A folder the user may not write into refuses the temporary file, and a sticky folder
    refuses the rename over another user's file. Both are injected: root writes anywhere, and
    CI runs as root."""
    args, target = WRITERS[writer](tmp_path)
    before = _snapshot(tmp_path)

    def denied(*_: object, **__: object) -> None:
        raise PermissionError(errno.EACCES, "Permission denied")

    if step.startswith("create"):
        monkeypatch.setattr(tempfile, "mkstemp", denied)
    else:
        monkeypatch.setattr(os, "replace", denied)
    assert run(*args) == (2, "", _failure(writer, target, "Permission denied"))
    assert _snapshot(tmp_path) == before  # same bytes, and no temporary file left


@pytest.mark.parametrize("writer", WRITERS)
def test_an_interrupt_while_writing_leaves_the_original_and_no_temporary_file(
        run, tmp_path, monkeypatch, writer):
    args, _ = WRITERS[writer](tmp_path)
    before = _snapshot(tmp_path)

    def interrupt(*_: object) -> None:
        raise KeyboardInterrupt

    monkeypatch.setattr(os, "fsync", interrupt)
    code, out, _ = run(*args)
    assert code != 0 and out == ""
    assert _snapshot(tmp_path) == before


@pytest.mark.parametrize("umask", [0o022, 0o077, 0o002])
@pytest.mark.parametrize("args", [
    ["convert", "demo.urdf", "--to", "ros2-p2", "--hardware-plugin", MOCK, "-o", "new.urdf"],
    ["schema", "-o", "new.urdf"],
])
def test_a_new_output_file_gets_the_umask_mode(run, tmp_path, args, umask):
    (tmp_path / "demo.urdf").write_bytes(DEMO)
    previous = os.umask(umask)
    try:
        assert run(*args)[0] == 0
    finally:
        os.umask(previous)
    assert stat.S_IMODE((tmp_path / "new.urdf").stat().st_mode) == 0o666 & ~umask


def test_convert_writes_through_a_symbolic_link(run, tmp_path):
    (tmp_path / "real").mkdir()
    target = tmp_path / "real" / "demo.urdf"
    target.write_bytes(DEMO)
    link = tmp_path / "demo.urdf"
    link.symlink_to(Path("real") / "demo.urdf")
    assert run("convert", "demo.urdf", "--to", "ros2-p2", "--hardware-plugin", MOCK, "-o", "demo.urdf", "--write") == (
        0, "", "")
    assert link.is_symlink() and os.readlink(link) == str(Path("real") / "demo.urdf")
    assert b"<ros2_control" in target.read_bytes()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["demo.urdf", "real"]


SPELLINGS = {
    "dot": lambda folder: "./demo.urdf",
    "absolute": lambda folder: str(folder / "demo.urdf"),
    "detour": lambda folder: "sub/../demo.urdf",
    "symlink": lambda folder: _symlink(folder),
    "hard link": lambda folder: _hard_link(folder),
}


def _symlink(folder: Path) -> str:
    (folder / "alias.urdf").symlink_to("demo.urdf")
    return "alias.urdf"


def _hard_link(folder: Path) -> str:
    os.link(folder / "demo.urdf", folder / "hard.urdf")
    return "hard.urdf"


@pytest.mark.parametrize("spelling", SPELLINGS)
def test_output_naming_the_input_needs_write(run, tmp_path, spelling):
    (tmp_path / "demo.urdf").write_bytes(DEMO)
    (tmp_path / "sub").mkdir()
    output = SPELLINGS[spelling](tmp_path)
    args = ["convert", "demo.urdf", "--to", "ros2-p2", "--hardware-plugin", MOCK, "-o", output]
    assert run(*args) == (
        2, "", f"txtool: {output}: is the input file; add --write to convert it in place\n")
    assert (tmp_path / "demo.urdf").read_bytes() == DEMO
    if spelling == "hard link":  # a rename would give the output name a file of its own
        assert run(*args, "--write") == (2, "", (
            f"txtool: {output}: has 2 hard links; replacing it would leave the other names "
            "with the old text, so it is not written (copy the file to break the link)\n"))
        assert (tmp_path / "demo.urdf").read_bytes() == DEMO
        return
    assert run(*args, "--write") == (0, "", "")
    assert b"<ros2_control" in Path(os.path.realpath(tmp_path / output)).read_bytes()


def test_a_xacro_file_is_not_replaced_by_its_expansion(run, tmp_path):
    path = tmp_path / "arm.urdf.xacro"
    path.write_bytes(XACRO)
    args = ["convert", "arm.urdf.xacro", "--to", "ros2-p2", "--hardware-plugin", MOCK, "-o", "arm.urdf.xacro", "--write"]
    assert run(*args) == (2, "", (
        "txtool: arm.urdf.xacro: converting a xacro file in place would replace it with its "
        "expansion; use 'txtool migrate --write --to TARGET' (or --no-xacro)\n"))
    assert path.read_bytes() == XACRO
    code, out, _ = run(*args, "--no-xacro")
    assert (code, out) == (0, "")
    converted = path.read_bytes()
    assert b"<mechanical_reduction>${ratio}</mechanical_reduction>" in converted
    assert b'<xacro:property name="ratio" value="50"/>' in converted


def _state(paths: list[Path]) -> list[tuple[bytes, int, int]]:
    return [(p.read_bytes(), p.stat().st_mtime_ns, p.stat().st_ino) for p in paths]


def _migrate_twice(run: Run, paths: list[Path], *options: str) -> None:
    """A first ``--write``, then a second that touches nothing, then a ``--check`` that passes."""
    names = [str(p) for p in paths]
    code, out, err = run("migrate", "--write", *options, *names)
    assert (code, out) == (0, ""), err
    for path in paths:  # an unchanged file keeps its time: any rewrite would show
        os.utime(path, ns=(1_000_000_000_000_000_000, 1_000_000_000_000_000_000))
    before = _state(paths)
    code, out, err = run("migrate", "--write", *options, *names)
    assert (code, out) == (0, "")
    assert err.endswith(f"nothing to do ({len(paths)} file(s) checked)\n")
    assert _state(paths) == before
    code, out, err = run("migrate", "--check", *options, *names)
    assert (code, out) == (0, "")
    assert err.endswith(f"nothing to do ({len(paths)} file(s) checked)\n")


@pytest.mark.parametrize("options", [(), ("--to", "ros2-p2", "--hardware-plugin", MOCK, "--allow-lossy"),
                                     ("--to", "ros1", "--allow-lossy")])
def test_migrating_the_fixtures_twice_changes_nothing_the_second_time(run, tmp_path, options):
    shutil.copytree(FIXTURES, tmp_path / "fixtures")
    _migrate_twice(run, sorted(p for p in (tmp_path / "fixtures").rglob("*") if p.is_file()),
                   *options)


def test_migrating_the_corpus_twice_changes_nothing_the_second_time(run, tmp_path):
    copies = []
    for original in corpus_files():
        copy = tmp_path / original.name
        shutil.copyfile(original, copy)
        copies.append(copy)
    _migrate_twice(run, copies)


ENCODED = {
    "CR line ends": b'<?xml version="1.0"?>\r<robot name="arm">\r  <link name="a"/>\r</robot>\r',
    "UTF-8 BOM": b"\xef\xbb\xbf<robot name='arm'/>\r\n",
    "UTF-16 LE BOM": '<?xml version="1.0" encoding="UTF-16"?>\n<robot/>\n'.encode("utf-16"),
    "UTF-16 BE": '<?xml version="1.0" encoding="UTF-16BE"?><robot/>'.encode("utf-16-be"),
    "UTF-32 BOM": "\ufeff<robot name='é'/>\n".encode("utf-32-le"),
}


@pytest.mark.parametrize("name", ENCODED)
def test_the_writer_passes_every_byte_through(tmp_path, name):
    """The writer changes no byte: line ends, byte-order marks and encodings are the caller's."""
    path = tmp_path / "robot.urdf"
    path.write_bytes(b"<robot/>\n")
    write_atomic(str(path), ENCODED[name])
    assert path.read_bytes() == ENCODED[name]


@pytest.mark.parametrize("option", ["--csv", "--plot"])
def test_an_interrupted_simulate_leaves_no_file_and_no_verdict(run, tmp_path, monkeypatch,
                                                              option):
    pytest.importorskip("pinocchio")
    if option == "--plot":
        pytest.importorskip("matplotlib")
    (tmp_path / "demo.urdf").write_bytes(DEMO)
    output = "series.csv" if option == "--csv" else "plot.png"

    def interrupt(*_: object) -> None:
        raise KeyboardInterrupt

    real_fsync = os.fsync
    monkeypatch.setattr(os, "fsync", interrupt)
    assert run("simulate", "demo.urdf", "--duration", "0.2", option, output) == (
        130, "", "txtool: interrupted\n")  # no verdict printed before the file is written
    assert sorted(p.name for p in tmp_path.iterdir()) == ["demo.urdf"]
    monkeypatch.setattr(os, "fsync", real_fsync)
    code, out, _ = run("simulate", "demo.urdf", "--duration", "0.2", option, output)
    assert code in (0, 1) and ("PASS" in out or "FAIL" in out)
    assert (tmp_path / output).stat().st_size > 0


def test_convert_write_refuses_a_file_edited_during_the_run(tmp_path, monkeypatch):
    """Issue: convert --write must notice, as migrate does, that the file changed meanwhile."""
    from click.testing import CliRunner

    from txtool.cli import cli
    from txtool.transform import convert

    robot = tmp_path / "robot.urdf"
    original = (Path(__file__).resolve().parents[2] / "fixtures" / "demo_robot.urdf").read_text()
    robot.write_text(original)
    edited = original.replace("<robot", "<!-- edited meanwhile -->\n<robot", 1)
    real = convert.convert_source

    def edit_meanwhile(*args, **kwargs):
        result = real(*args, **kwargs)
        robot.write_text(edited)
        return result

    monkeypatch.setattr(convert, "convert_source", edit_meanwhile)
    result = CliRunner().invoke(cli, ["convert", str(robot), "--to", "ros2-p2", "--hardware-plugin", MOCK, "-o", str(robot),
                                      "--write"])
    assert result.exit_code == 2
    assert result.stderr.endswith(
        f"txtool: {robot}: changed on disk during the conversion; not written\n")
    assert robot.read_text() == edited
    assert [p.name for p in tmp_path.iterdir()] == ["robot.urdf"]  # no temporary file left
