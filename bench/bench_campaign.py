"""``txtool simulate --campaign``: serial against a local Dask cluster on this machine's cores.

Run: ``python bench/bench_campaign.py [ROBOT.urdf [SAMPLES]]`` (default: the corpus UR5e,
``../shared/corpus/universal_robot__ur5e.urdf``, 8 samples of a payload on its wrist, extra
joint friction and damping, scaled gains and sensor noise). Three measurements of the same
tasks, in one run, so that they share the machine's load:

- ``serial``: :func:`txtool.simulation.campaign.execute` with ``--serial``, the floor;
- ``cluster``: the same on an embedded ``LocalCluster`` of one worker per usable core, as the
  command runs it: starting the cluster, its workers, and closing it included;
- ``warm``: the tasks alone on a cluster already running (a real cluster's case).

It prints the wall and CPU time of each, the speed-up of each against the serial floor, and
checks that the three give the same records. The 1-minute load average is printed before and
after: on a busy machine the cores are shared, and the speed-up shows it.
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


def warm(tasks: list, workers: int):  # type: ignore[no-untyped-def]
    """The tasks on a cluster started beforehand: (records, wall, None)."""
    from distributed import Client

    with campaign.local_cluster(workers) as cluster, Client(cluster) as client:
        client.run(lambda: None)  # every worker up
        started = time.perf_counter()
        records = client.gather(client.map(campaign.run_sample, tasks, pure=False))
        return records, time.perf_counter() - started, None


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
    hot, hot_wall, _ = warm(tasks, workers)
    assert cold == floor and hot == floor, "a cluster's records differ from the serial ones"
    print("| run | wall | speed-up against serial |")
    print("|---|---|---|")
    print(f"| serial | {serial_wall:.1f} s (CPU {serial_cpu:.1f} s) | 1.00x |")
    print(f"| LocalCluster, started and closed | {cold_wall:.1f} s | "
          f"{serial_wall / cold_wall:.2f}x |")
    print(f"| LocalCluster, running already | {hot_wall:.1f} s | {serial_wall / hot_wall:.2f}x |")
    print(f"records identical: yes; load average {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    given = sys.argv[1:]
    main(given[0] if given else str(UR5E), int(given[1]) if len(given) > 1 else 8,
         given[2] if len(given) > 2 else "wrist_3_link")
