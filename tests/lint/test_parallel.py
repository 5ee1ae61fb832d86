"""Many files are shared among worker processes; the report is the same as from one process."""

from __future__ import annotations

from collections.abc import Callable

from click.testing import CliRunner

from tests.lint.conftest import BROKEN
from txtool.cli import cli
from txtool.lint.api import MIN_FILES_PER_WORKER, LintOptions, lint_paths, worker_count

CLEAN = """<robot name="r">
  <link name="a"/><link name="b"/>
  <joint name="j" type="revolute"><parent link="a"/><child link="b"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>
"""


def write_files(folder, count):
    for index in range(count):
        text = BROKEN if index % 3 == 0 else CLEAN
        (folder / f"robot_{index:03d}.urdf").write_text(text.replace('name="r"', f'name="r{index}"'))
    return folder / "robot_010b.urdf"  # missing: an input error in the middle of the run


def test_few_files_are_checked_in_process():
    assert worker_count(MIN_FILES_PER_WORKER - 1, 0) == 1
    assert worker_count(10_000, 1) == 1


def test_many_files_use_at_most_the_requested_workers():
    assert worker_count(10_000, 2) == 2
    assert worker_count(3 * MIN_FILES_PER_WORKER, 8) == 3


def test_workers_report_exactly_what_one_process_reports(tmp_path):
    missing = write_files(tmp_path, 4 * MIN_FILES_PER_WORKER)
    files = sorted([str(missing), *(str(p) for p in tmp_path.iterdir())])
    one = lint_paths(files, LintOptions(jobs=1))
    many = lint_paths(files, LintOptions(jobs=2))
    assert many.problems == one.problems
    assert [p.message for p in many.problems] == [p.message for p in one.problems]
    assert (many.files, many.errors) == (one.files, one.errors)
    assert one.files == 4 * MIN_FILES_PER_WORKER and len(one.errors) == 1


def test_jobs_option_gives_the_same_report_and_exit_code(tmp_path):
    missing = str(write_files(tmp_path, 2 * MIN_FILES_PER_WORKER))
    runner = CliRunner()
    args = ["--format", "json", str(tmp_path), missing]
    serial = runner.invoke(cli, ["validate", "-j", "1", *args])
    parallel = runner.invoke(cli, ["validate", "--jobs", "2", *args])
    assert serial.exit_code == parallel.exit_code == 2  # the missing file
    assert parallel.stdout == serial.stdout
    assert '"files": 64' in serial.stdout


def test_progress_counts_every_process_s_files_as_they_are_done(tmp_path):
    """With worker processes, the progress counts the forks' chunks as they are done, not
    only when their results come back. Files order the two processes, not a clock: the fork
    starts once this process has taken a chunk; this process finishes that chunk only after
    the fork has done a whole chunk (and told its count); the fork goes past its second chunk
    only once this process has told a count, so that count is not the last one."""
    import os
    import time

    from txtool.lint.workers import forked_map

    parent = os.getpid()
    own = [0]  # indices this process has done (a fork counts in its own copy)
    told: list[tuple[int, int]] = []
    started = tmp_path / "parent-started"
    counted = tmp_path / "counted"

    def wait_for(ready: Callable[[], bool]) -> None:
        deadline = time.monotonic() + 60
        while not ready():
            assert time.monotonic() < deadline
            time.sleep(0.001)

    def work(index: int) -> int:
        if os.getpid() == parent:
            started.touch()
            # 5 indices done by the fork: its first chunk of 4, and its count, are written
            wait_for(lambda: len(list(tmp_path.glob("fork-*"))) > 4)
            own[0] += 1
        else:
            wait_for(started.exists)
            if len(list(tmp_path.glob("fork-*"))) >= 8:
                wait_for(counted.exists)
            (tmp_path / f"fork-{index}").touch()
        return os.getpid()

    def progress(done: int) -> None:
        told.append((done, own[0]))
        counted.touch()

    pids = list(forked_map(work, 64, 2, size=4, progress=progress))
    assert len(set(pids)) == 2  # both processes did some
    counts = [done for done, _ in told]
    assert counts == sorted(counts) and counts[-1] == 64
    assert any(done > mine for done, mine in told[:-1])  # a fork's chunks counted on the way


def test_progress_with_workers_reports_what_one_process_reports(tmp_path):
    missing = write_files(tmp_path, 4 * MIN_FILES_PER_WORKER)
    files = sorted([str(missing), *(str(p) for p in tmp_path.iterdir())])
    told: list[tuple[int, int]] = []
    many = lint_paths(files, LintOptions(jobs=2), progress=lambda *pair: told.append(pair))
    assert many.problems == lint_paths(files, LintOptions(jobs=1)).problems
    assert told[-1] == (len(files), len(files)) and len(told) > len(files)


UNPREFIXED = CLEAN.replace("</joint>", """</joint>
  <transmission name="t"><type>transmission_interface/SimpleTransmission</type>
    <joint name="j"><hardwareInterface>EffortJointInterface</hardwareInterface></joint>
    <actuator name="m"><mechanicalReduction>2</mechanicalReduction></actuator></transmission>""")


def test_fixes_are_confirmed_and_made_alike_by_many_processes(tmp_path):
    """Which findings migrate's fixes really fix (validate's fixable marks) and what --fix
    writes do not depend on how many processes share the files."""
    for folder in ("one", "two"):
        (tmp_path / folder).mkdir()
        for index in range(4 * MIN_FILES_PER_WORKER):  # half with a finding: two processes
            text = UNPREFIXED if index % 2 else CLEAN
            (tmp_path / folder / f"robot_{index:03d}.urdf").write_text(text)
    runner = CliRunner()
    serial = runner.invoke(cli, ["validate", "-j", "1", "--format", "json", str(tmp_path / "one")])
    parallel = runner.invoke(cli, ["validate", "-j", "2", "--format", "json",
                                   str(tmp_path / "one")])
    assert serial.exit_code == parallel.exit_code == 1
    assert parallel.stdout == serial.stdout
    assert serial.stdout.count('"fixable": true') == 2 * MIN_FILES_PER_WORKER  # one a file
    for folder, jobs in (("one", "1"), ("two", "2")):
        fixed = runner.invoke(cli, ["validate", "-j", jobs, "--fix", str(tmp_path / folder)])
        assert fixed.exit_code == 0, fixed.output
    for index in range(4 * MIN_FILES_PER_WORKER):
        name = f"robot_{index:03d}.urdf"
        written = (tmp_path / "two" / name).read_text()
        assert written == (tmp_path / "one" / name).read_text()
        assert ("hardware_interface/EffortJointInterface" in written) == bool(index % 2)
