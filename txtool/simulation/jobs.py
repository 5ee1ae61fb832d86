"""Several configs at once: ``--jobs`` forks of this process, once everything is imported.

A fork inherits the loaded modules (numpy, pinocchio, this package), so a worker starts in a
few milliseconds, where a fresh interpreter takes 0.3-0.5 s to import them: the reason an
earlier spawn-based pool made ``-j 2`` slower than ``-j 1``. Configs go out one at a time
(:func:`txtool.lint.workers.forked_map`), this process works too, and the results come back in
the order of the configs. The first config is prepared before any fork, so the first call's
costs are paid once. There are never more processes than configs or idle CPUs (a machine that
is already busy gains nothing from more); runs whose loop takes less than a fork costs, and
every run where ``os.fork`` is missing (Windows), go one after the other.
"""

from __future__ import annotations

import os

from txtool.lint.workers import forked_map
from txtool.simulation.result import RunResult
from txtool.simulation.run import (
    Options,
    Prepared,
    Progress,
    Unchecked,
    candidates,
    complete,
    prepare,
)

MIN_LOOP_S = 0.005  # a fork costs about 10 ms of CPU: shorter runs go one after the other


def usable_cpus() -> int:
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # pragma: no cover - macOS, Windows
        return os.cpu_count() or 1


def idle_cpus() -> int:
    """Usable CPUs minus those the rest of the machine keeps busy (1-minute load average)."""
    cpus = usable_cpus()
    try:
        others = max(os.getloadavg()[0] - 1.0, 0.0)  # this process is part of the load
    except (AttributeError, OSError):  # pragma: no cover - no load average
        return cpus
    return max(1, min(cpus, cpus - int(others + 0.5)))


def processes_for(jobs: int, configs: int) -> int:
    """At most ``jobs``, one per config, and one per idle CPU: a busy machine gains nothing
    from more processes, and each costs a fork and the pickling of its results."""
    if jobs <= 1 or configs <= 1 or not hasattr(os, "fork"):
        return 1
    return max(1, min(jobs, configs, idle_cpus()))


def loop_seconds(p: Prepared | Unchecked) -> float:
    """A rough cost of a prepared run's loop: about 4 + 0.6 nv µs a step (docs/simulate.md,
    "Performance")."""
    if isinstance(p, Unchecked):
        return 0.0
    return p.plan.steps * (4.0 + 0.6 * p.robot.nv) * 1e-6


def execute(options: Options, progress: Progress | None = None) -> list[RunResult]:
    """All runs, in the order of the configs, from up to ``options.jobs`` processes."""
    pairs = candidates(options)
    first = prepare(options, *pairs[0])  # also pays the first call's costs once, before forks
    if len(pairs) == 1:
        return [complete(first, progress)]
    processes = processes_for(options.jobs, len(pairs))
    if loop_seconds(first) < MIN_LOOP_S:
        processes = 1  # a fork costs about as much as such a run saves
    parent = os.getpid()
    done = 0

    def one(index: int) -> RunResult:
        nonlocal done
        run = complete(first if index == 0 else prepare(options, *pairs[index]))
        # Only this process draws progress (a fork must not touch the bar's thread and lock);
        # it counts its own runs, a lower bound while the forks work.
        if progress is not None and os.getpid() == parent:
            done += 1
            progress(done, len(pairs))
        return run

    if processes == 1:
        return [one(i) for i in range(len(pairs))]
    runs = list(forked_map(one, len(pairs), processes, size=1))
    if progress is not None:
        progress(len(pairs), len(pairs))
    return runs
