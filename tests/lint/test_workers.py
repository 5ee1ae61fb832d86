"""forked_map: every result once, in order, whatever the forks do."""

from __future__ import annotations

import os
import subprocess
import sys
import time

import pytest

from txtool.lint import workers
from txtool.lint.workers import MAX_CHUNKS, _queue, chunk_size, forked_map


@pytest.fixture
def forks(monkeypatch: pytest.MonkeyPatch) -> list[int]:
    """The process ids of the forks this test makes (not of children other tests left)."""
    made: list[int] = []
    real_fork = os.fork

    def recording_fork() -> int:
        pid = real_fork()
        if pid:
            made.append(pid)
        return pid

    monkeypatch.setattr(os, "fork", recording_fork)
    return made


def all_reaped(pids: list[int]) -> bool:
    """True when every one of ``pids`` has been waited for (none running, none a zombie)."""
    for pid in pids:
        try:
            os.waitpid(pid, os.WNOHANG)
        except ChildProcessError:
            continue
        return False
    return True


def test_results_come_in_order_from_several_processes(forks):
    def slow_square(index):
        time.sleep(0.001)  # long enough for every process to take chunks
        return index * index, os.getpid()

    results = list(forked_map(slow_square, 300, 3))
    assert [value for value, _ in results] == [i * i for i in range(300)]
    assert os.getpid() in {pid for _, pid in results}
    assert len({pid for _, pid in results}) > 1
    assert forks and all_reaped(forks)


def test_large_results_do_not_block_the_forks(forks):
    text = "x" * 20_000  # a fork's results are far larger than a pipe's buffer
    assert list(forked_map(lambda index: (index, text), 400, 2)) == [(i, text) for i in range(400)]
    assert forks and all_reaped(forks)


def test_chunks_a_fork_never_reported_are_computed_here(forks):
    parent = os.getpid()

    def dies_in_a_fork(index):
        if os.getpid() != parent:
            os._exit(3)
        time.sleep(0.0005)
        return index

    assert list(forked_map(dies_in_a_fork, 200, 3)) == list(range(200))
    assert forks and all_reaped(forks)


def test_an_error_in_a_fork_is_raised_here(forks):
    def fails_on_seven(index):
        if index == 7:
            raise ValueError("seven")
        return index

    with pytest.raises(ValueError, match="seven"):
        list(forked_map(fails_on_seven, 100, 2))
    assert forks and all_reaped(forks)


def test_ctrl_c_here_stops_the_forks(forks):
    parent = os.getpid()

    def interrupted(index):
        time.sleep(0.001)
        if os.getpid() == parent and index >= 40:
            raise KeyboardInterrupt
        return index

    with pytest.raises(KeyboardInterrupt):
        list(forked_map(interrupted, 2000, 3))
    assert forks and all_reaped(forks)


def test_chunk_numbers_fit_a_pipe_buffer():
    for count in (1, 10, 1000, 4096, 10**6, 10**7):
        assert -(-count // chunk_size(count)) <= MAX_CHUNKS
    assert chunk_size(1000) == 4


def test_records_a_pipe_cannot_hold_are_refused_without_blocking():
    assert _queue(b"\0" * (1 << 22)) is None  # more than any pipe buffer holds
    queue = _queue(b"\1\0\0\0")
    assert queue is not None
    try:
        assert os.read(queue, 8) == b"\1\0\0\0" and os.read(queue, 8) == b""  # then the end
    finally:
        os.close(queue)


def test_without_a_queue_everything_is_computed_here(monkeypatch, forks):
    monkeypatch.setattr(workers, "_queue", lambda records: None)
    results = list(forked_map(lambda index: (index, os.getpid()), 100, 3))
    assert results == [(i, os.getpid()) for i in range(100)]
    assert forks == []


def test_a_child_another_test_left_running_does_not_count(forks):
    stranger = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(30)"])
    try:
        assert list(forked_map(lambda index: index, 50, 2)) == list(range(50))
        assert forks and stranger.pid not in forks and all_reaped(forks)
        assert not all_reaped([stranger.pid])  # the check does see a child still running
    finally:
        stranger.kill()
        stranger.wait()
