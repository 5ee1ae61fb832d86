"""``--plot``: every config of a run overlaid in one figure.

One cell per joint (reference and actual position above, tracking error with the tolerance band
below) and one per actuator (demanded effort above, speed below, against their limits), laid
out in a grid whose columns grow with the number of cells, so a 30-joint robot stays readable.
Joints and actuators that fail come first, the worst first. Units are in every axis label.
matplotlib is the optional extra ``plot``; :func:`require` fails early with a clear message.
The file format follows the suffix: .png, .svg or .pdf.
"""

from __future__ import annotations

import importlib.util
import io
import math
from pathlib import Path
from typing import Any

import numpy as np

from txtool.io.xmlio import InputError, write_atomic
from txtool.simulation.result import RunResult

SUFFIXES = (".png", ".svg", ".pdf")
CELL = (5.0, 3.4)  # inches: one joint or actuator, two stacked axes
MAX_COLUMNS = 6
REFERENCE = {"color": "black", "linestyle": "--", "linewidth": 1.0, "zorder": 3}
LIMIT = {"color": "tab:red", "linestyle": ":", "linewidth": 1.0}
BAND = {"color": "tab:green", "alpha": 0.15, "linewidth": 0}


def require(path: str) -> None:
    """Check ``--plot PATH`` before the run: a known suffix and matplotlib installed."""
    if Path(path).suffix.lower() not in SUFFIXES:
        raise InputError(f"{path}: --plot writes .png, .svg or .pdf files (by the suffix)")
    if importlib.util.find_spec("matplotlib") is None:
        from txtool.io.resources import install_extra

        raise InputError(f"{path}: --plot needs matplotlib (the 'plot' extra): "
                         f"{install_extra('plot')}")


def plot(runs: list[RunResult], path: str) -> None:
    """Write the figure of ``runs`` (all on the same robot) to ``path``."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    kept = [run for run in runs if run.series is not None]
    if not kept:
        raise ValueError("no run kept its time series")
    first = kept[0].series
    assert first is not None
    cells = cell_order(kept)
    columns, rows = grid(len(cells))
    figure = plt.figure(figsize=(CELL[0] * columns, CELL[1] * rows + 1.2),
                        layout="constrained")
    outer = figure.add_gridspec(rows, columns)
    colors = [f"C{i % 10}" for i in range(len(kept))]
    for index, (kind, name) in enumerate(cells):
        inner = outer[index // columns, index % columns].subgridspec(2, 1)
        top = figure.add_subplot(inner[0])
        bottom = figure.add_subplot(inner[1], sharex=top)
        top.tick_params(labelbottom=False)
        bottom.set_xlabel("time (s)")
        if kind == "joint":
            units = first.units[first.joints.index(name)]
            _joint_row((top, bottom), kept, colors, name, units)
        else:
            _actuator_row((top, bottom), kept, colors, name)
    handles = [plt.Line2D([], [], color=c, label=f"{run.config} ({run.verdict})")
               for run, c in zip(kept, colors, strict=True)]
    handles += [plt.Line2D([], [], label="reference", **REFERENCE),
                plt.Line2D([], [], label="limit", **LIMIT),
                matplotlib.patches.Patch(label="tolerance", **BAND)]
    figure.legend(handles=handles, loc="outside upper center", ncol=2, fontsize="small",
                  frameon=False, title=f"simulate {kept[0].robot}")
    image = io.BytesIO()  # then one atomic write: an interrupted run leaves no half an image
    figure.savefig(image, format=Path(path).suffix[1:].lower())
    plt.close(figure)
    write_atomic(path, image.getvalue(), report=True)


def grid(cells: int) -> tuple[int, int]:
    """(columns, rows) for ``cells`` cells: about as wide as tall, at most MAX_COLUMNS wide."""
    columns = max(1, min(MAX_COLUMNS, math.ceil(math.sqrt(cells * CELL[1] / CELL[0]))))
    return columns, math.ceil(cells / columns)


def cell_order(runs: list[RunResult]) -> list[tuple[str, str]]:
    """("joint"|"actuator", name) in drawing order: joints, then actuators; within each, those
    outside the tolerance or their limits in any run first, the worst first; the rest in the
    robot's order."""
    first = runs[0].series
    assert first is not None
    tolerance = runs[0].tolerance or 0.0

    def joint_key(item: tuple[int, str]) -> tuple[bool, float, int]:
        v, name = item
        worst = max((r.joints[name].max_error for r in runs if name in r.joints), default=0.0)
        return (not worst > tolerance, -worst if worst > tolerance else 0.0, v)

    def actuator_key(item: tuple[int, str]) -> tuple[bool, float, int]:
        i, name = item
        over = max((max(r.actuators[name].peak_effort / r.actuators[name].effort_limit,
                        r.actuators[name].peak_velocity / r.actuators[name].velocity_limit)
                    for r in runs if name in r.actuators), default=0.0)
        return (not over > 1.0, -over if over > 1.0 else 0.0, i)

    joints = sorted(enumerate(first.joints), key=joint_key)
    actuators = sorted(enumerate(first.actuators), key=actuator_key)
    return [("joint", n) for _, n in joints] + [("actuator", n) for _, n in actuators]


def _joint_row(axes: Any, runs: list[RunResult], colors: list[str], joint: str,
               units: str) -> None:
    position, error = axes
    reference_drawn = False
    worst = 0.0
    for run, color in zip(runs, colors, strict=True):
        s = run.series
        if s is None or joint not in s.joints:
            continue
        v = s.joints.index(joint)
        if not reference_drawn:
            position.plot(s.time, s.q_ref[:, v], **REFERENCE)
            reference_drawn = True
        position.plot(s.time, s.q[:, v], color=color, linewidth=1.0)
        e = s.q[:, v] - s.q_ref[:, v]
        error.plot(s.time, e, color=color, linewidth=1.0)
        worst = max(worst, float(np.nanmax(np.abs(e), initial=0.0)))
    tolerance = runs[0].tolerance
    if tolerance:
        error.axhspan(-tolerance, tolerance, **BAND)
        if worst > 20 * tolerance:  # a failing config would flatten the band: log beyond it
            error.set_yscale("symlog", linthresh=tolerance)
    position.set_ylabel(f"{joint}\nposition ({units})")
    error.set_ylabel(f"error ({units})")
    for ax in axes:
        ax.grid(alpha=0.3)


def _actuator_row(axes: Any, runs: list[RunResult], colors: list[str], actuator: str) -> None:
    effort, speed = axes
    for run, color in zip(runs, colors, strict=True):
        s = run.series
        if s is None or actuator not in s.actuators:
            continue
        i = s.actuators.index(actuator)
        effort.plot(s.time[: len(s.effort_demand)], s.effort_demand[:, i], color=color,
                    linewidth=1.0)
        speed.plot(s.time, s.velocity[:, i], color=color, linewidth=1.0)
    s = runs[0].series
    assert s is not None
    i = s.actuators.index(actuator)
    for ax, limit in ((effort, s.effort_limit[i]), (speed, s.velocity_limit[i])):
        if math.isfinite(limit):
            ax.axhline(limit, **LIMIT)
            ax.axhline(-limit, **LIMIT)
    stats = runs[0].actuators[actuator]
    effort.set_ylabel(f"{actuator}\neffort ({stats.effort_units})")
    speed.set_ylabel(f"speed ({stats.speed_units})")
    for ax in axes:
        ax.grid(alpha=0.3)

