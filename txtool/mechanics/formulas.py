"""ros2_control's standard transmission formulas, on columns of values (no numpy).

Each formula takes ``(x, ar, jr, off)``: ``x`` holds one value per transmission index (a float
each, or a numpy array each for many samples at once), ``ar``/``jr``/``off`` the actuator and
joint reductions and joint offsets. It returns the mapped values the same way. The formulas are
written out as ros2_control's ``transmission_interface`` computes them (not via a matrix
inverse), so results match its test vectors to the last bits, with floats and arrays alike.
Names follow the reference: a = actuator, j = joint; ``_aj`` maps actuator to joint.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any

Red = Sequence[float]
Columns = Sequence[Any]  # floats, or numpy arrays of one shape
Formula = Callable[[Columns, Red, Red, Any], tuple[Any, ...]]
EFFORT_ALIASES = ("effort", "torque", "force")


def _simple_pos_aj(x: Columns, ar: Red, jr: Red, off: Any) -> tuple[Any, ...]:
    return (x[0] / (ar[0] * jr[0]) + off[0],)


def _simple_pos_ja(x: Columns, ar: Red, jr: Red, off: Any) -> tuple[Any, ...]:
    return ((x[0] - off[0]) * (ar[0] * jr[0]),)


def _simple_vel_aj(x: Columns, ar: Red, jr: Red, off: Any) -> tuple[Any, ...]:
    return (x[0] / (ar[0] * jr[0]),)


def _simple_vel_ja(x: Columns, ar: Red, jr: Red, off: Any) -> tuple[Any, ...]:
    return (x[0] * (ar[0] * jr[0]),)


def _diff_pos_aj(x: Columns, ar: Red, jr: Red, off: Any) -> tuple[Any, ...]:
    a0, a1 = x[0] / ar[0], x[1] / ar[1]
    return (a0 + a1) / (2 * jr[0]) + off[0], (a0 - a1) / (2 * jr[1]) + off[1]


def _diff_pos_ja(x: Columns, ar: Red, jr: Red, off: Any) -> tuple[Any, ...]:
    p0, p1 = x[0] - off[0], x[1] - off[1]
    return (p0 * jr[0] + p1 * jr[1]) * ar[0], (p0 * jr[0] - p1 * jr[1]) * ar[1]


def _diff_vel_aj(x: Columns, ar: Red, jr: Red, off: Any) -> tuple[Any, ...]:
    a0, a1 = x[0] / ar[0], x[1] / ar[1]
    return (a0 + a1) / (2 * jr[0]), (a0 - a1) / (2 * jr[1])


def _diff_vel_ja(x: Columns, ar: Red, jr: Red, off: Any) -> tuple[Any, ...]:
    v0, v1 = x[0], x[1]
    return (v0 * jr[0] + v1 * jr[1]) * ar[0], (v0 * jr[0] - v1 * jr[1]) * ar[1]


def _diff_eff_aj(x: Columns, ar: Red, jr: Red, off: Any) -> tuple[Any, ...]:
    e0, e1 = x[0] * ar[0], x[1] * ar[1]
    return jr[0] * (e0 + e1), jr[1] * (e0 - e1)


def _diff_eff_ja(x: Columns, ar: Red, jr: Red, off: Any) -> tuple[Any, ...]:
    e0, e1 = x[0] / jr[0], x[1] / jr[1]
    return (e0 + e1) / (2 * ar[0]), (e0 - e1) / (2 * ar[1])


def _fourbar_pos_aj(x: Columns, ar: Red, jr: Red, off: Any) -> tuple[Any, ...]:
    a0 = x[0] / (jr[0] * ar[0])
    return a0 + off[0], (x[1] / ar[1] - a0) / jr[1] + off[1]


def _fourbar_pos_ja(x: Columns, ar: Red, jr: Red, off: Any) -> tuple[Any, ...]:
    p0, p1 = x[0] - off[0], x[1] - off[1]
    return p0 * jr[0] * ar[0], (p0 + p1 * jr[1]) * ar[1]


def _fourbar_vel_aj(x: Columns, ar: Red, jr: Red, off: Any) -> tuple[Any, ...]:
    a0 = x[0] / (jr[0] * ar[0])
    return a0, (x[1] / ar[1] - a0) / jr[1]


def _fourbar_vel_ja(x: Columns, ar: Red, jr: Red, off: Any) -> tuple[Any, ...]:
    v0, v1 = x[0], x[1]
    return v0 * jr[0] * ar[0], (v0 + v1 * jr[1]) * ar[1]


def _fourbar_eff_aj(x: Columns, ar: Red, jr: Red, off: Any) -> tuple[Any, ...]:
    e0, e1 = x[0], x[1]
    return jr[0] * e0 * ar[0] + e1 * ar[1], jr[1] * e1 * ar[1]


def _fourbar_eff_ja(x: Columns, ar: Red, jr: Red, off: Any) -> tuple[Any, ...]:
    e0, e1 = x[0], x[1]
    return (e0 - e1 / jr[1]) / (jr[0] * ar[0]), e1 / (ar[1] * jr[1])


def _fourbar_ros1_eff_aj(x: Columns, ar: Red, jr: Red, off: Any) -> tuple[Any, ...]:
    e0, e1 = x[0], x[1]
    return jr[0] * (e0 * ar[0]), jr[1] * (e1 * ar[1] - e0 * ar[0] * jr[0])


def _fourbar_ros1_eff_ja(x: Columns, ar: Red, jr: Red, off: Any) -> tuple[Any, ...]:
    e0, e1 = x[0], x[1]
    return e0 / (ar[0] * jr[0]), (e0 + e1 / jr[1]) / ar[1]


# (kind, quantity) -> (actuator_to_joint, joint_to_actuator)
FORMULAS: dict[tuple[str, str], tuple[Formula, Formula]] = {
    ("simple", "position"): (_simple_pos_aj, _simple_pos_ja),
    ("simple", "velocity"): (_simple_vel_aj, _simple_vel_ja),
    # Simple effort is the inverse of the velocity map: e_j = e_a * n, e_a = e_j / n.
    ("simple", "effort"): (_simple_vel_ja, _simple_vel_aj),
    ("differential", "position"): (_diff_pos_aj, _diff_pos_ja),
    ("differential", "velocity"): (_diff_vel_aj, _diff_vel_ja),
    ("differential", "effort"): (_diff_eff_aj, _diff_eff_ja),
    ("four_bar", "position"): (_fourbar_pos_aj, _fourbar_pos_ja),
    ("four_bar", "velocity"): (_fourbar_vel_aj, _fourbar_vel_ja),
    ("four_bar", "effort"): (_fourbar_eff_aj, _fourbar_eff_ja),
    ("four_bar_ros1", "effort"): (_fourbar_ros1_eff_aj, _fourbar_ros1_eff_ja),
}


def read_parameters(kind: str, ar: Red, jr: Red, off: Red) -> tuple[tuple[str, ...], ...]:
    """What the formulas of ``kind`` read of ``(ar, jr, off)``, bit for bit: two sets of
    parameters that read the same map every value to the same bits. A simple transmission's
    formulas read its two reductions only as their product ``ar[0] * jr[0]`` (so ROS 1's
    reduction on the actuator and ROS 2's on the joint read the same)."""
    if kind == "simple":
        return (float(ar[0] * jr[0]).hex(),), (float(off[0]).hex(),)
    return tuple(tuple(float(v).hex() for v in values) for values in (ar, jr, off))


def formula_key(kind: str, quantity: str, convention: str) -> tuple[str, str]:
    """The :data:`FORMULAS` key of ``quantity`` (effort aliases and absolute position
    included) for a transmission of ``kind`` under an effort ``convention``."""
    if quantity in EFFORT_ALIASES:
        if kind == "four_bar" and convention == "ros1":
            return "four_bar_ros1", "effort"
        return kind, "effort"
    if quantity == "absolute_position":
        quantity = "position"
    return kind, quantity
