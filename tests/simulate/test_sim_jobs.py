"""``--jobs``: forks of the loaded process give the results of one process, in config order."""

from __future__ import annotations

import json

import pytest
from click.testing import CliRunner

from tests.simulate.robots import arm_ros1, arm_ros2, write
from txtool.cli import cli
from txtool.simulation import jobs


def simulate(*args: str) -> tuple[int, str, str]:
    result = CliRunner().invoke(cli, ["simulate", *args], catch_exceptions=False)
    return result.exit_code, result.stdout, result.stderr


@pytest.fixture
def forks(monkeypatch):
    """Pretend two CPUs are idle (the test machine may be busy) and record each forked map."""
    calls: list[tuple[int, int]] = []
    real = jobs.forked_map

    def spy(function, count, processes, size=None):
        calls.append((count, processes))
        return real(function, count, processes, size=size)

    monkeypatch.setattr(jobs, "idle_cpus", lambda: 2)
    monkeypatch.setattr(jobs, "forked_map", spy)
    return calls


def test_two_jobs_give_the_json_of_one(tmp_path, forks):
    robot = write(tmp_path, "arm.urdf", arm_ros1())
    configs = [write(tmp_path, "ros2.urdf", arm_ros2()),
               write(tmp_path, "offset.urdf", arm_ros1(offset=0.4)),
               write(tmp_path, "flipped.urdf", arm_ros1(n=-50)), robot]
    args = [robot, "--format", "json"]
    for config in configs:
        args += ["--candidate", config]
    one = simulate(*args, "-j", "1")
    assert forks == []
    two = simulate(*args, "-j", "2")
    assert forks == [(4, 2)]
    assert one == two
    code, out, _ = one
    runs = json.loads(out)["runs"]
    assert code == 1 and [r["config"] for r in runs] == configs
    assert [r["verdict"] for r in runs] == ["pass", "fail", "fail", "pass"]


def test_a_bad_config_is_the_same_one_line_error_with_forks(tmp_path, forks):
    robot = write(tmp_path, "arm.urdf", arm_ros1())
    bad = write(tmp_path, "bad.urdf", "<robot><joint></robot>")
    args = [robot, "--candidate", robot, "--candidate", bad]
    one = simulate(*args, "-j", "1")
    assert simulate(*args, "-j", "2") == one
    code, out, err = one
    assert (code, out) == (2, "") and err.count("\n") == 1 and "bad.urdf:1:" in err


def test_runs_shorter_than_a_fork_stay_in_one_process(tmp_path, forks):
    robot = write(tmp_path, "arm.urdf", arm_ros1())
    args = [robot, "--candidate", robot, "--candidate", robot, "--format", "json", "-j", "2"]
    short = simulate(*args, "--duration", "0.1")
    assert forks == [] and len(json.loads(short[1])["runs"]) == 2
    simulate(*args, "--duration", "2")
    assert forks == [(2, 2)]


@pytest.mark.parametrize(
    ("jobs_asked", "configs", "idle", "expected"),
    [(1, 4, 2, 1), (2, 1, 2, 1), (2, 4, 2, 2), (4, 4, 2, 2), (4, 3, 8, 3), (4, 4, 1, 1)],
)
def test_processes_never_exceed_configs_or_idle_cpus(monkeypatch, jobs_asked, configs, idle,
                                                     expected):
    monkeypatch.setattr(jobs, "idle_cpus", lambda: idle)
    assert jobs.processes_for(jobs_asked, configs) == expected


@pytest.mark.parametrize(("load", "idle"), [(0.2, 2), (1.0, 2), (1.6, 1), (2.4, 1), (9.5, 1)])
def test_idle_cpus_leave_out_what_others_keep_busy(monkeypatch, load, idle):
    monkeypatch.setattr(jobs, "usable_cpus", lambda: 2)
    monkeypatch.setattr(jobs.os, "getloadavg", lambda: (load, load, load))
    assert jobs.idle_cpus() == idle
