"""The smallest fault of each kind that a simulate run shows in the motion itself.

Run: ``python bench/fault_thresholds.py [--duration S] [--tolerance X] [--corpus NAME ...]``.

A candidate whose maps differ from the robot's always fails: the maps are compared exactly
(a reduction off by a relative 1e-9, an offset off by 1e-12 rad). This script measures the
other half, what the *motion* shows: the smallest fault for which the run has a symptom of its
own (a tracking error beyond the tolerance, an effort or speed limit, a position limit, the
effort-path check, a divergence), not only the comparison of the maps. For each robot it edits
the first simulated transmission (or the one of ``--joint``) of the robot's own config
(``tests/simulate/faults.py``) and bisects:

* the reduction factor above 1 (in (1, 2]) and below 1 (in [0.5, 1));
* the joint offset (in (0, 0.3] rad or m).

Then it runs each discrete fault once (sign reversed, joints swapped, roles swapped, another
effort convention, a joint removed, the interface changed) and says whether the motion shows
it ("compared only": the run fails on the comparison of the configs alone). Every candidate
follows the robot's own default motion (planned once, then given as a trajectory), with the
default gains and ``--tolerance``.
"""

from __future__ import annotations

import argparse
import sys
import tempfile
from collections.abc import Callable
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from tests.simulate.faults import (  # noqa: E402
    FAULTS,
    inject,
    with_offset,
    with_reduction_factor,
)
from tests.simulate.generated_robots import (  # noqa: E402
    CHAIN,
    COUNTERBALANCED,
    DIFFERENTIAL,
    FOUR_BAR,
)
from txtool.simulation.result import RunResult  # noqa: E402
from txtool.simulation.run import Options, simulate_one  # noqa: E402

CORPUS = ROOT.parent / "shared" / "corpus"
STEPS = 14  # bisection steps: the bracket shrinks 16384 times
NOT_SYMPTOMS = ("likely cause: ", "the config's maps differ from the robot's")
DISCRETE = [f for f in FAULTS if not f.startswith(("reduction x", "offset "))]


def symptoms(run: RunResult) -> list[str]:
    interfaces = {c.text for c in run.causes if c.kind == "interface"}
    return [r for r in run.reasons if not r.startswith(NOT_SYMPTOMS) and r not in interfaces]


class Bench:
    def __init__(self, robot: Path, folder: Path, duration: float | None, tolerance: float,
                 joint: str | None) -> None:
        self.robot, self.folder, self.joint = robot, folder, joint
        own = simulate_one(Options(robot=str(robot), duration=duration, tolerance=tolerance),
                           None)
        if not own.passed or own.series is None:
            raise SystemExit(f"{robot}: its own config does not pass: {own.reasons[:2]}")
        self.own = own
        motion = folder / "motion.csv"
        rows = np.column_stack([own.series.time, own.series.q_ref])
        np.savetxt(motion, rows, delimiter=",", header="time," + ",".join(own.series.joints),
                   comments="", fmt="%.12g")
        self.options = Options(robot=str(robot), trajectory=str(motion), tolerance=tolerance,
                               keep_series=False)
        self.text = robot.read_bytes()

    def run(self, config: bytes) -> RunResult:
        path = self.folder / "candidate.urdf"
        path.write_bytes(config)
        return simulate_one(self.options, str(path))

    def seen(self, edit: Callable[[float], tuple[bytes, str] | None], size: float) -> bool:
        edited = edit(size)
        assert edited is not None
        run = self.run(edited[0])
        assert run.verdict == "fail"  # the maps differ: always caught
        return bool(symptoms(run))

    def smallest(self, edit: Callable[[float], tuple[bytes, str] | None], none: float,
                 most: float) -> float | None:
        """The fault size nearest ``none`` (no fault) that the motion shows, up to ``most``."""
        if not self.seen(edit, most):
            return None
        low, high = none, most
        for _ in range(STEPS):
            middle = (low + high) / 2
            low, high = (low, middle) if self.seen(edit, middle) else (middle, high)
        return high

    def thresholds(self) -> dict[str, str]:
        simulated = self.own.coverage.simulated
        factor = lambda k: with_reduction_factor(self.text, simulated, k, self.joint)  # noqa: E731
        shift = lambda d: with_offset(self.text, simulated, d, self.joint)  # noqa: E731
        edited = factor(2.0)
        out = {"transmission": edited[1] if edited else "-"}
        up = self.smallest(factor, 1.0, 2.0)
        down = self.smallest(factor, 1.0, 0.5)
        offset = self.smallest(shift, 0.0, 0.3)
        out["reduction up"] = f"x{up:.5f}" if up else "not seen"
        out["reduction down"] = f"x{down:.5f}" if down else "not seen"
        out["offset"] = f"{offset:.5f}" if offset else "not seen"
        for name in DISCRETE:
            twin = FOUR_BAR.ros1().encode() if self.robot.name.startswith("four_bar") else None
            fault = inject(self.text, simulated, name, self.joint, twin)
            if fault is None:
                out[name] = "n/a"
                continue
            run = self.run(fault.config)
            out[name] = "seen" if symptoms(run) else "compared only"
        return out


def robots(folder: Path, corpus: list[str]) -> list[tuple[str, Path, str | None]]:
    made = []
    for robot, form, joint in ((CHAIN, "ros1", None), (COUNTERBALANCED, "ros2", "shoulder"),
                               (DIFFERENTIAL, "ros1", "elbow"), (FOUR_BAR, "ros2", "elbow")):
        path = folder / f"{robot.name}.{form}.urdf"
        path.write_text(getattr(robot, form)(), encoding="utf-8")
        made.append((f"{robot.name} ({form}, {joint or 'first'})", path, joint))
    made += [(name.split("__")[-1].removesuffix(".urdf"), CORPUS / name, None) for name in corpus]
    return made


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--duration", type=float, default=None,
                        help="length of the default motion (default: simulate's own)")
    parser.add_argument("--tolerance", type=float, default=0.01)
    parser.add_argument("--corpus", nargs="*", default=["universal_robot__ur5e.urdf",
                                                        "iiwa_stack__iiwa14.urdf"])
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        rows = []
        for label, path, joint in robots(folder, args.corpus):
            rows.append((label, Bench(path, folder, args.duration, args.tolerance,
                                      joint).thresholds()))
            print(label, rows[-1], file=sys.stderr, flush=True)
    columns = list(rows[0][1])
    print("| robot | " + " | ".join(columns) + " |")
    print("|---" * (len(columns) + 1) + "|")
    for label, row in rows:
        print(f"| {label} | " + " | ".join(row[c] for c in columns) + " |")


if __name__ == "__main__":
    main()
