"""``txtool simulate --campaign``: serial against a local Dask cluster on this machine's cores.

Run: ``python bench/bench_campaign.py [ROBOT.urdf [SAMPLES]]`` (default: the corpus UR5e,
``../shared/corpus/universal_robot__ur5e.urdf``, 8 samples of a payload on its wrist, extra
joint friction and damping, scaled gains and sensor noise). Three measurements of the same
tasks, in one run, so that they share the machine's load:

- ``serial``: :func:`txtool.simulation.campaign.execute` with ``--serial``, the floor;
- ``cluster``: the same on an embedded ``LocalCluster`` of one worker per usable core, as the
  command runs it: starting the cluster, its workers, and closing it included;
- ``warm``: the tasks alone on a cluster already running (a real cluster's case), with the
  CPU time each worker spent on them.

It prints the wall time of each and its speed-up against the serial floor, and checks that the
three give the same records. On a machine that other jobs keep busy, wall times mostly show
their load (the 1-minute load average is printed before and after); CPU times do not: on idle
cores the tasks take about as long as the busiest worker's CPU time, so serial CPU time
against that is the speed-up the cores give, and the workers' sum against serial CPU time is
what distributing costs.
"""

from __future__ import annotations

import os
import resource
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from txtool.simulation import campaign  # noqa: E402
from txtool.simulation.campaign_file import read_campaign  # noqa: E402
from txtool.simulation.jobs import usable_cpus  # noqa: E402
from txtool.simulation.run import Options  # noqa: E402

UR5E = ROOT.parent / "shared" / "corpus" / "universal_robot__ur5e.urdf"
CAMPAIGN = """seed = 1
samples = {samples}
[bounds]
damping = [0.0, 0.05]
friction = [0.0, 0.05]
gains = [0.8, 1.2]
sensor_noise = [0.0, 2e-5]
[bounds.payload]
link = "{link}"
mass = [0.0, 3.0]
xyz = [0.0, 0.0, 0.05]
"""


def cpu_seconds() -> float:
    """CPU time of this process and of its finished children."""
    own, children = (resource.getrusage(who)
                     for who in (resource.RUSAGE_SELF, resource.RUSAGE_CHILDREN))
    return own.ru_utime + own.ru_stime + children.ru_utime + children.ru_stime


def timed(function, *args):  # type: ignore[no-untyped-def]
    wall, cpu = time.perf_counter(), cpu_seconds()
    result = function(*args)
    return result, time.perf_counter() - wall, cpu_seconds() - cpu


def own_cpu() -> float:
    used = resource.getrusage(resource.RUSAGE_SELF)
    return used.ru_utime + used.ru_stime


def warm(tasks: list, workers: int):  # type: ignore[no-untyped-def]
    """The tasks on a cluster started beforehand: (records, wall, CPU seconds per worker)."""
    from distributed import Client

    with campaign.local_cluster(workers) as cluster, Client(cluster) as client:
        before = client.run(own_cpu)  # also: every worker is up
        started = time.perf_counter()
        records = client.gather(client.map(campaign.run_sample, tasks, pure=False))
        wall = time.perf_counter() - started
        after = client.run(own_cpu)
        return records, wall, sorted(after[w] - before[w] for w in before)


def main(robot: str, samples: int, link: str) -> None:
    workers = usable_cpus()
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "campaign.toml"
        path.write_text(CAMPAIGN.format(samples=samples, link=link))
        tasks = campaign.tasks_of(read_campaign(str(path)), Options(robot=robot))
    print(f"{Path(robot).name}: {len(tasks)} samples, {workers} workers (usable cores); "
          f"load average {os.getloadavg()[0]:.2f}")
    floor, serial_wall, serial_cpu = timed(campaign.execute, tasks, campaign.Where(serial=True))
    cold, cold_wall, _ = timed(campaign.execute, tasks, campaign.Where(workers=workers))
    hot, hot_wall, worker_cpu = warm(tasks, workers)
    assert cold == floor and hot == floor, "a cluster's records differ from the serial ones"
    busiest = max(worker_cpu)
    print("| run | wall | speed-up against serial (wall) |")
    print("|---|---|---|")
    print(f"| serial | {serial_wall:.1f} s | 1.00x |")
    print(f"| LocalCluster, started and closed | {cold_wall:.1f} s | "
          f"{serial_wall / cold_wall:.2f}x |")
    print(f"| LocalCluster, running already | {hot_wall:.1f} s | {serial_wall / hot_wall:.2f}x |")
    cpus = " + ".join(f"{c:.1f}" for c in worker_cpu)
    print(f"CPU: serial {serial_cpu:.1f} s; workers {cpus} s (sum {sum(worker_cpu):.1f} s); "
          f"serial / busiest worker: {serial_cpu / busiest:.2f}x")
    print(f"records identical: yes; load average {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    given = sys.argv[1:]
    main(given[0] if given else str(UR5E), int(given[1]) if len(given) > 1 else 8,
         given[2] if len(given) > 2 else "wrist_3_link")
