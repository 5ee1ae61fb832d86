"""The linear part of the standard transmissions, in pure Python (no numpy).

``A`` maps joint velocities to actuator velocities (``qdot_a = A @ qdot_j``). A power-conserving
effort map is ``tau_j = A^T tau_a``; ros_control's (ROS 1) four-bar linkage uses another matrix,
fixed in ros2_control by PR #1837 (issue #1746). The linter imports this module, so it must stay
free of numpy.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Literal

from txtool.model.semantics import Effective

Convention = Literal["ros2", "ros1"]
CONVENTIONS: tuple[str, ...] = ("ros2", "ros1")
Matrix = list[list[float]]
MAX_CONDITION = 1e12


def velocity_matrix(kind: str, ar: Sequence[float], jr: Sequence[float]) -> Matrix:
    """``A`` from the reductions, exactly as ros2_control's velocity formulas imply."""
    if kind == "simple":
        return [[ar[0] * jr[0]]]
    if kind == "differential":
        return [[ar[0] * jr[0], ar[0] * jr[1]], [ar[1] * jr[0], -ar[1] * jr[1]]]
    if kind == "four_bar":
        return [[jr[0] * ar[0], 0.0], [ar[1], ar[1] * jr[1]]]
    raise ValueError(f"no linear map for transmission kind {kind!r}")


def effort_matrix(
    kind: str, ar: Sequence[float], jr: Sequence[float], convention: str = "ros2"
) -> Matrix:
    """``E`` with ``tau_j = E @ tau_a`` under the given effort convention."""
    check_convention(convention)
    if kind == "four_bar" and convention == "ros1":
        return [[jr[0] * ar[0], 0.0], [-jr[1] * ar[0] * jr[0], jr[1] * ar[1]]]
    return transpose(velocity_matrix(kind, ar, jr))


def check_convention(convention: str) -> None:
    if convention not in CONVENTIONS:
        raise ValueError(f"unknown effort convention {convention!r} (expected ros2 or ros1)")


def transpose(m: Matrix) -> Matrix:
    return [list(row) for row in zip(*m, strict=True)]


def a_matrix(eff: Effective) -> Matrix:
    """``A`` of a loaded transmission, in the index order of ``eff.joints``/``eff.actuators``."""
    return velocity_matrix(eff.kind, eff.actuator_reduction, eff.joint_reduction)


def determinant(m: Matrix) -> float:
    if len(m) == 1:
        return m[0][0]
    return m[0][0] * m[1][1] - m[0][1] * m[1][0]


def condition_number(eff: Effective) -> float:
    """The 2-norm condition number of ``A`` (ratio of singular values); inf when singular."""
    return matrix_condition(a_matrix(eff))


def matrix_condition(m: Matrix) -> float:
    values = [x for row in m for x in row]
    if not all(math.isfinite(x) for x in values):
        return math.inf
    det = abs(determinant(m))
    if det == 0.0:
        return math.inf
    if len(m) == 1:
        return 1.0
    frobenius2 = sum(x * x for x in values)
    # Singular values s1 >= s2: s1^2 + s2^2 = |A|_F^2 and s1 * s2 = |det A|.
    root = math.sqrt(max(frobenius2 * frobenius2 - 4.0 * det * det, 0.0))
    s1_squared = (frobenius2 + root) / 2.0
    return s1_squared / det


def singular(eff: Effective, max_condition: float = MAX_CONDITION) -> str | None:
    """Why ``A`` cannot be inverted reliably, or None when it can.

    The reason does not quote the condition number; :func:`condition_number` gives it.
    """
    for names, values, side in (
        (eff.actuators, eff.actuator_reduction, "actuator"),
        (eff.joints, eff.joint_reduction, "joint"),
    ):
        for name, value in zip(names, values, strict=True):
            if value == 0.0:
                return f"{side} reduction of '{name}' is zero"
            if not math.isfinite(value):
                return f"{side} reduction of '{name}' is {value!r}"
    return matrix_singular(a_matrix(eff), max_condition)


def matrix_singular(m: Matrix, max_condition: float = MAX_CONDITION) -> str | None:
    if determinant(m) == 0.0:
        return "the velocity map A has determinant 0"
    if matrix_condition(m) > max_condition:
        return "the velocity map A is ill-conditioned"
    return None


def power_mismatch(eff: Effective, convention: str = "ros2") -> float:
    """How far the effort map is from conserving power, relative to the size of ``A``.

    Power is conserved for every motion and load exactly when ``E^T == A``; the result is
    ``max|E^T - A| / max|A|`` (0 for simple and differential transmissions and for the
    ros2_control four-bar; about 1 or more for the ROS 1 four-bar).
    """
    a = a_matrix(eff)
    e = effort_matrix(eff.kind, eff.actuator_reduction, eff.joint_reduction, convention)
    et = transpose(e)
    scale = max(abs(x) for row in a for x in row)
    if scale == 0.0 or not math.isfinite(scale):
        return math.inf
    worst = max(abs(et[i][j] - a[i][j]) for i in range(len(a)) for j in range(len(a)))
    return worst / scale
