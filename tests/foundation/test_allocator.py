"""The command line frees the trees of large documents at once (txtool.io.allocator)."""

from __future__ import annotations

import ctypes
import os
import platform
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest
from click.testing import CliRunner

from txtool.cli import cli
from txtool.io import allocator
from txtool.io.xmlio import parse_bytes

ROOT = Path(__file__).resolve().parents[2]
GLIBC = sys.platform.startswith("linux") and platform.libc_ver()[0] == "glibc"


@pytest.fixture
def asked(monkeypatch) -> list[int]:
    """The calls to glibc, recorded instead of made; the switch off, as in a library."""
    calls: list[int] = []
    monkeypatch.setattr(allocator._State, "enabled", False)
    monkeypatch.setattr(allocator._State, "asked", False)
    monkeypatch.setattr(allocator, "for_large_trees", lambda: calls.append(1) or True)
    return calls


def large_robot() -> bytes:
    links = "".join(f'<link name="l{i}"/>' for i in range(allocator.LARGE // 16))
    return f'<robot name="r">{links}</robot>'.encode()


def test_a_library_parse_leaves_the_allocator_alone(asked):
    parse_bytes(large_robot(), "big.urdf")
    assert asked == []


def test_the_command_line_asks_once_at_its_first_large_document(asked, tmp_path):
    small, big = tmp_path / "small.urdf", tmp_path / "big.urdf"
    small.write_bytes(b'<robot name="r"><link name="a"/></robot>')
    big.write_bytes(large_robot())
    assert CliRunner().invoke(cli, ["show", str(small)]).exit_code == 0
    assert asked == []  # enabled, but a small document pays nothing
    for _ in range(2):
        assert CliRunner().invoke(cli, ["show", str(big)]).exit_code == 0
    assert asked == [1]


@pytest.mark.skipif(not GLIBC, reason="glibc's mallopt and mallinfo2")
@pytest.mark.parametrize(("enabled", "held_in_fast_bins"), [(False, True), (True, False)])
def test_with_fast_bins_off_a_freed_tree_leaves_nothing_to_merge_later(enabled,
                                                                       held_in_fast_bins):
    """What glibc holds in its fast bins after a large tree is freed (mallinfo2's fsmblks):
    the merging that the next large allocation does first."""
    if not hasattr(ctypes.CDLL(None), "mallinfo2"):
        pytest.skip("glibc before 2.33")
    program = textwrap.dedent(f"""
        import ctypes
        from txtool.io import allocator
        from txtool.io.xmlio import parse_bytes

        class Info(ctypes.Structure):
            _fields_ = [(name, ctypes.c_size_t) for name in (
                "arena", "ordblks", "smblks", "hblks", "hblkhd", "usmblks", "fsmblks",
                "uordblks", "fordblks", "keepcost")]

        info = ctypes.CDLL(None).mallinfo2
        info.restype = Info
        if {enabled}:
            allocator.enable()
        links = "".join(f'<link name="l{{i}}"><visual/></link>' for i in range(100000))
        tree = parse_bytes(f'<robot name="r">{{links}}</robot>'.encode(), "big.urdf")
        del tree
        print(info().fsmblks)
    """)
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    done = subprocess.run([sys.executable, "-c", program], capture_output=True, text=True,
                          env=env, timeout=120)
    assert done.returncode == 0, done.stderr
    assert (int(done.stdout) > 1 << 20) is held_in_fast_bins


@pytest.mark.skipif(not GLIBC, reason="glibc's mallopt")
@pytest.mark.parametrize(("enabled", "fresh_pages"), [(False, True), (True, False)])
def test_set_for_large_trees_what_is_freed_is_reused(enabled, fresh_pages):
    """A document's bytes written a second time (16 MB, as a block or a diff of a large robot
    is): by default glibc gives each allocation that large pages of its own, returned when
    freed, and the second takes a fault for each of its 4,096 pages again; set for large trees
    it reuses the first one's."""
    program = textwrap.dedent(f"""
        import resource
        from txtool.io import allocator

        if {enabled}:
            assert allocator.for_large_trees()
        faults = lambda: resource.getrusage(resource.RUSAGE_SELF).ru_minflt
        first = b"a" * (16 << 20)
        del first
        before = faults()
        second = b"b" * (16 << 20)
        print(faults() - before)
    """)
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    done = subprocess.run([sys.executable, "-c", program], capture_output=True, text=True,
                          env=env, timeout=120)
    assert done.returncode == 0, done.stderr
    assert (int(done.stdout) > 2000) is fresh_pages
