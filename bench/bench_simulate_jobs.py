"""``txtool simulate --jobs``: wall time with 1, 2 and 4 processes for 1, 2 and 4 configs.

Run: ``python bench/bench_simulate_jobs.py [ROBOT.urdf ...]`` (default:
``fixtures/demo_robot.urdf``). Each config is the robot itself, so every run does the same work.
Two measurements, the settings alternated within each round and the best of ``REPEAT`` kept:

- ``in-process``: :func:`txtool.simulation.jobs.execute` after the imports, the part ``--jobs``
  can change;
- ``forced``: the same with forks even when the machine looks busy (``idle_cpus`` patched to
  all usable CPUs), to show what a fork costs or saves;
- ``command``: the whole ``txtool simulate`` command in a fresh interpreter, as a user sees it;
- ``cpu``: with forks forced and ``-j 2``, the CPU time of this process and of its fork. On a
  busy machine wall times mostly show the others' load; on idle CPUs a run takes about as long
  as its busiest process, so ``max(this, fork)`` against ``-j 1``'s CPU time is what ``-j 2``
  gains, and ``this + fork`` against it is what forking costs.

The 1-minute load average is printed before and after: on a busy machine ``--jobs`` falls back
to fewer processes, and the figures mostly show the others' load.
"""

from __future__ import annotations

import os
import resource
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from txtool.simulation import jobs  # noqa: E402
from txtool.simulation.jobs import execute  # noqa: E402
from txtool.simulation.run import Options  # noqa: E402

REPEAT = 7
CONFIGS = (1, 2, 4)
JOBS = (1, 2, 4)


def in_process(robot: str, configs: int, jobs: int) -> float:
    options = Options(robot=robot, configs=(robot,) * configs, jobs=jobs, keep_series=False)
    started = time.perf_counter()
    execute(options)
    return time.perf_counter() - started


def forced(robot: str, configs: int, jobs_asked: int) -> float:
    idle = jobs.idle_cpus
    jobs.idle_cpus = jobs.usable_cpus
    try:
        return in_process(robot, configs, jobs_asked)
    finally:
        jobs.idle_cpus = idle


def cpu_split(robot: str, configs: int, jobs_asked: int) -> tuple[float, float]:
    """(CPU seconds of this process, of its forks) for one forced run."""
    before = resource.getrusage(resource.RUSAGE_SELF), resource.getrusage(resource.RUSAGE_CHILDREN)
    forced(robot, configs, jobs_asked)
    after = resource.getrusage(resource.RUSAGE_SELF), resource.getrusage(resource.RUSAGE_CHILDREN)
    used = [a.ru_utime + a.ru_stime - b.ru_utime - b.ru_stime
            for a, b in zip(after, before, strict=True)]
    return used[0], used[1]


def command(robot: str, configs: int, jobs: int) -> float:
    args = [sys.executable, "-m", "txtool", "simulate", robot, "-j", str(jobs)]
    for _ in range(configs):
        args += ["--config", robot]
    started = time.perf_counter()
    subprocess.run(args, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=False,
                   cwd=ROOT)
    return time.perf_counter() - started


def main(robots: list[str]) -> None:
    print(f"load average {os.getloadavg()[0]:.2f}, usable CPUs {jobs.usable_cpus()}")
    print("| robot | configs | measure | " + " | ".join(f"-j {j}" for j in JOBS) + " |")
    print("|---|---|---|" + "---|" * len(JOBS))
    for robot in robots:
        for configs in CONFIGS:
            for name, measure in (("in-process", in_process), ("forced", forced),
                                  ("command", command)):
                best = {j: float("inf") for j in JOBS}
                for _ in range(REPEAT):
                    for j in JOBS:
                        best[j] = min(best[j], measure(robot, configs, j))
                cells = " | ".join(f"{1000 * best[j]:.0f} ms" for j in JOBS)
                print(f"| {Path(robot).name} | {configs} | {name} | {cells} |", flush=True)
    print("\n| robot | configs | -j 1 CPU | -j 2: this + fork CPU | busiest |")
    print("|---|---|---|---|---|")
    for robot in robots:
        for configs in CONFIGS[1:]:
            one = min(sum(cpu_split(robot, configs, 1)) for _ in range(REPEAT))
            split = min((cpu_split(robot, configs, 2) for _ in range(REPEAT)), key=max)
            print(f"| {Path(robot).name} | {configs} | {1000 * one:.0f} ms | "
                  f"{1000 * split[0]:.0f} + {1000 * split[1]:.0f} ms | "
                  f"{1000 * max(split):.0f} ms |", flush=True)
    print(f"load average {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main(sys.argv[1:] or [str(ROOT / "fixtures" / "demo_robot.urdf")])
