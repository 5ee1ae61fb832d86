"""The budgets on what users run: growth, real sizes and memory, as ratios measured in one run.

Run: ``python bench/bench_scale.py [--sizes 1000,8000] [--shapes after,...] [--commands ...]
[--repeat 3]``.

Each document is one of the shapes of ``tests/shapes.py`` (the transmissions after the links and
joints, interleaved with them, on one line, CRLF, UTF-16, with comments between, prettified, with
a ``<ros2_control>`` block, as xacro writes them, the demo robot repeated). Each command runs
through txtool's entry point (``txtool.cli.main``, as the ``txtool`` command runs it) in a
fresh interpreter that first runs it on the one-transmission
document of the same shape (imports and first-call caches not counted) and then times the run
itself (processor seconds) and measures its peak memory above what it held before, the least
of ``--repeat`` runs of each; what it
writes goes to the null device, as a pipe would take it (nothing holds it). The floor is
``lxml.etree.parse`` of the same file, measured the same way (lxml imported before: the parse
is measured, not the import of the module).

Budgets (docs/performance.md): at the smallest size every command within 1 s; the growth
exponent between the smallest and the largest size at most 1.1; a conversion's peak memory (to
either proposal) at most 3x a parse's; and, with the corpus beside the repository, the
conversion of a real robot of 47 transmissions (tiago_pal-hey5.urdf) within 1.5x its
validation. Exit 1 if one is exceeded. Figures of one machine move by a fifth from run to run
under load: judge ratios.
"""

from __future__ import annotations

import argparse
import math
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from tests.shapes import SHAPES, robot  # noqa: E402

COMMANDS = {
    "convert": ["convert", "--to", "ros2-p2", "--no-xacro"],
    "convert-p1": ["convert", "--to", "ros2-p1", "--no-xacro"],
    "migrate-diff": ["migrate", "--diff", "--to", "ros2-p2", "--no-xacro"],
    "migrate-write": ["migrate", "--write", "--to", "ros2-p1", "--no-xacro"],
    "roundtrip": ["roundtrip", "--format", "json", "--no-xacro"],
    "show": ["show", "--format", "json", "--no-xacro"],
    "validate": ["validate", "--format", "json", "--jobs", "1", "--no-xacro"],
    "validate-fix": ["validate", "--fix", "--jobs", "1", "--no-xacro"],
}
REAL = ROOT.parent / "shared" / "corpus" / "tiago_robot__tiago_pal-hey5.urdf"

MEASURE = """
import contextlib, os, resource, shutil, sys, time
from lxml import etree  # imported before the figures start: a parse is measured, not an import
from txtool import cli
def rss():
    with open("/proc/self/status") as status:
        return next(int(line.split()[1]) for line in status if line.startswith("VmRSS"))
def run(argv):  # as the txtool command runs it, its output going where nothing holds it
    sys.argv = ["txtool", *argv]
    with open(os.devnull, "w") as sink, contextlib.redirect_stdout(sink), \\
            contextlib.redirect_stderr(sink):
        try:
            cli.main()
        except SystemExit as exit:
            return exit.code or 0
    return 0
warm_up, source, target, args = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4:]
if args and run([*args, warm_up]) not in (0, 1):  # loads what the command imports lazily
    sys.exit(f"{' '.join(args)}: the warm-up run failed")
shutil.copyfile(source, target)  # a command that writes starts from the original
before = rss()
start = time.process_time()
if args:
    code = run([*args, target])
    if code not in (0, 1):
        sys.exit(f"{' '.join(args)}: exit {code}")
else:
    tree = etree.parse(target)
elapsed = time.process_time() - start
print(elapsed, (resource.getrusage(resource.RUSAGE_SELF).ru_maxrss - before) * 1024)
"""


def measure(args: list[str], source: Path, warm_up: Path) -> tuple[float, float]:
    """Processor seconds and peak bytes of ``txtool ARGS`` on a copy of ``source`` (no
    ``args``: a bare parse), in a fresh interpreter warmed up on ``warm_up``."""
    target = source.with_suffix(".urdf")
    argv = [sys.executable, "-c", MEASURE, str(warm_up), str(source), str(target), *args]
    out = subprocess.run(argv, capture_output=True, text=True, check=False,
                         env={"PYTHONPATH": str(ROOT), "PATH": "/usr/bin:/bin"})
    if out.returncode != 0:
        raise SystemExit(out.stderr.strip() or f"{' '.join(args)}: exit {out.returncode}")
    seconds, peak = out.stdout.strip().splitlines()[-1].split()
    return float(seconds), float(peak)


def least(args: list[str], source: Path, warm_up: Path, repeat: int) -> tuple[float, float]:
    """The least processor time and peak memory of ``repeat`` runs of :func:`measure`: what
    other work on the machine adds to a run is never negative, so the least is the run's own
    cost (as ``timeit`` takes it)."""
    runs = [measure(args, source, warm_up) for _ in range(repeat)]
    return min(run[0] for run in runs), min(run[1] for run in runs)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", default="1000,8000")
    parser.add_argument("--shapes", default=",".join(SHAPES))
    parser.add_argument("--commands", default=",".join(COMMANDS))
    parser.add_argument("--repeat", type=int, default=3,
                        help="runs of each command and size; the least time and memory count")
    options = parser.parse_args()
    sizes = [int(size) for size in options.sizes.split(",")]
    small, large = sizes[0], sizes[-1]
    folder = Path(tempfile.mkdtemp())
    failures = []
    print(f"{'shape':13} {'command':14} " + " ".join(f"{size:>8}" for size in sizes)
          + "  exponent  memory/parse")
    for shape in options.shapes.split(","):
        warm_up = folder / f"{shape}_1.source"
        warm_up.write_bytes(robot(shape, 1))
        sources = {}
        for size in sizes:
            sources[size] = folder / f"{shape}_{size}.source"
            sources[size].write_bytes(robot(shape, size))
        parse_peak = least([], sources[large], warm_up, options.repeat)[1]
        for name in options.commands.split(","):
            figures = {size: least(COMMANDS[name], sources[size], warm_up, options.repeat)
                       for size in sizes}
            exponent = (math.log(figures[large][0] / figures[small][0]) / math.log(large / small)
                        if large != small else math.nan)  # one size: no growth to measure
            memory = figures[large][1] / parse_peak
            print(f"{shape:13} {name:14} " + " ".join(f"{figures[s][0]:8.3f}" for s in sizes)
                  + f"  {exponent:8.2f}  {memory:12.1f}", flush=True)
            if figures[small][0] > 1.0:
                failures.append(f"{shape} {name}: {figures[small][0]:.2f} s at {small}")
            if exponent > 1.1:
                failures.append(f"{shape} {name}: exponent {exponent:.2f}")
            if name.startswith("convert") and memory > 3:
                failures.append(f"{shape} {name}: memory {memory:.1f}x a parse")
    if REAL.is_file():
        real = folder / "real.source"
        real.write_bytes(REAL.read_bytes())
        convert = min(measure(COMMANDS["convert"], real, real)[0] for _ in range(3))
        validate = min(measure(COMMANDS["validate"], real, real)[0] for _ in range(3))
        print(f"{REAL.name}: convert {convert:.3f} s, validate {validate:.3f} s, "
              f"ratio {convert / validate:.2f}")
        if convert > 1.5 * validate:
            failures.append(f"{REAL.name}: convert {convert / validate:.2f}x validate")
    for failure in failures:
        print("over budget:", failure)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
