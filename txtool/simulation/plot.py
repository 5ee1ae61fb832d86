"""``--plot``: every config of a run overlaid in one figure.

One cell per joint (reference and actual position above, tracking error with the tolerance band
below) and one per actuator (demanded effort above, speed below, against their limits), laid
out in a grid whose columns grow with the number of cells, so a 30-joint robot stays readable.
Joints and actuators that fail come first, the worst first. Units are in every axis label.
matplotlib is the optional extra ``plot``; :func:`require` fails early with a clear message.
The file format follows the suffix: .png, .svg or .pdf.
"""

from __future__ import annotations

import fnmatch
import importlib.util
import io
import math
from collections.abc import Sequence
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
SUMMARY_BARS = 20  # the worst joints and actuators the summary cell draws bars for


def require(path: str) -> None:
    """Check ``--plot PATH`` before the run: a known suffix and matplotlib installed."""
    if Path(path).suffix.lower() not in SUFFIXES:
        raise InputError(f"{path}: --plot writes .png, .svg or .pdf files (by the suffix)")
    if importlib.util.find_spec("matplotlib") is None:
        from txtool.io.resources import install_extra

        raise InputError(f"{path}: --plot needs matplotlib (the 'plot' extra): "
                         f"{install_extra('plot')}")


def plot(runs: list[RunResult], path: str, joints: Sequence[str] = ()) -> None:
    """Write the figure of ``runs`` (all on the same robot) to ``path``: the joints
    ``joints`` names (names or shell patterns; default: those a transmission drives)."""
    kept = [run for run in runs if run.series is not None]
    if not kept:
        raise ValueError("no run kept its time series")
    cells = cell_order(kept, selected(kept, joints))
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    first = kept[0].series
    assert first is not None
    columns, rows = grid(len(cells) + 1)
    figure = plt.figure(figsize=(CELL[0] * columns, CELL[1] * rows + 1.2),
                        layout="constrained")
    outer = figure.add_gridspec(rows, columns)
    colors = [f"C{i % 10}" for i in range(len(kept))]
    _summary(figure, outer[0, 0].subgridspec(2, 1), kept, colors, cells)
    for index, (kind, name) in enumerate(cells, 1):
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


def selected(runs: list[RunResult], patterns: Sequence[str]) -> list[str]:
    """The joints to draw, in the robot's order: those ``patterns`` match (each must match
    one), else those a transmission drives in any run (all of them when none is)."""
    first = runs[0].series
    assert first is not None
    if patterns:
        for pattern in patterns:
            if not fnmatch.filter(first.joints, pattern):
                raise InputError(f"--joints: no joint of {runs[0].robot} is named {pattern!r}")
        return [j for j in first.joints if any(fnmatch.fnmatchcase(j, p) for p in patterns)]
    driven = [j for j in first.joints
              if any(r.joints[j].transmission for r in runs if j in r.joints)]
    return driven or list(first.joints)


def grid(cells: int) -> tuple[int, int]:
    """(columns, rows) for ``cells`` cells: about as wide as tall, at most MAX_COLUMNS wide."""
    columns = max(1, min(MAX_COLUMNS, math.ceil(math.sqrt(cells * CELL[1] / CELL[0]))))
    return columns, math.ceil(cells / columns)


def cell_order(runs: list[RunResult], joints: Sequence[str] | None = None
               ) -> list[tuple[str, str]]:
    """("joint"|"actuator", name) in drawing order: the ``joints`` (default: all), then the
    actuators driving them; within each, the worst first (tracking error against the
    tolerance; effort or speed against the limit), in the robot's order where equal."""
    first = runs[0].series
    assert first is not None
    shown = set(first.joints if joints is None else joints)
    actuators = {i for j in shown for i in first.joint_actuators.get(j, [])
                 if first.transmission_of[i]}
    order = sorted((v for v, j in enumerate(first.joints) if j in shown),
                   key=lambda v: (-error_ratio(runs, first.joints[v]), v))
    motors = sorted(actuators, key=lambda i: (-limit_ratio(runs, first.actuators[i]), i))
    return [("joint", first.joints[v]) for v in order] + [
        ("actuator", first.actuators[i]) for i in motors]


def error_ratio(runs: list[RunResult], joint: str) -> float:
    """The largest tracking error of ``joint`` over the runs, in tolerances."""
    tolerance = runs[0].tolerance or 1.0
    return max((r.joints[joint].max_error for r in runs if joint in r.joints),
               default=0.0) / tolerance


def limit_ratio(runs: list[RunResult], actuator: str) -> float:
    """The largest share of its effort or speed limit ``actuator`` reaches over the runs."""
    shares = [max(_share(a.peak_effort, a.effort_limit), _share(a.peak_velocity,
                                                                 a.velocity_limit))
              for a in (r.actuators.get(actuator) for r in runs) if a is not None]
    return max(shares, default=0.0)


def _share(value: float, limit: float) -> float:
    return value / limit if limit > 0 else 0.0  # no limit (0 or inf): nothing to reach


def _summary(figure: Any, cell: Any, runs: list[RunResult], colors: list[str],
             cells: list[tuple[str, str]]) -> None:
    """Bars of every drawn joint's error (in tolerances) and actuator's peak (in limits), the
    worst at the top."""
    for slot, (kind, measure, label) in enumerate((
            ("joint", error_ratio, "joints: max error / tolerance, worst first"),
            ("actuator", limit_ratio, "actuators: peak / limit, worst first"))):
        ax = figure.add_subplot(cell[slot])
        names = [name for k, name in cells if k == kind][:SUMMARY_BARS]
        height = 1 / (len(runs) + 1)
        for index, (run, color) in enumerate(zip(runs, colors, strict=True)):
            values = [measure([run], name) for name in names]
            ax.barh(np.arange(len(names)) + index * height, values, height=height, color=color)
        ax.axvline(1.0, **LIMIT)
        ax.set_xscale("symlog", linthresh=1.0)  # within the bound linear, far beyond it log
        ax.set_yticks(np.arange(len(names)), names, fontsize="x-small")
        ax.invert_yaxis()  # the worst first, at the top
        ax.set_title(label, fontsize="small")
        ax.grid(alpha=0.3, axis="x")


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

