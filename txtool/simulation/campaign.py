"""``txtool simulate --campaign FILE``: every candidate against every sample, and the summary.

The samples (:mod:`txtool.simulation.campaign_file`) times the candidates make the tasks; each
is :func:`txtool.simulation.campaign_task.run_sample`, a pure function. They run on Dask: an
embedded ``distributed.LocalCluster`` (one process per core, one thread each) by default, the
cluster of ``--scheduler ADDRESS``, or one after the other in this process (``--serial``). The
records come back in task order whatever ran them, so the report is the same to the bit.
Dask is imported here only, when a campaign runs on a cluster.

The embedded cluster listens on this machine's loopback, where any local process could connect
and run code as the user: it speaks TLS with a key and certificate made for the run
(:func:`run_security`), and a connection without them is refused. A scheduler address is first
checked with one bounded exchange (:func:`check_scheduler`): Dask's own client waits for ever
on a server that accepts and never answers, and believes the sizes a garbled one sends.
"""

from __future__ import annotations

import contextlib
import json
import logging
import multiprocessing
import os
import shutil
import socket
import ssl
import struct
import subprocess
import tempfile
import time
from collections.abc import Iterator, Sequence
from dataclasses import dataclass, replace
from typing import Any

from rich.console import Console
from rich.table import Table

from txtool.io.xmlio import InputError
from txtool.simulation.campaign_file import PARAMETERS, Campaign, draw, read_campaign
from txtool.simulation.campaign_task import Record, Task, run_sample
from txtool.simulation.jobs import usable_cpus
from txtool.simulation.params import _line_of
from txtool.simulation.report import VERDICT_CELL, escape
from txtool.simulation.run import EXIT_INCONCLUSIVE, Options, candidates
from txtool.views import render

CONNECT_TIMEOUT = "10s"
GREETING_LIMIT = 64 * 1024  # bytes of a scheduler's greeting (a real one is about 200)
PRELOAD = ("distributed", "txtool.simulation.campaign_task")  # what a forked worker runs


@dataclass(frozen=True)
class Where:
    """Where the tasks run: ``serial`` here, else a scheduler's ``address`` or a local cluster
    of ``workers`` processes (None: one per usable core)."""

    serial: bool = False
    address: str | None = None
    workers: int | None = None


def tasks_of(campaign: Campaign, options: Options) -> list[Task]:
    """Candidate by candidate, sample by sample. The file's candidates replace the command's
    configs; without either, the robot's own config is the candidate."""
    if campaign.candidates:
        options = replace(options, configs=campaign.candidates, labels=())
    options = replace(options, keep_series=False, jobs=1)
    line = _line_of(campaign.text, "bounds.payload.link")
    where = f"{campaign.path}:{line}: bounds.payload.link" if line else campaign.path
    samples = draw(campaign)
    return [Task(options, config, label or config or options.robot, index, sample,
                 campaign.seed, campaign.payload, where)
            for config, label in candidates(options)
            for index, sample in enumerate(samples)]


def execute(tasks: Sequence[Task], where: Where) -> list[Record]:
    """The records of ``tasks``, in their order."""
    if where.serial:
        return [run_sample(task) for task in tasks]
    with _client(where) as client:
        futures = client.map(run_sample, list(tasks), pure=False)
        return list(client.gather(futures))


@contextlib.contextmanager
def _client(where: Where) -> Iterator[Any]:
    from distributed import Client

    if where.address is not None:
        check_scheduler(where.address)
        try:
            client = Client(where.address, timeout=CONNECT_TIMEOUT)
        except (OSError, TimeoutError, ValueError) as exc:
            reason = str(exc) or f"no answer within {CONNECT_TIMEOUT}"  # (a bare timeout)
            raise InputError(f"--scheduler {where.address}: cannot connect: {reason}") from None
        with client:
            yield client
        return
    with local_cluster(where.workers or usable_cpus()) as cluster, \
            Client(cluster, security=cluster.security) as client:
        yield client


def check_scheduler(address: str) -> None:
    """Refuse, in one line, an address that is not a Dask scheduler's: an unknown scheme, no
    answer within ``CONNECT_TIMEOUT``, or a greeting that is not Dask's (read within
    :data:`GREETING_LIMIT` bytes, whatever sizes it claims)."""
    from dask.utils import parse_timedelta
    from distributed.comm.addressing import parse_address, parse_host_port

    def refused(reason: str) -> InputError:
        return InputError(f"--scheduler {address}: {reason}")

    try:
        scheme, location = parse_address(address, strict=False)
        if scheme not in ("tcp", "tls"):
            raise refused(f"unknown scheme '{scheme}' (expected tcp:// or tls://)")
        host, port = parse_host_port(location)
    except (ValueError, TypeError) as exc:
        raise refused(f"not an address ({exc})") from None
    wait = float(parse_timedelta(CONNECT_TIMEOUT))
    context = _client_tls() if scheme == "tls" else None
    if scheme == "tls" and context is None:
        raise refused("tls:// needs Dask's TLS configuration (distributed.comm.tls)")
    deadline = time.monotonic() + wait
    try:
        with socket.create_connection((host, port), timeout=wait) as raw:
            stream = context.wrap_socket(raw) if context is not None else raw
            with stream:
                greeting = _greeting(stream, deadline)
    except TimeoutError:
        raise refused(f"no answer within {wait:g} s") from None
    except (OSError, ssl.SSLError) as exc:
        raise refused(f"cannot connect: {(getattr(exc, 'strerror', None) or exc)}") from None
    if greeting is None:
        raise refused("what answers is not a Dask scheduler")


def _client_tls() -> ssl.SSLContext | None:
    from distributed.security import Security

    return Security().get_connection_args("client")["ssl_context"]


def _greeting(stream: socket.socket, deadline: float) -> dict[str, Any] | None:
    """A Dask server's first message (its handshake), or None for anything else."""

    def read(count: int) -> bytes:
        data = b""
        while len(data) < count:
            stream.settimeout(max(deadline - time.monotonic(), 0.001))
            piece = stream.recv(count - len(data))
            if not piece:
                break
            data += piece
        return data

    head = read(8)
    if len(head) < 8:
        return None
    (size,) = struct.unpack("Q", head)
    if size > GREETING_LIMIT:
        return None
    packed = read(size)
    if len(packed) < size or size < 8:
        return None
    (count,) = struct.unpack_from("Q", packed)
    if 8 + 8 * count > size:
        return None
    lengths = struct.unpack_from(f"{count}Q", packed, 8)
    rest = sum(lengths) - (size - 8 - 8 * count)
    if rest < 0 or rest > GREETING_LIMIT:
        return None
    data = packed + read(rest)
    if len(data) < size + rest:
        return None
    from distributed.protocol import loads
    from distributed.protocol.utils import unpack_frames

    try:
        message = loads(unpack_frames(data), deserialize=False)
    except Exception:  # whatever the bytes make the decoder raise: not Dask's greeting
        return None
    return message if isinstance(message, dict) and "python" in message else None


def local_cluster(workers: int) -> Any:
    """A ``distributed.LocalCluster`` of ``workers`` processes of one thread each.

    Where the platform has it, workers are forked from a server process that has imported
    Dask and the simulation once (a fresh interpreter spends seconds importing them); the
    server lives as long as this process, so a second cluster starts at once.
    """
    import dask
    from distributed import LocalCluster
    from distributed.utils import get_mp_context

    forkserver = "forkserver" in multiprocessing.get_all_start_methods()  # not on Windows
    method = "forkserver" if forkserver else "spawn"
    security = run_security()
    with dask.config.set({"distributed.worker.multiprocessing-method": method}):
        if forkserver:  # pragma: no branch - POSIX platforms have it
            get_mp_context().set_forkserver_preload(list(PRELOAD))  # after Dask's own list
        return LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                            dashboard_address=None, silence_logs=logging.CRITICAL,
                            security=security, protocol="tls://", host="127.0.0.1")


def run_security() -> Any:
    """Dask's security for one local cluster: TLS both ways with a key and self-signed
    certificate made now, known to this process and its workers only (they receive them
    through the pipe that starts them). Made by ``cryptography`` when it is installed
    (``Security.temporary``), else by the ``openssl`` program."""
    from distributed.security import Security

    with contextlib.suppress(ImportError):
        return Security.temporary()
    openssl = shutil.which("openssl")
    if openssl is None:
        raise InputError("simulate --campaign: the local cluster is secured with TLS, which "
                         "needs the 'cryptography' package or the openssl program (or --serial)")
    with tempfile.TemporaryDirectory(prefix="txtool-tls-") as folder:
        key, cert = os.path.join(folder, "key.pem"), os.path.join(folder, "cert.pem")
        try:
            subprocess.run([openssl, "req", "-x509", "-newkey", "rsa:2048", "-nodes",
                            "-keyout", key, "-out", cert, "-days", "2",
                            "-subj", "/CN=dask-internal"],
                           check=True, capture_output=True, timeout=60)
            with open(key, encoding="ascii") as k, open(cert, encoding="ascii") as c:
                key_text, cert_text = k.read(), c.read()
        except (OSError, subprocess.SubprocessError) as exc:
            raise InputError(f"simulate --campaign: cannot make the local cluster's TLS "
                             f"certificate with {openssl}: {exc}") from None
    return Security(require_encryption=True, tls_ca_file=cert_text,
                    tls_client_key=key_text, tls_client_cert=cert_text,
                    tls_scheduler_key=key_text, tls_scheduler_cert=cert_text,
                    tls_worker_key=key_text, tls_worker_cert=cert_text)


def run_campaign(path: str, options: Options, where: Where) -> dict[str, Any]:
    """The campaign's JSON document (see docs/simulate.md, "Campaigns")."""
    campaign = read_campaign(path)
    tasks = tasks_of(campaign, options)
    records = execute(tasks, where)
    failed = next((r["error"] for r in records if "error" in r), None)
    if failed is not None:
        raise InputError(failed)
    count = len(draw(campaign))  # the tasks go candidate by candidate, sample by sample
    summaries = [summary(tasks[start].label, records[start : start + count])
                 for start in range(0, len(tasks), count)]
    bounds = {name: list(campaign.bounds[name]) for name in PARAMETERS if name in campaign.bounds}
    return {
        "verdict": _overall(s["verdict"] for s in summaries),
        "campaign": campaign.path,
        "robot": options.robot,
        "seed": campaign.seed,
        "samples": count,
        "bounds": bounds,
        "payload": ({"link": campaign.payload.link, "xyz": list(campaign.payload.xyz),
                     "xyz_units": "m"} if campaign.payload else None),
        "units": {name: PARAMETERS[name][0] for name in bounds},
        "candidates": summaries,
    }


def summary(label: str, runs: list[Record]) -> dict[str, Any]:
    """Counts, the smallest tracking margin and the first failing sample of one candidate."""
    counts = {v: sum(r["verdict"] == v for r in runs) for v in ("pass", "fail", "inconclusive")}
    scored = [r for r in runs if r["verdict"] != "inconclusive"]
    worst = min(scored, key=lambda r: -1e308 if r["margin"] is None else r["margin"],
                default=None)
    first = next((r for r in runs if r["verdict"] == "fail"), None)
    return {
        "config": label,
        "verdict": _overall(r["verdict"] for r in runs),
        "samples": len(runs), "passed": counts["pass"], "failed": counts["fail"],
        "inconclusive": counts["inconclusive"],
        "worst": None if worst is None else {
            key: worst[key] for key in ("sample", "margin", "joint", "max_error", "units")},
        "first_failure": None if first is None else {
            key: first[key] for key in ("sample", "perturbation", "reason")},
        "runs": runs,
    }


def _overall(verdicts: Any) -> str:
    found = set(verdicts)
    return next(v for v in ("fail", "inconclusive", "pass") if v in found)


def exit_code(document: dict[str, Any]) -> int:
    return {"pass": 0, "fail": 1, "inconclusive": EXIT_INCONCLUSIVE}[document["verdict"]]


def render_json(document: dict[str, Any], console: Console) -> None:
    console.file.write(json.dumps(document, indent=2, ensure_ascii=False) + "\n")


def render_text(document: dict[str, Any], console: Console) -> None:
    """A table of the candidates, then the first failure of each that failed."""
    table = Table(title=f"campaign: {_count(document['samples'], 'sample')} per candidate, "
                        f"seed {document['seed']}", title_justify="left")
    table.add_column("config", overflow="fold")
    table.add_column("verdict")
    for name in ("samples", "pass", "fail", "inconcl."):
        table.add_column(name, justify="right")
    table.add_column("worst tracking margin\n(% of tolerance left)", justify="right")
    for s in document["candidates"]:
        table.add_row(escape(s["config"]), VERDICT_CELL[s["verdict"]], str(s["samples"]),
                      str(s["passed"]), str(s["failed"]), str(s["inconclusive"]), _worst(s))
    console.print(table)
    units = document["units"]
    for s in document["candidates"]:
        first = s["first_failure"]
        if first is None:
            continue
        values = ", ".join(f"{name} {value:.4g} {units[name]}"
                           for name, value in first["perturbation"].items())
        console.print(f"{escape(s['config'])}: first failure at sample {first['sample']} "
                      f"({escape(values) or 'unperturbed'}): {escape(first['reason'])}",
                      soft_wrap=True)
    counts = [(s["failed"], s["samples"]) for s in document["candidates"]]
    failed, total = sum(f for f, _ in counts), sum(n for _, n in counts)
    line = {"fail": f"[bold red]FAIL[/]: {failed} of {_count(total, 'sample')} "
                    + ("fails" if failed == 1 else "fail"),
            "inconclusive": "[bold yellow]INCONCLUSIVE[/]: a candidate could not be checked",
            "pass": "[bold green]PASS[/]: " + ("the 1 sample passes" if total == 1
                                               else f"all {total} samples pass")}
    console.print(line[document["verdict"]])


def _count(number: int, noun: str) -> str:
    return f"{number} {noun}" + ("" if number == 1 else "s")


def _worst(s: dict[str, Any]) -> str:
    worst = s["worst"]
    if worst is None:
        return "-"
    margin = "diverged" if worst["margin"] is None else f"{100 * worst['margin']:.1f}%"
    return f"{margin} ({escape(worst['joint'])}, sample {worst['sample']})"


def main(path: str, options: Options, where: Where, output: str = "text") -> int:
    """Run the campaign, print it on stdout, return the exit code."""
    document = run_campaign(path, options, where)
    console = render.console()  # the terminal's width, or wide enough in a pipe
    if output == "json":
        render_json(document, console)
    else:
        render_text(document, console)
    return exit_code(document)
