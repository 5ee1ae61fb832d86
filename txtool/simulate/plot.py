"""``--plot``: tracking error and actuator effort against limits, one row per joint.

matplotlib is the optional extra ``plot``; :func:`require` fails early with a clear message.
"""

from __future__ import annotations

import importlib.util
import io
import math

from txtool.io.xmlio import InputError, write_atomic
from txtool.simulate.result import RunResult

SUFFIXES = (".png", ".svg")


def require(path: str) -> None:
    """Check ``--plot PATH`` before the run: a known suffix and matplotlib installed."""
    if not path.lower().endswith(SUFFIXES):
        raise InputError(f"{path}: --plot writes .png or .svg files")
    if importlib.util.find_spec("matplotlib") is None:
        raise InputError(f"{path}: --plot needs matplotlib; install it with "
                         "pip install 'txtool[plot]'")


def plot(run: RunResult, path: str) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    series = run.series
    if series is None:
        raise ValueError("the run kept no time series")
    n = len(series.joints)
    figure, axes = plt.subplots(n, 2, figsize=(11, 2.4 * n + 0.8), squeeze=False,
                                sharex=True)
    t_effort = series.time[: len(series.effort)]
    for v, joint in enumerate(series.joints):
        left, right = axes[v]
        left.plot(series.time, series.q[:, v] - series.q_ref[:, v], color="tab:blue")
        left.set_ylabel(f"{joint}\nerror [{series.units[v]}]")
        left.grid(alpha=0.3)
        for i in series.joint_actuators.get(joint, []):
            name = series.actuators[i]
            line = right.plot(t_effort, series.effort_demand[:, i], label=name)[0]
            limit = series.effort_limit[i]
            if math.isfinite(limit):
                right.axhline(limit, color=line.get_color(), linestyle="--", linewidth=0.8)
                right.axhline(-limit, color=line.get_color(), linestyle="--", linewidth=0.8)
        right.set_ylabel("actuator effort")
        right.legend(loc="upper right", fontsize="small")
        right.grid(alpha=0.3)
    axes[-1][0].set_xlabel("time [s]")
    axes[-1][1].set_xlabel("time [s]")
    figure.suptitle(f"{run.config}: {run.verdict}")
    figure.tight_layout()
    image = io.BytesIO()  # then one atomic write: an interrupted run leaves no half an image
    figure.savefig(image, format=path.rsplit(".", 1)[-1].lower())
    plt.close(figure)
    write_atomic(path, image.getvalue())
