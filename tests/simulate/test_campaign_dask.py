"""``simulate --campaign`` on Dask: a local cluster, or a scheduler's address, gives the JSON of
the serial run to the bit (the tasks are pure functions; floats travel exactly)."""

from __future__ import annotations

import pytest
from click.testing import CliRunner

from tests.simulate.robots import pendulum, write
from txtool.cli import cli
from txtool.simulation import campaign

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


def simulate(*args: str) -> tuple[int, str, str]:
    result = CliRunner().invoke(cli, ["simulate", *args], catch_exceptions=False)
    return result.exit_code, result.stdout, result.stderr


@pytest.fixture
def args(tmp_path, monkeypatch):
    """The command line of a small campaign, its files in the working folder."""
    monkeypatch.chdir(tmp_path)
    write(tmp_path, "p.urdf", pendulum(2.0, 0.5, 40.0))
    write(tmp_path, "flipped.urdf", pendulum(2.0, 0.5, -40.0))
    write(tmp_path, "campaign.toml", CAMPAIGN)
    return ["p.urdf", "--campaign", "campaign.toml", "--duration", "0.3", "--format", "json"]


@pytest.fixture
def serial(args):
    """(args, exit code and JSON of the serial run)."""
    code, out, err = simulate(*args, "--serial")
    assert (code, err) == (1, "")
    assert '"passed": 0' not in out.split('"config": "flipped.urdf"')[0]  # p.urdf passes some
    assert '"failed": 0' not in out.split('"config": "flipped.urdf"')[0]  # and fails some
    return args, code, out


def test_a_local_cluster_gives_the_serial_json_to_the_bit(serial):
    args, code, out = serial
    assert simulate(*args, "--workers", "2") == (code, out, "")


def test_a_scheduler_address_gives_the_serial_json_to_the_bit(serial):
    args, code, out = serial
    with campaign.local_cluster(2) as cluster:
        assert simulate(*args, "--scheduler", cluster.scheduler_address) == (code, out, "")


def test_a_scheduler_that_does_not_answer_is_one_line(args, monkeypatch):
    monkeypatch.setattr(campaign, "CONNECT_TIMEOUT", "0.5s")
    code, out, err = simulate(*args, "--scheduler", "tcp://127.0.0.1:9")
    assert (code, out) == (2, "")
    assert err.startswith("txtool: --scheduler tcp://127.0.0.1:9: cannot connect: ")
    assert len(err.splitlines()) == 1
