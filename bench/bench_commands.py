"""Cost of ``show --format json`` and ``roundtrip`` on one robot, against the import floor.

Run: ``python bench/bench_commands.py [--repeat R] [--robot FILE]``.

Each command runs as a fresh process on one robot (default: the generated 7-DoF arm of
``bench_validate.py``), interleaved with ``python -c "import click, lxml.etree, pydantic,
rich"`` (the floor: what any txtool command imports to start), so that load changes hit both
alike. Prints the median wall time of each over R runs (default 21) and each command's ratio to
the floor (budget: at most 1.5). txtool is byte-compiled first, as installing it does.
"""

from __future__ import annotations

import argparse
import json
import statistics
import sys
import tempfile
from pathlib import Path

from bench_validate import BASELINE, synthetic_arm, txtool_command, wall
from installed import byte_compile

COMMANDS = {
    "show --format json": ["show", "--format", "json"],
    "roundtrip": ["roundtrip"],
}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=21)
    parser.add_argument("--robot", help="a URDF (default: a generated 7-DoF arm)")
    args = parser.parse_args()
    byte_compile()
    with tempfile.TemporaryDirectory() as folder:
        robot = Path(args.robot) if args.robot else Path(folder) / "arm.urdf"
        if not args.robot:
            robot.write_text(synthetic_arm())
        times: dict[str, list[float]] = {"floor": [], **{name: [] for name in COMMANDS}}
        for _ in range(args.repeat):
            times["floor"].append(wall([sys.executable, "-c", BASELINE]))
            for name, command in COMMANDS.items():
                times[name].append(wall([*txtool_command(), *command, str(robot)]))
    median = {name: statistics.median(values) for name, values in times.items()}
    print(f"floor ({BASELINE}): {median['floor'] * 1000:.0f} ms")
    for name in COMMANDS:
        print(f"{name}: {median[name] * 1000:.0f} ms, ratio "
              f"{median[name] / median['floor']:.2f} (budget 1.5)")
    print(json.dumps({name: {"median_s": m, "ratio": m / median["floor"]}
                      for name, m in median.items()}))


if __name__ == "__main__":
    main()
