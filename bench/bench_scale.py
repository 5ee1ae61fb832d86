"""Work grows linearly with the document: time per transmission from 100 to 100,000.

Run: ``python bench/bench_scale.py [--sizes 100,1000,10000,100000] [--commands ...]
[--repeat R] [--pretty] [--as-written] [--instructions]``.

Each size N is one generated robot: a chain of N revolute joints, each driven by one ROS 1
simple transmission (about 450 bytes per joint: 100,000 joints make a 45 MB file, under the 64
MB input limit); with ``--pretty`` every element is on a line of its own (about 700 bytes per
joint), the repetitive lines a line diff has to align; with ``--as-written`` the file has an XML
declaration, a comment and single quotes, as people write robots (the default chain is byte for
byte what lxml writes, which a writer may take a shortcut on). Each command runs through the
command line (click), in a fresh interpreter that times the run itself (start-up and imports not
counted) and measures its peak memory above what the interpreter held before the run. The floor
is ``lxml.etree.parse`` of the same file, timed and measured the same way; runs are interleaved
and each figure is the median of R runs (default 1). The tables show microseconds per
transmission, each size's ratio to the smallest (flat means linear; a step quadratic in N shows
as ratios near 10, 100 and 1,000), and each command's time and peak memory against the floor;
with R > 1, also the fastest and the slowest of the command's runs against the floor's median,
which shows how far one run strays on a shared machine.

Wall time on a shared machine moves by a fifth from run to run. ``--instructions`` counts
instead (valgrind's callgrind, one run each; one to two minutes a command at 20,000): each
command's instructions and the floor's, each less those of the same process given the one-joint
robot (start-up, imports and the warm-up are then counted out), and their ratio. The same code
and input give the same count to about half a per cent (Python's hash randomization); it leaves
out what an instruction count cannot see (page faults, caches), which the wall time holds.
"""

from __future__ import annotations

import argparse
import json
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

LINK = '<link name="l{i}"/>'
JOINT = ('<joint name="j{i}" type="revolute"><parent link="l{p}"/><child link="l{i}"/>'
         '<limit lower="-1" upper="1" effort="10" velocity="2"/></joint>')
TRANSMISSION = (
    '<transmission name="t{i}"><type>transmission_interface/SimpleTransmission</type>'
    '<joint name="j{i}"><hardwareInterface>hardware_interface/EffortJointInterface'
    '</hardwareInterface></joint><actuator name="m{i}"><mechanicalReduction>{n}'
    "</mechanicalReduction></actuator></transmission>"
)
COMMANDS = {
    "validate": ["validate", "--format", "json", "--jobs", "1"],
    "show": ["show", "--format", "json"],
    "convert": ["convert", "--to", "ros2-p2"],
    "roundtrip": ["roundtrip"],
    "migrate": ["migrate", "--diff", "--to", "ros2-p2"],
}


def robot(joints: int, pretty: bool = False, as_written: bool = False) -> str:
    parts = ['<robot name="chain">', LINK.format(i=0)]
    parts += [LINK.format(i=i) + JOINT.format(i=i, p=i - 1) for i in range(1, joints + 1)]
    parts += [TRANSMISSION.format(i=i, n=10 + i % 90) for i in range(1, joints + 1)]
    text = "\n".join(parts) + "\n</robot>\n"
    text = text.replace("><", ">\n<") if pretty else text
    if as_written:  # as people write robots, not as lxml writes them
        text = '<?xml version="1.0"?>\n<!-- a robot -->\n' + text.replace('"', "'")
    return text


PRELUDE = """
import resource, sys, time
def rss():
    with open("/proc/self/status") as status:
        return next(int(line.split()[1]) for line in status if line.startswith("VmRSS"))
"""
MEASURE = PRELUDE + """
from click.testing import CliRunner
from txtool.cli import cli
warm_up, args = sys.argv[1], sys.argv[2:]
runner = CliRunner()
runner.invoke(cli, [*args[:-1], warm_up])  # loads what the command imports lazily
before = rss()
start = time.perf_counter()
result = runner.invoke(cli, args)
elapsed = time.perf_counter() - start
crashed = result.exception is not None and not isinstance(result.exception, SystemExit)
if crashed or result.exit_code not in (0, 1):
    sys.exit(f"{' '.join(args)}: exit {result.exit_code}: {result.output[:500]}")
print(elapsed, (resource.getrusage(resource.RUSAGE_SELF).ru_maxrss - before) * 1024)
"""
PARSE = PRELUDE + """
from lxml import etree
before = rss()
start = time.perf_counter()
tree = etree.parse(sys.argv[1])
elapsed = time.perf_counter() - start
print(elapsed, (resource.getrusage(resource.RUSAGE_SELF).ru_maxrss - before) * 1024)
"""


def measure(command: list[str] | None, path: Path) -> tuple[float, float]:
    """Seconds and peak bytes of one run, in a fresh interpreter that first ran the command on
    a one-joint robot (imports and start-up not counted), so that one run's leftovers do not
    slow the next; ``None`` is the floor, a bare parse of the file."""
    argv = _argv(command, path, _warm_up(path))
    out = subprocess.run(argv, capture_output=True, text=True, check=False)
    if out.returncode != 0:
        raise SystemExit(out.stderr.strip() or f"{' '.join(argv[3:])}: exit {out.returncode}")
    seconds, peak = out.stdout.strip().splitlines()[-1].split()
    return float(seconds), float(peak)


def _warm_up(path: Path) -> Path:
    """The one-joint robot beside ``path``, which a command runs on first."""
    warm_up = path.with_name("warm_up.urdf")
    warm_up.write_text(robot(1))
    return warm_up


def _argv(command: list[str] | None, target: Path, warm_up: Path) -> list[str]:
    """The fresh interpreter that runs ``command`` on ``target`` after ``warm_up`` (None: the
    floor, a bare parse of ``target``)."""
    if command is None:
        return [sys.executable, "-c", PARSE, str(target)]
    return [sys.executable, "-c", MEASURE, str(warm_up), *command, str(target)]


def instructions(command: list[str] | None, path: Path) -> int:
    """Instructions the command (None: the floor) executes on ``path``, less those of the same
    process on the one-joint robot (valgrind's callgrind)."""
    warm_up = _warm_up(path)
    counts = []
    for target in (path, warm_up):
        out = subprocess.run(["valgrind", "--tool=callgrind", "--callgrind-out-file=/dev/null",
                              *_argv(command, target, warm_up)],
                             capture_output=True, text=True, check=False)
        found = re.search(r"Collected : (\d+)", out.stderr)
        if out.returncode != 0 or found is None:
            raise SystemExit(out.stderr.strip()[-500:] or f"valgrind: exit {out.returncode}")
        counts.append(int(found.group(1)))
    return counts[0] - counts[1]


def count_instructions(sizes: list[int], names: list[str], pretty: bool,
                       as_written: bool) -> None:
    """``--instructions``: each command's instructions against the floor's, per size."""
    if shutil.which("valgrind") is None:
        raise SystemExit("--instructions needs valgrind on PATH")
    with tempfile.TemporaryDirectory(prefix="txtool-scale-") as folder:
        for size in sizes:
            path = Path(folder) / f"chain_{size}.urdf"
            path.write_text(robot(size, pretty, as_written))
            floor = instructions(None, path)
            print(f"N={size:>7}: parse {floor / 1e6:,.0f}M instructions", flush=True)
            for name in names[1:]:
                count = instructions(COMMANDS[name], path)
                print(f"  {name:10s} {count / 1e6:,.0f}M: {count / floor:.2f}x the parse",
                      flush=True)


def _runs(spread: tuple[float, float], floor: float) -> str:
    """The fastest and the slowest run of a command against the floor's median."""
    return f" (runs {spread[0] / floor:.1f}-{spread[1] / floor:.1f}x)"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", default="100,1000,10000,100000")
    parser.add_argument("--commands", default=",".join(COMMANDS))
    parser.add_argument("--repeat", type=int, default=1)
    parser.add_argument("--pretty", action="store_true", help="one element per line")
    parser.add_argument("--as-written", action="store_true",
                        help="an XML declaration, a comment and single quotes: a file that "
                             "lxml would not write byte for byte")
    parser.add_argument("--instructions", action="store_true",
                        help="count instructions under valgrind instead of timing")
    args = parser.parse_args()
    sizes = [int(s) for s in args.sizes.split(",")]
    names = ["parse", *args.commands.split(",")]
    if args.instructions:
        count_instructions(sizes, names, args.pretty, args.as_written)
        return
    seconds: dict[str, dict[int, float]] = {name: {} for name in names}
    spread: dict[str, dict[int, tuple[float, float]]] = {name: {} for name in names}
    memory: dict[str, dict[int, float]] = {name: {} for name in names}
    with tempfile.TemporaryDirectory(prefix="txtool-scale-") as folder:
        for size in sizes:
            path = Path(folder) / f"chain_{size}.urdf"
            path.write_text(robot(size, args.pretty, args.as_written))
            megabytes = path.stat().st_size / 1e6
            runs: dict[str, list[tuple[float, float]]] = {name: [] for name in names}
            for _ in range(args.repeat):  # interleaved: load changes hit every command alike
                for name in names:
                    runs[name].append(measure(COMMANDS.get(name), path))
            for name in names:
                seconds[name][size] = statistics.median(t for t, _ in runs[name])
                spread[name][size] = (min(t for t, _ in runs[name]),
                                      max(t for t, _ in runs[name]))
                memory[name][size] = statistics.median(m for _, m in runs[name])
            print(f"N={size:>7} ({megabytes:5.1f} MB): " + "  ".join(
                f"{name} {seconds[name][size] / size * 1e6:7.1f} us" for name in names),
                flush=True)
    smallest = min(sizes)
    print(f"\nratio of time per transmission to N={smallest} "
          f"(flat = linear, quadratic ~N/{smallest}):")
    for name in names:
        ratios = {s: seconds[name][s] * smallest / s / seconds[name][smallest] for s in sizes}
        print(f"  {name:10s} " + "  ".join(f"N={s}: {r:4.2f}" for s, r in ratios.items()))
    print("\nagainst the floor (a bare lxml parse of the same file): time x, peak memory x "
          "(MB)")
    for name in names[1:]:
        print(f"  {name:10s} " + "  ".join(
            f"N={s}: {seconds[name][s] / seconds['parse'][s]:5.1f}x"
            f"{_runs(spread[name][s], seconds['parse'][s]) if args.repeat > 1 else ''} "
            f"{memory[name][s] / max(memory['parse'][s], 1):4.1f}x "
            f"({memory[name][s] / 1e6:.0f})" for s in sizes))
    print(json.dumps({"seconds": {n: {str(s): t for s, t in row.items()}
                                  for n, row in seconds.items()},
                      "peak_bytes": {n: {str(s): m for s, m in row.items()}
                                     for n, row in memory.items()}}), file=sys.stderr)


if __name__ == "__main__":
    main()
