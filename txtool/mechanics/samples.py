"""Joint values to sample a transmission's maps at, as plain floats (no numpy).

Positions span each joint's limits (``JointInfo.position_range()``, +-pi where absent);
velocities and efforts +-their URDF limits (+-1 where absent). Each axis has the values
``numpy.linspace`` gives, bit for bit.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping, Sequence

from txtool.model.robot import JointInfo

Sample = tuple[float, ...]


def axis(lo: float, hi: float, count: int) -> list[float]:
    """``count`` values from ``lo`` to ``hi`` (``count`` >= 2), as ``numpy.linspace``."""
    if math.isfinite(hi - lo):
        return _linspace(lo, hi, count)
    # Limits such as +-1e308: the width overflows, a weighted mean of the two does not.
    return [lo * (1.0 - t) + hi * t for t in _linspace(0.0, 1.0, count)]


def _linspace(lo: float, hi: float, count: int) -> list[float]:
    div = count - 1
    delta = hi - lo
    step = delta / div
    if step == 0:  # numpy's handling of denormal widths
        values = [float(i) / div * delta + lo for i in range(count)]
    else:
        values = [float(i) * step + lo for i in range(count)]
    values[-1] = hi
    return values


def grid(ranges: Sequence[tuple[float, float]], per_axis: int) -> list[Sample]:
    """Every combination of ``per_axis`` values per range, the last range varying fastest."""
    return list(itertools.product(*(axis(lo, hi, per_axis) for lo, hi in ranges)))


def joint_samples(
    names: Sequence[str], joints: Mapping[str, JointInfo] | None = None, per_axis: int = 9
) -> dict[str, list[Sample]]:
    """Grids of joint position, velocity and effort, one value per joint of ``names``."""
    positions, velocities, efforts = [], [], []
    for name in names:
        info = joints.get(name) if joints else None
        positions.append(info.position_range() if info else (-math.pi, math.pi))
        speed = info.velocity if info and info.velocity else 1.0
        effort = info.effort if info and info.effort else 1.0
        velocities.append((-abs(speed), abs(speed)))
        efforts.append((-abs(effort), abs(effort)))
    return {
        "position": grid(positions, per_axis),
        "velocity": grid(velocities, per_axis),
        "effort": grid(efforts, per_axis),
    }
