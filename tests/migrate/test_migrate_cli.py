"""``txtool migrate``: modes, exit codes, messages and what is written (exit code and output
asserted together)."""

from __future__ import annotations

import os
import stat

import pytest

ROBOT = """
<?xml version="1.0"?>
<robot name='arm'>
  <link name='base' />
  <!-- the elbow -->
  <transmission name="elbow_trans" type="SimpleTransmission">
    <joint name="elbow"/>
    <actuator name="elbow_motor">
      <hardwareInterface>EffortJointInterface</hardwareInterface>
      <mechanicalReduction>50</mechanicalReduction>
    </actuator>
  </transmission>
</robot>
"""

ROBOT_DIFF = """\
--- a/robot.urdf
+++ b/robot.urdf
@@ -2,10 +2,13 @@
 <robot name='arm'>
   <link name='base' />
   <!-- the elbow -->
-  <transmission name="elbow_trans" type="SimpleTransmission">
-    <joint name="elbow"/>
+  <transmission name="elbow_trans">
+    <type>transmission_interface/SimpleTransmission</type>
+    <joint name="elbow">
+      <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
+    </joint>
     <actuator name="elbow_motor">
-      <hardwareInterface>EffortJointInterface</hardwareInterface>
+      <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
       <mechanicalReduction>50</mechanicalReduction>
     </actuator>
   </transmission>
"""

ROBOT_FIXED = """\
<?xml version="1.0"?>
<robot name='arm'>
  <link name='base' />
  <!-- the elbow -->
  <transmission name="elbow_trans">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="elbow">
      <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
    </joint>
    <actuator name="elbow_motor">
      <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
      <mechanicalReduction>50</mechanicalReduction>
    </actuator>
  </transmission>
</robot>
"""

CLEAN = """
<robot name="arm">
  <transmission name="t">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="j"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>
    <actuator name="m"><mechanicalReduction>1</mechanicalReduction></actuator>
  </transmission>
</robot>
"""

PENDING = "would change robot.urdf (TX300 x1, TX301 x1, TX302 x1)\n1 file(s) would be changed\n"


@pytest.fixture(autouse=True)
def _in_tmp(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)


def test_diff_prints_a_unified_diff_and_exits_1(run, write):
    path = write("robot.urdf", ROBOT)
    assert run("migrate", "--diff", "robot.urdf") == (1, ROBOT_DIFF, PENDING)
    assert path.read_text() == ROBOT.lstrip("\n")  # --diff writes nothing


def test_a_walk_of_the_working_folder_names_files_without_dot_slash(run, write):
    """``migrate --diff .`` heads the diff ``a/src/robot.urdf``, as git does, not
    ``a/./src/robot.urdf``: a patch applies with ``-p1`` from the same folder."""
    write("src/robot.urdf", ROBOT)
    code, out, _ = run("migrate", "--diff", ".")
    assert code == 1
    assert out.startswith("--- a/src/robot.urdf\n+++ b/src/robot.urdf\n")
    assert run("migrate", "--diff", "./src/robot.urdf")[1] == out


def test_diff_applies_with_patch(run, write, tmp_path):
    import shutil
    import subprocess

    if shutil.which("patch") is None:
        pytest.skip("no patch program")
    path = write("robot.urdf", ROBOT)
    _, diff, _ = run("migrate", "--diff", "robot.urdf")
    subprocess.run(["patch", "-p1", "-s"], input=diff.encode(), cwd=tmp_path, check=True)
    assert path.read_text() == ROBOT_FIXED


def test_check_exits_1_when_changes_are_pending_and_writes_nothing(run, write):
    path = write("robot.urdf", ROBOT)
    assert run("migrate", "--check", "robot.urdf") == (1, "", PENDING)
    assert path.read_text() == ROBOT.lstrip("\n")


def test_check_exits_0_when_there_is_nothing_to_do(run, write):
    write("robot.urdf", CLEAN)
    assert run("migrate", "--check", "robot.urdf") == (
        0, "", "nothing to do (1 file(s) checked)\n")
    assert run("migrate", "--diff", "robot.urdf") == (
        0, "", "nothing to do (1 file(s) checked)\n")


def test_write_rewrites_then_a_second_run_finds_nothing(run, write):
    path = write("robot.urdf", ROBOT)
    assert run("migrate", "--write", "robot.urdf") == (
        0, "", "changed robot.urdf (TX300 x1, TX301 x1, TX302 x1)\n1 file(s) changed\n")
    assert path.read_text() == ROBOT_FIXED
    assert run("migrate", "--write", "robot.urdf") == (
        0, "", "nothing to do (1 file(s) checked)\n")
    assert run("migrate", "--check", "robot.urdf")[0] == 0
    assert path.read_text() == ROBOT_FIXED


def test_an_unchanged_file_is_never_rewritten(run, write):
    path = write("robot.urdf", CLEAN)
    os.utime(path, (1_000_000_000, 1_000_000_000))
    before = path.stat()
    assert run("migrate", "--write", "robot.urdf")[0] == 0
    after = path.stat()
    assert (after.st_mtime_ns, after.st_ino) == (before.st_mtime_ns, before.st_ino)


def test_write_keeps_the_file_mode(run, write):
    path = write("robot.urdf", ROBOT)
    path.chmod(0o640)
    assert run("migrate", "--write", "robot.urdf")[0] == 0
    assert stat.S_IMODE(path.stat().st_mode) == 0o640
    assert path.read_text() == ROBOT_FIXED
    assert [p.name for p in path.parent.iterdir()] == ["robot.urdf"]  # no temp file left


def test_a_symlink_is_written_through_to_its_target(run, write, tmp_path):
    target = write("real/robot.urdf", ROBOT)
    link = tmp_path / "robot.urdf"
    link.symlink_to(target)
    assert run("migrate", "--write", "robot.urdf")[0] == 0
    assert link.is_symlink() and os.readlink(link) == str(target)
    assert target.read_text() == ROBOT_FIXED


def test_exactly_one_mode_is_required(run, write):
    write("robot.urdf", ROBOT)
    for args in ([], ["--check", "--write"], ["--diff", "--check"]):
        code, out, err = run("migrate", *args, "robot.urdf")
        assert (code, out) == (2, "")
        assert "give exactly one of --check, --diff, --write" in err


def test_paths_are_required(run):
    code, out, err = run("migrate", "--check")
    assert (code, out) == (2, "")
    assert "Missing argument 'PATHS...'" in err


def test_standard_input_is_refused(run):
    assert run("migrate", "--check", "-") == (
        2, "", "txtool: -: migrate rewrites files in place; standard input is not supported\n")


def test_a_missing_file_is_one_line_and_exit_2(run, write):
    write("robot.urdf", ROBOT)
    assert run("migrate", "--check", "nope.urdf", "robot.urdf") == (
        2, "",
        "txtool: nope.urdf: no such file\n"
        "would change robot.urdf (TX300 x1, TX301 x1, TX302 x1)\n"
        "1 file(s) would be changed, 1 file(s) could not be read or written\n",
    )


def test_a_malformed_file_is_reported_and_skipped_and_the_others_are_written(run, write):
    write("robots/bad.urdf", '<robot name="r">\n  <transmission name="t">\n</robot>\n')
    good = write("robots/good.urdf", ROBOT)
    code, out, err = run("migrate", "--write", "robots")
    assert (code, out) == (2, "")
    lines = err.splitlines()
    assert lines[0].startswith("txtool: robots/bad.urdf:3:") and "mismatch" in lines[0]
    assert lines[1:] == [
        "changed robots/good.urdf (TX300 x1, TX301 x1, TX302 x1)",
        "1 file(s) changed, 1 file(s) could not be read or written",
    ]
    assert good.read_text() == ROBOT_FIXED


def test_folders_are_searched_like_validate_does(run, write):
    write("d/robot.urdf", ROBOT)
    write("d/sub/arm.urdf.xacro", ROBOT)
    write("d/frag.xml", '<transmission name="t" type="SimpleTransmission"><joint name="j"/>'
                        '<actuator name="m"/></transmission>\n')
    write("d/notes.xml", "<notes><transmission name='t' type='SimpleTransmission'/></notes>\n")
    write("d/robot.txt", ROBOT)
    write("d/.hidden/robot.urdf", ROBOT)
    assert run("migrate", "--check", "d") == (1, "", (
        "would change d/frag.xml (TX302 x1)\n"
        "would change d/robot.urdf (TX300 x1, TX301 x1, TX302 x1)\n"
        "would change d/sub/arm.urdf.xacro (TX300 x1, TX301 x1, TX302 x1)\n"
        "3 file(s) would be changed\n"
    ))


def test_select_and_ignore_choose_the_fixes(run, write):
    write("robot.urdf", ROBOT)
    code, out, err = run("migrate", "--diff", "--select", "TX302", "robot.urdf")
    assert code == 1
    assert "-    <joint name=\"elbow\"/>" not in out and "+    <type>" in out
    assert err == "would change robot.urdf (TX302 x1)\n1 file(s) would be changed\n"
    assert run("migrate", "--check", "--ignore", "TX300,TX301", "robot.urdf") == (
        1, "", "would change robot.urdf (TX302 x1)\n1 file(s) would be changed\n")
    assert run("migrate", "--check", "--ignore", "TX3", "robot.urdf") == (
        0, "", "nothing to do (1 file(s) checked)\n")


def test_an_unknown_code_is_a_usage_error_before_anything_is_read(run, write):
    path = write("robot.urdf", ROBOT)
    assert run("migrate", "--write", "--select", "TX999", "robot.urdf") == (
        2, "", "txtool: option '--select': unknown rule code 'TX999'\n")
    assert path.read_text() == ROBOT.lstrip("\n")


def test_the_configuration_file_is_honoured(run, write):
    write(".txtool.toml", 'ignore = ["TX300", "TX301"]\n')
    write("robot.urdf", ROBOT)
    assert run("migrate", "--check", "robot.urdf") == (
        1, "", "would change robot.urdf (TX302 x1)\n1 file(s) would be changed\n")
    write("other.toml", 'select = ["TX300"]\n')
    assert run("migrate", "--check", "--config", "other.toml", "robot.urdf") == (
        1, "", "would change robot.urdf (TX300 x1)\n1 file(s) would be changed\n")


def test_a_bad_configuration_stops_the_run_with_nothing_written(run, write):
    # The configuration is the root's (nested ones are passed over, see the next test).
    first = write("a/robot.urdf", ROBOT)
    write(".txtool.toml", 'selectt = ["TX300"]\n')
    path = write("b/robot.urdf", ROBOT)
    code, out, err = run("migrate", "--write", "a", "b")
    assert (code, out) == (2, "")
    assert err.startswith("txtool: ") and err.count("\n") == 1
    assert err.endswith(".txtool.toml: key 'selectt': unknown key; did you mean 'select'?\n")
    assert path.read_text() == first.read_text() == ROBOT.lstrip("\n")


def test_a_configuration_below_the_root_is_passed_over_with_a_note(run, write, tmp_path):
    write("b/.txtool.toml", 'selectt = ["TX300"]\n')  # not even read
    write("b/robot.urdf", ROBOT)
    code, out, err = run("migrate", "--check", "b")
    assert (code, out) == (1, "")
    assert err.splitlines()[0] == (
        f"txtool: note: {tmp_path / 'b' / '.txtool.toml'}: not read: a configuration below the "
        "repository's root is passed over (the defaults apply; --config names the file to use)")


def test_suppression_comments_keep_a_fix_off(run, write):
    path = write("robot.urdf", """
        <robot name="arm">
          <transmission name="a">
            <type>transmission_interface/SimpleTransmission</type>
            <joint name="ja">
              <!-- txtool: disable-next-line TX300 -->
              <hardwareInterface>EffortJointInterface</hardwareInterface>
            </joint>
            <actuator name="ma"/>
          </transmission>
          <transmission name="b">
            <type>transmission_interface/SimpleTransmission</type>
            <joint name="jb">
              <hardwareInterface>EffortJointInterface</hardwareInterface>
            </joint>
            <actuator name="mb"/>
          </transmission>
        </robot>
        """)
    assert run("migrate", "--write", "robot.urdf")[0] == 0
    text = path.read_text()
    assert text.count("<hardwareInterface>EffortJointInterface<") == 1
    assert text.count("<hardwareInterface>hardware_interface/EffortJointInterface<") == 1
    whole = write("whole.urdf", "<!-- txtool: disable-file TX300 -->\n" + ROBOT.lstrip("\n")
                  .replace('<?xml version="1.0"?>\n', ""))
    assert run("migrate", "--check", "whole.urdf") == (
        1, "", "would change whole.urdf (TX301 x1, TX302 x1)\n1 file(s) would be changed\n")
    assert "hardware_interface/" not in whole.read_text()


def test_crlf_line_endings_are_kept(run, write, tmp_path):
    path = tmp_path / "robot.urdf"
    path.write_bytes(ROBOT.lstrip("\n").replace("\n", "\r\n").encode())
    assert run("migrate", "--write", "robot.urdf")[0] == 0
    data = path.read_bytes()
    assert data == ROBOT_FIXED.replace("\n", "\r\n").encode()
    assert run("migrate", "--check", "robot.urdf")[0] == 0


def test_migrate_imports_nothing_heavy(write, tmp_path):
    import subprocess
    import sys

    write("robot.urdf", ROBOT)
    probe = (
        "import atexit, sys\n"
        "atexit.register(lambda: print(sorted(m for m in ('numpy', 'pinocchio', 'yourdfpy', "
        "'xacro') if m in sys.modules)))\n"
        "from txtool.cli import main\n"
        "sys.argv = ['txtool', 'migrate', '--check', '--to', 'ros2-p2', 'robot.urdf']\n"
        "main()\n"
    )
    done = subprocess.run([sys.executable, "-c", probe], cwd=tmp_path, capture_output=True,
                          text=True)
    assert (done.returncode, done.stdout) == (1, "[]\n"), done.stderr


def test_a_file_that_cannot_be_written_is_one_line_and_exit_2(run, write, monkeypatch):

    def refuse(path: str, data: bytes, **how: object) -> None:
        raise PermissionError(13, "Permission denied")

    from txtool.io import xmlio

    monkeypatch.setattr(xmlio, "write_atomic", refuse)
    path = write("robot.urdf", ROBOT)
    clean = write("clean.urdf", CLEAN)
    assert run("migrate", "--write", "robot.urdf", "clean.urdf") == (2, "", (
        "txtool: robot.urdf: cannot write: Permission denied\n"
        "1 file(s) could not be read or written\n"
    ))
    assert path.read_text() == ROBOT.lstrip("\n") and clean.read_text() == CLEAN.lstrip("\n")


def test_a_file_changed_on_disk_meanwhile_is_not_overwritten(write, monkeypatch):
    from txtool.transform import migrate

    path = write("robot.urdf", ROBOT)
    real = migrate.migrate_file

    def edit_meanwhile(*args, **kwargs):
        result = real(*args, **kwargs)
        path.write_text(CLEAN)
        return result

    monkeypatch.setattr(migrate, "migrate_file", edit_meanwhile)
    report = migrate.migrate_paths(["robot.urdf"], migrate.MigrateOptions(mode="write"))
    assert report.exit_code == 2
    assert report.messages == [
        "txtool: robot.urdf: changed on disk during the migration; not written",
        "1 file(s) could not be read or written",
    ]
    assert path.read_text() == CLEAN
