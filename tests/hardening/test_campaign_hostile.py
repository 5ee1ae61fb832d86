"""``simulate`` and its campaigns against hostile values and addresses: one line, exit 2.

A campaign file or a parameters file comes with the pull request: numbers like 1e307, nan, inf,
negative ones, durations and time steps that would hold gigabytes are refused before anything
is allocated. A scheduler address is checked with one bounded exchange (a server that accepts
and never answers, one that answers garbage claiming exabytes, an unknown scheme). The
embedded cluster speaks TLS with a key of its own: another local process cannot run code in it.
"""

from __future__ import annotations

import importlib.util
import os
import socket
import struct
import subprocess
import sys
import threading
import time
from collections.abc import Iterator
from pathlib import Path

import pytest

from tests.hardening.conftest import Run

ROOT = Path(__file__).resolve().parents[2]
ENV = {**os.environ, "PYTHONPATH": str(ROOT)}
needs_sim = pytest.mark.skipif(importlib.util.find_spec("pinocchio") is None,
                               reason="simulate needs the 'sim' extra (pinocchio)")


@pytest.fixture
def arm(tmp_path: Path) -> str:
    (tmp_path / "arm.urdf").write_bytes((ROOT / "fixtures" / "demo_robot.urdf").read_bytes())
    return "arm.urdf"


def one_line(code: int, out: str, err: str) -> str:
    assert (code, out) == (2, ""), (code, out, err)
    assert err.startswith("txtool: ") and len(err.splitlines()) == 1, err
    assert "internal error" not in err, err
    return err


# --- campaign files --------------------------------------------------------------------------

@needs_sim
@pytest.mark.parametrize(("bound", "reason"), [
    ("damping = [0, 1e307]", "c.toml:3: bounds.damping: at most 1e+06"),
    ("friction = 1e307", "c.toml:3: bounds.friction: at most 1e+06"),
    ("rotor_inertia = [1, 1e300]", "c.toml:3: bounds.rotor_inertia: at most 1e+06"),
    ("gains = 1e307", "c.toml:3: bounds.gains: at most 1e+06"),
    ("sensor_noise = [0, 1.7976931348623157e308]", "c.toml:3: bounds.sensor_noise: at most"),
    ("damping = nan", "c.toml:3: bounds.damping: expected [low, high] or one number"),
    ("friction = [0, inf]", "c.toml:3: bounds.friction: expected [low, high] or one number"),
    ("gains = -inf", "c.toml:3: bounds.gains: expected [low, high] or one number"),
    ("damping = -1e-300", "c.toml:3: bounds.damping: must be zero or positive"),
    ("gains = 0", "c.toml:3: bounds.gains: must be positive"),
    ('payload = {link = "tool_link", mass = 1e307}', "bounds.payload.mass: at most 1e+06"),
    ('payload = {link = "tool_link", mass = 1, xyz = [1e307, 0, 0]}',
     "bounds.payload.xyz: expected three numbers (m) within ±1000"),
    ('payload = {link = "tool_link", mass = 1, xyz = [nan, 0, 0]}', "bounds.payload.xyz"),
])
def test_a_campaign_value_out_of_range_is_one_line(run: Run, tmp_path: Path, arm: str,
                                                   bound: str, reason: str):
    (tmp_path / "c.toml").write_text(f"samples = 1\n[bounds]\n{bound}\n")
    err = one_line(*run("simulate", arm, "--campaign", "c.toml", "--serial"))
    assert reason in err, err


@needs_sim
@pytest.mark.parametrize("text", [
    "samples = 9223372036854775807\n", "samples = -1\n", "samples = 1e3\n", "seed = -1\n",
    "samples = 99999\ncorners = true\n[bounds]\ndamping = [0, 1]\nfriction = [0, 1]\n",
    "samples = 100000\ncandidates = [" + ", ".join(['"arm.urdf"'] * 2000) + "]\n",  # 2e8 runs
])
def test_counts_are_bounded_before_any_sample_is_drawn(run: Run, tmp_path: Path, arm: str,
                                                       text: str):
    (tmp_path / "c.toml").write_text(text)
    one_line(*run("simulate", arm, "--campaign", "c.toml", "--serial"))


# --- simulate settings -------------------------------------------------------------------

@needs_sim
@pytest.mark.parametrize(("args", "reason"), [
    (["--duration", "1e307"], "--duration: at most 1e+09"),
    (["--dt", "1e-300"], "--duration/--dt: more than"),
    (["--duration", "nan"], "--duration: must be a positive number"),
    (["--dt", "inf"], "--dt: must be a positive number"),
    (["--duration", "-1"], "--duration: must be a positive number"),
    (["--bandwidth", "1e307"], "--bandwidth: at most 1e+09"),
    (["--tolerance", "1e307"], "--tolerance: at most 1e+09"),
    # within the step count, but gigabytes of arrays: priced before they are allocated
    (["--duration", "99000", "--dt", "0.005"], "would hold about 17.7 GiB (at most 2 GiB)"),
    (["--duration", "5", "--dt", "1e-6"], "would hold about 4.5 GiB (at most 2 GiB)"),
])
def test_a_setting_out_of_range_is_one_line(run: Run, arm: str, args: list[str], reason: str):
    err = one_line(*run("simulate", arm, *args))
    assert reason in err, err


@needs_sim
@pytest.mark.parametrize(("run_table", "reason"), [
    ("duration = 1e307", "--duration: at most 1e+09"),
    ("dt = 5e-324", "--duration/--dt: more than"),
    ("duration = 3000\ndt = 0.001", "would hold about"),
])
def test_a_parameters_file_out_of_range_is_one_line(run: Run, tmp_path: Path, arm: str,
                                                    run_table: str, reason: str):
    (tmp_path / "p.toml").write_text(f"{run_table}\n")
    err = one_line(*run("simulate", arm, "--params", "p.toml"))
    assert reason in err, err


# --- scheduler addresses -------------------------------------------------------------------

@pytest.fixture
def server() -> Iterator[callable]:
    """A listening socket on the loopback that answers each connection with ``reply`` (None:
    accepts and says nothing), until the test ends."""
    sockets: list[socket.socket] = []
    stop = threading.Event()

    def start(reply: bytes | None) -> str:
        listener = socket.socket()
        listener.bind(("127.0.0.1", 0))
        listener.listen()
        listener.settimeout(0.1)
        sockets.append(listener)

        def serve() -> None:
            while not stop.is_set():
                try:
                    connection, _ = listener.accept()
                except OSError:
                    continue
                sockets.append(connection)
                if reply is not None:  # says it, and leaves
                    try:
                        connection.sendall(reply)
                        connection.shutdown(socket.SHUT_WR)
                    except OSError:  # the client left first (it read enough)
                        pass

        threading.Thread(target=serve, daemon=True).start()
        return f"tcp://127.0.0.1:{listener.getsockname()[1]}"

    yield start
    stop.set()
    for each in sockets:
        each.close()


def greeting(count: int, lengths: list[int], payload: bytes = b"") -> bytes:
    frames = struct.pack("Q", count) + struct.pack(f"{len(lengths)}Q", *lengths) + payload
    return struct.pack("Q", len(frames)) + frames


@pytest.mark.parametrize(("reply", "reason"), [
    (None, "no answer within 0.5 s"),
    (b"\xff" * 64, "what answers is not a Dask scheduler"),  # claims 2^64 - 1 bytes
    (b"HTTP/1.1 400 Bad Request\r\n\r\n", "what answers is not a Dask scheduler"),
    (greeting(2**60, [1]), "what answers is not a Dask scheduler"),  # exabytes of frames
    (greeting(1, [2**62]), "what answers is not a Dask scheduler"),
    (greeting(1, [5], b"\xc1\xc1\xc1\xc1\xc1"), "what answers is not a Dask scheduler"),
    (b"", "what answers is not a Dask scheduler"),  # closes at once
])
def test_a_scheduler_that_is_none_is_one_line_in_bounded_time(server, monkeypatch,
                                                              reply: bytes | None, reason: str):
    pytest.importorskip("distributed")
    from txtool.io.xmlio import InputError
    from txtool.simulation import campaign

    monkeypatch.setattr(campaign, "CONNECT_TIMEOUT", "0.5s")
    address = server(reply)
    started = time.monotonic()
    with pytest.raises(InputError) as refused:
        campaign.check_scheduler(address)
    assert time.monotonic() - started < 30  # (0.5 s, and a loaded machine)
    assert str(refused.value) == f"--scheduler {address}: {reason}"


@pytest.mark.parametrize(("address", "reason"), [
    ("foo://127.0.0.1:1", "unknown scheme 'foo' (expected tcp:// or tls://)"),
    ("inproc://127.0.0.1/1/1", "unknown scheme 'inproc'"),
    ("ucx://127.0.0.1:1", "unknown scheme 'ucx'"),
    ("tcp://127.0.0.1", "not an address"),
    ("tcp://127.0.0.1:notaport", "not an address"),
    ("tcp://127.0.0.1:1", "cannot connect: "),
])
def test_an_address_that_is_no_scheduler_s_is_one_line(address: str, reason: str):
    pytest.importorskip("distributed")
    from txtool.io.xmlio import InputError
    from txtool.simulation import campaign

    with pytest.raises(InputError) as refused:
        campaign.check_scheduler(address)
    assert str(refused.value).startswith(f"--scheduler {address}: {reason}")
    assert "\n" not in str(refused.value)


@needs_sim
def test_the_command_refuses_a_silent_scheduler_in_one_line(server, tmp_path: Path, arm: str):
    pytest.importorskip("distributed")
    address = server(None)
    (tmp_path / "c.toml").write_text("samples = 1\n")
    setup = "from txtool.simulation import campaign\ncampaign.CONNECT_TIMEOUT = '0.5s'\n"
    script = f"import sys\n{setup}from txtool.cli import main\n" \
             "sys.argv = ['txtool', *sys.argv[1:]]\nmain()\n"
    done = subprocess.run([sys.executable, "-c", script, "simulate", arm, "--campaign",
                           "c.toml", "--scheduler", address], cwd=tmp_path, env=ENV,
                          capture_output=True, text=True, timeout=120)
    assert (done.returncode, done.stdout, done.stderr) == (
        2, "", f"txtool: --scheduler {address}: no answer within 0.5 s\n")


# --- the embedded cluster ----------------------------------------------------------------

CLUSTER = """
import sys
from txtool.simulation import campaign
if __name__ == "__main__":
    cluster = campaign.local_cluster(1)
    print(cluster.scheduler_address, flush=True)
    sys.stdin.read()  # until the test closes it
    cluster.close()
"""

INTRUDER = """
import sys
from distributed import Client
from distributed.security import Security
from txtool.simulation import campaign
address = sys.argv[1]
plain = address.replace("tls://", "tcp://")
tries = [(address, None), (plain, None), (address, campaign.run_security())]
for where, security in tries:
    try:
        with Client(where, timeout=5, security=security) as client:
            print("ran", client.submit(sum, [1, 2]).result(), flush=True)
    except Exception as exc:
        print("refused", type(exc).__name__, flush=True)
"""


@needs_sim
def test_another_local_process_cannot_run_code_in_the_embedded_cluster(tmp_path: Path):
    pytest.importorskip("distributed")
    cluster = subprocess.Popen([sys.executable, "-c", CLUSTER], stdin=subprocess.PIPE,
                               stdout=subprocess.PIPE, text=True, cwd=tmp_path, env=ENV)
    try:
        assert cluster.stdout is not None
        address = cluster.stdout.readline().strip()
        assert address.startswith("tls://127.0.0.1:"), address
        intruder = subprocess.run([sys.executable, "-c", INTRUDER, address], cwd=tmp_path,
                                  env=ENV, capture_output=True, text=True, timeout=120)
    finally:
        cluster.communicate(timeout=120)
    lines = intruder.stdout.splitlines()
    assert len(lines) == 3 and all(line.startswith("refused ") for line in lines), \
        (intruder.stdout, intruder.stderr[-2000:])
