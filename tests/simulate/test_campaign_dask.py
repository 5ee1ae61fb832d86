"""``simulate --campaign`` on Dask: a local cluster, or a scheduler's address, gives the JSON of
the serial run to the bit (the tasks are pure functions; floats travel exactly)."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from tests.simulate.robots import pendulum, write

ROOT = Path(__file__).resolve().parents[2]

distributed = pytest.importorskip("distributed")

# Candidates that pass and fail by sample: the payload and the scaled gains decide.
CAMPAIGN = """seed = 2
samples = 4
candidates = ["p.urdf", "flipped.urdf"]
[bounds]
gains = [0.6, 1.4]
friction = [0.0, 1.0]
sensor_noise = [0.0, 2e-4]
[bounds.payload]
link = "rod"
mass = [0.0, 0.4]
xyz = [0.5, 0.0, 0.0]
"""


def simulate(*args: str, cwd: Path, setup: str = "") -> tuple[int, str, str]:
    """``txtool simulate ARGS`` in a process of its own: Dask's client leaves threads running
    for the life of its process (an event loop, an offload pool), and a test process with
    threads would not share files among forked workers (txtool.lint.api.worker_count)."""
    script = f"import sys\n{setup}\nfrom txtool.cli import main\nsys.argv = ['txtool', *sys.argv[1:]]\nmain()\n"
    done = subprocess.run([sys.executable, "-c", script, "simulate", *args], cwd=cwd,
                          env={**os.environ, "PYTHONPATH": str(ROOT)}, capture_output=True,
                          text=True, timeout=600)
    return done.returncode, done.stdout, done.stderr


@pytest.fixture
def args(tmp_path):
    """The command line of a small campaign, its files in the working folder."""
    write(tmp_path, "p.urdf", pendulum(2.0, 0.5, 40.0))
    write(tmp_path, "flipped.urdf", pendulum(2.0, 0.5, -40.0))
    write(tmp_path, "campaign.toml", CAMPAIGN)
    return ["p.urdf", "--campaign", "campaign.toml", "--duration", "0.3", "--format", "json"]


@pytest.fixture
def serial(args, tmp_path):
    """(args, exit code and JSON of the serial run)."""
    code, out, err = simulate(*args, "--serial", cwd=tmp_path)
    assert (code, err) == (1, "")
    assert '"passed": 0' not in out.split('"config": "flipped.urdf"')[0]  # p.urdf passes some
    assert '"failed": 0' not in out.split('"config": "flipped.urdf"')[0]  # and fails some
    return args, code, out


def test_a_local_cluster_gives_the_serial_json_to_the_bit(serial, tmp_path):
    args, code, out = serial
    assert simulate(*args, "--workers", "2", cwd=tmp_path) == (code, out, "")


# A cluster of the user's own, on plain TCP (txtool's embedded one speaks TLS with a key of
# its own, which no other client has).
CLUSTER = """
import logging, sys
from distributed import LocalCluster
if __name__ == "__main__":
    cluster = LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                           dashboard_address=None, silence_logs=logging.CRITICAL)
    print(cluster.scheduler_address, flush=True)
    sys.stdin.read()  # until the test closes it
    cluster.close()
"""


def test_a_scheduler_address_gives_the_serial_json_to_the_bit(serial, tmp_path):
    args, code, out = serial
    # Its workers read the files at the paths given: relative ones from the folder they run in.
    cluster = subprocess.Popen([sys.executable, "-c", CLUSTER], stdin=subprocess.PIPE,
                               stdout=subprocess.PIPE, text=True, cwd=tmp_path,
                               env={**os.environ, "PYTHONPATH": str(ROOT)})
    try:
        address = cluster.stdout.readline().strip()
        assert address.startswith("tcp://"), address
        assert simulate(*args, "--scheduler", address, cwd=tmp_path) == (code, out, "")
    finally:
        cluster.communicate(timeout=120)


def test_a_scheduler_that_does_not_answer_is_one_line(args, tmp_path):
    code, out, err = simulate(*args, "--scheduler", "tcp://127.0.0.1:9", cwd=tmp_path,
                              setup="from txtool.simulation import campaign\n"
                                    "campaign.CONNECT_TIMEOUT = '0.5s'")
    assert (code, out) == (2, "")
    assert err.startswith("txtool: --scheduler tcp://127.0.0.1:9: cannot connect: ")
    assert len(err.splitlines()) == 1
