"""Work grows linearly with the document: time per transmission from 100 to 100,000.

Run: ``python bench/bench_scale.py [--sizes 100,1000,10000,100000] [--commands ...]``.

Each size N is one generated robot: a chain of N revolute joints, each driven by one ROS 1
simple transmission (about 450 bytes per joint: 100,000 joints make a 45 MB file, under the 64 MB
input limit). Each command runs once per size, through the command line (click), in a fresh
interpreter that times the run itself (start-up and imports not counted); the table shows
microseconds per transmission and the ratio of each size to the smallest. Flat means linear; a
step quadratic in N shows as ratios near 10, 100 and 1,000 (a large process's cache and
garbage-collector effects alone stay below 2).
"""

from __future__ import annotations

import argparse
import json
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


def robot(joints: int) -> str:
    parts = ['<robot name="chain">', LINK.format(i=0)]
    parts += [LINK.format(i=i) + JOINT.format(i=i, p=i - 1) for i in range(1, joints + 1)]
    parts += [TRANSMISSION.format(i=i, n=10 + i % 90) for i in range(1, joints + 1)]
    return "\n".join(parts) + "\n</robot>\n"


MEASURE = """
import sys, time
from click.testing import CliRunner
from txtool.cli import cli
warm_up, args = sys.argv[1], sys.argv[2:]
runner = CliRunner()
runner.invoke(cli, [*args[:-1], warm_up])  # loads what the command imports lazily
start = time.perf_counter()
result = runner.invoke(cli, args)
elapsed = time.perf_counter() - start
crashed = result.exception is not None and not isinstance(result.exception, SystemExit)
if crashed or result.exit_code not in (0, 1):
    sys.exit(f"{' '.join(args)}: exit {result.exit_code}: {result.output[:500]}")
print(elapsed)
"""


def measure(command: list[str], path: Path) -> float:
    """Seconds of one run, in a fresh interpreter that first ran the command on a one-joint
    robot (imports and start-up not counted), so that one run's leftovers do not slow the next."""
    warm_up = path.with_name("warm_up.urdf")
    warm_up.write_text(robot(1))
    args = [*command, str(path)]
    out = subprocess.run([sys.executable, "-c", MEASURE, str(warm_up), *args],
                         capture_output=True, text=True, check=False)
    if out.returncode != 0:
        raise SystemExit(out.stderr.strip() or f"{' '.join(args)}: exit {out.returncode}")
    return float(out.stdout.strip().splitlines()[-1])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", default="100,1000,10000,100000")
    parser.add_argument("--commands", default=",".join(COMMANDS))
    args = parser.parse_args()
    sizes = [int(s) for s in args.sizes.split(",")]
    commands = args.commands.split(",")
    table: dict[str, dict[int, float]] = {name: {} for name in commands}
    with tempfile.TemporaryDirectory(prefix="txtool-scale-") as folder:
        for size in sizes:
            path = Path(folder) / f"chain_{size}.urdf"
            path.write_text(robot(size))
            megabytes = path.stat().st_size / 1e6
            for name in commands:
                table[name][size] = measure(COMMANDS[name], path) / size
            print(f"N={size:>7} ({megabytes:5.1f} MB): " + "  ".join(
                f"{name} {table[name][size] * 1e6:7.1f} us" for name in commands), flush=True)
    smallest = min(sizes)
    print(f"\nratio of time per transmission to N={smallest} "
          f"(flat = linear, quadratic ~N/{smallest}):")
    for name in commands:
        ratios = {size: table[name][size] / table[name][smallest] for size in sizes}
        print(f"  {name:10s} " + "  ".join(f"N={s}: {r:4.2f}" for s, r in ratios.items()))
    print(json.dumps({name: {str(s): t for s, t in row.items()} for name, row in table.items()}),
          file=sys.stderr)


if __name__ == "__main__":
    main()
