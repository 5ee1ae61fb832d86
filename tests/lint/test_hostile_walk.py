"""A pull request writes the files a folder walk reads: names, links, .gitignore files, patterns,
configuration files. None of them may stall the walk, stop it without a word, or decide how
the files beside them are checked (docs/security.md, "The walk and configuration")."""

from __future__ import annotations

import os
import resource
import subprocess
import sys
from pathlib import Path

import pytest

from tests.lint.conftest import BROKEN, CLEAN
from txtool.lint.config import find_config

ROOT = Path(__file__).resolve().parents[2]
CRAFTED = "**/a**a**a**a**a**a**a**a**a**a**a**b"  # see tests/lint/test_wildmatch.py


def txtool(cwd: Path, *args: str, timeout: float = 60) -> subprocess.CompletedProcess[str]:
    """``txtool ARGS`` in a fresh interpreter (its CPU time is the children's of this one)."""
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    env.pop("GITHUB_ACTIONS", None)
    return subprocess.run([sys.executable, "-m", "txtool", *args], cwd=cwd, env=env,
                          capture_output=True, text=True, timeout=timeout)


@pytest.fixture
def repo(tmp_path, monkeypatch) -> Path:
    """A git work tree (its top marked by ``.git``) holding one broken robot, as checked out."""
    top = tmp_path / "repo"
    (top / ".git").mkdir(parents=True)
    (top / "urdf").mkdir()
    (top / "urdf" / "broken.urdf").write_text(BROKEN)
    monkeypatch.chdir(top)
    find_config.cache_clear()
    yield top
    find_config.cache_clear()


# Patterns


def test_a_crafted_gitignore_pattern_does_not_stall_the_walk(repo):
    (repo / ".gitignore").write_text(CRAFTED + "\n")
    (repo / ("a" * 30)).mkdir()
    (repo / ("a" * 30) / "clean.urdf").write_text(CLEAN)
    done = txtool(repo, "validate", "--select", "TX1", ".", timeout=30)  # re: hours
    assert done.returncode == 1
    assert f"{'a' * 30}/clean.urdf" not in done.stdout and "urdf/broken.urdf" in done.stdout


# Links, special files, folders


def test_a_symbolic_link_loop_is_one_line_and_the_walk_goes_on(repo):
    (repo / "urdf" / "l1.urdf").symlink_to("l2.urdf")
    (repo / "urdf" / "l2.urdf").symlink_to("l1.urdf")
    (repo / "loop").symlink_to("loop")
    done = txtool(repo, "validate", "--select", "TX1", ".")
    assert done.returncode == 2
    assert "urdf/broken.urdf:" in done.stdout  # the findings are still reported
    assert done.stderr.splitlines() == [
        "txtool: ./loop: symbolic link loop (too many levels of symbolic links)",
        "txtool: ./urdf/l1.urdf: symbolic link loop (too many levels of symbolic links)",
        "txtool: ./urdf/l2.urdf: symbolic link loop (too many levels of symbolic links)",
    ]


def test_a_named_link_loop_is_one_line(repo):
    (repo / "l1.urdf").symlink_to("l2.urdf")
    (repo / "l2.urdf").symlink_to("l1.urdf")
    done = txtool(repo, "validate", "l1.urdf")
    assert (done.returncode, done.stdout.count("\n"), done.stderr.count("\n")) == (2, 1, 1)
    assert done.stderr == "txtool: l1.urdf: Too many levels of symbolic links\n"


@pytest.mark.parametrize("kind", ["fifo", "device", "huge"])
def test_a_gitignore_that_is_no_small_regular_file_is_refused_unread(repo, kind):
    gitignore = repo / "urdf" / ".gitignore"
    if kind == "fifo":
        os.mkfifo(gitignore)  # reading it would block for ever
        reason = "is a named pipe (FIFO), not a regular file"
    elif kind == "device":
        gitignore.symlink_to("/dev/zero")  # reading it would never end
        reason = "is a character device, not a regular file"
    else:
        gitignore.write_text("*.xacro\n" * 40_000)
        reason = "file is 320000 bytes, larger than the 262144 limit"
    done = txtool(repo, "validate", "--select", "TX1", ".", timeout=30)
    assert done.returncode == 2
    assert "urdf/broken.urdf:" in done.stdout
    assert done.stderr.count("\n") == 1 and done.stderr.startswith(
        f"txtool: urdf/.gitignore: {reason}")


def test_a_folder_that_cannot_be_listed_is_one_line(repo, monkeypatch, validate):
    (repo / "urdf" / "private").mkdir()
    listing = os.scandir

    def scandir(path):  # as an unreadable folder (the tests may run as root, who reads all)
        if str(path).endswith("private"):
            raise PermissionError(13, "Permission denied", str(path))
        return listing(path)

    monkeypatch.setattr(os, "scandir", scandir)
    code, out, err = validate("--select", "TX1", ".")
    assert code == 2
    assert "urdf/broken.urdf:" in out
    assert err == "txtool: ./urdf/private: cannot list this folder: permission denied\n"


def test_a_thousand_nested_folders_cost_linear_time(tmp_path):
    folder = tmp_path
    for _ in range(1000):
        folder = folder / "d"
        folder.mkdir()
        (folder / "notes.txt").write_text("")
    (folder / "robot.urdf").write_text(CLEAN)
    try:
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        done = txtool(tmp_path, "validate", ".", timeout=120)
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
    finally:
        _remove_chain(tmp_path / "d")  # deeper than shutil.rmtree's recursion (pytest's too)
    assert (done.returncode, done.stderr) == (0, "")
    # Measured: 0.8 s of CPU (start-up included); a walk quadratic in depth took minutes.
    assert (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime) < 8


def _remove_chain(top: Path) -> None:
    folders = [top]
    while (folders[-1] / "d").is_dir():
        folders.append(folders[-1] / "d")
    for folder in reversed(folders):
        for entry in folder.iterdir():
            entry.unlink()
        folder.rmdir()


# Configuration


def test_a_configuration_nested_too_deep_is_one_line(repo):
    (repo / ".txtool.toml").write_text("x = " + "[" * 50_000 + "]" * 50_000 + "\n")
    done = txtool(repo, "validate", ".")
    assert (done.returncode, done.stdout) == (2, "")
    assert done.stderr == f"txtool: {repo / '.txtool.toml'}: configuration nested too deep\n"


@pytest.mark.parametrize("kind", ["fifo", "device"])
def test_a_configuration_that_is_no_regular_file_is_refused_unread(repo, kind):
    config = repo / ".txtool.toml"
    os.mkfifo(config) if kind == "fifo" else config.symlink_to("/dev/zero")
    done = txtool(repo, "validate", ".", timeout=30)
    assert (done.returncode, done.stdout) == (2, "")
    assert done.stderr.count("\n") == 1
    assert done.stderr.startswith(f"txtool: {config}: is a ")


def test_a_configuration_dropped_beside_the_files_is_passed_over(repo, validate):
    (repo / "urdf" / ".txtool.toml").write_text('ignore = ["ALL"]\nexclude = ["*"]\n')
    code, out, err = validate("--select", "TX106", ".")
    assert code == 1
    assert out.startswith("urdf/broken.urdf:6:24: error TX106 ")
    assert err == (f"txtool: note: {repo / 'urdf' / '.txtool.toml'}: not read: a configuration "
                   "below the repository's root is passed over (the defaults apply; --config "
                   "names the file to use)\n")


def test_the_roots_configuration_applies_from_any_folder_of_the_repository(repo, validate,
                                                                           monkeypatch):
    (repo / "pyproject.toml").write_text('[tool.txtool]\nselect = ["TX106"]\n')
    (repo / "urdf" / "pyproject.toml").write_text('[tool.txtool]\nselect = ["TX102"]\n')
    monkeypatch.chdir(repo / "urdf")
    code, out, err = validate("broken.urdf")
    assert (code, [line.split()[2] for line in out.splitlines()[:-1]]) == (1, ["TX106"])
    assert err.startswith(f"txtool: note: {repo / 'urdf' / 'pyproject.toml'}: not read: ")
    assert f"({repo / 'pyproject.toml'} applies;" in err


def test_without_git_the_working_folder_is_the_root(tmp_path, monkeypatch, validate):
    (tmp_path / "sub").mkdir()
    (tmp_path / "sub" / "broken.urdf").write_text(BROKEN)
    (tmp_path / ".txtool.toml").write_text('select = ["TX106"]\n')
    (tmp_path / "sub" / ".txtool.toml").write_text('select = ["TX102"]\n')
    monkeypatch.chdir(tmp_path)
    find_config.cache_clear()
    code, out, err = validate("--quiet", "sub")
    assert (code, [line.split()[2] for line in out.splitlines()]) == (1, ["TX106"])
    assert "sub/.txtool.toml: not read" in err
    monkeypatch.chdir(tmp_path / "sub")  # run from the folder: its configuration is the root's
    code, out, err = validate("--quiet", ".")
    assert (code, [line.split()[2] for line in out.splitlines()], err) == (0, ["TX102"], "")


def test_config_pins_the_configuration(repo, validate, tmp_path):
    (repo / ".txtool.toml").write_text('ignore = ["ALL"]\n')  # a pull request's edit
    pinned = tmp_path / "base.toml"
    pinned.write_text('select = ["TX106"]\n')
    assert validate(".")[0] == 0
    code, out, err = validate("--quiet", "--config", str(pinned), ".")
    assert (code, [line.split()[2] for line in out.splitlines()], err) == (1, ["TX106"], "")


@pytest.mark.parametrize("planted", ["package.xml", "urdf/package.xml"])
def test_a_package_xml_that_is_a_fifo_is_passed_over_unread(tmp_path, monkeypatch, planted):
    """The readers and $(find) look for package.xml upward from each file: a FIFO there would
    block the run until the job's timeout."""
    import subprocess
    import sys

    (tmp_path / ".git").mkdir()
    (tmp_path / "urdf").mkdir()
    (tmp_path / "urdf" / "robot.urdf").write_text(
        '<robot name="r"><transmission name="t"><type>transmission_interface/'
        'SimpleTransmission</type><joint name="j"><hardwareInterface>hardware_interface/'
        'EffortJointInterface</hardwareInterface></joint><actuator name="m">'
        "<mechanicalReduction>0</mechanicalReduction></actuator></transmission></robot>")
    os.mkfifo(tmp_path / planted)
    done = subprocess.run([sys.executable, "-m", "txtool", "validate", "urdf"], cwd=tmp_path,
                          capture_output=True, text=True, timeout=60)
    assert done.returncode == 1 and "TX106" in done.stdout
