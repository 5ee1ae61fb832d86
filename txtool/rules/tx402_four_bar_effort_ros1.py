"""The ROS 1 four-bar effort map does not conserve power.

What it checks
    Every ROS 1 ``transmission_interface/FourBarLinkageTransmission``.

Why
    ros_control's four-bar maps efforts with
    ``e_j1 = jr1 * (e_a1 * ar1 - e_a0 * ar0 * jr0)``, which is not the transpose of its own
    velocity map, so joint power differs from actuator power (ros_control#523, still open).
    ros2_control fixed the same formulas in PR #1837 (issue #1746) to
    ``tau_a = J^T tau_j``. Positions and velocities agree between the two; efforts, and every
    effort-controlled joint, do not, so a robot behaves differently after migrating to ROS 2
    with the same reductions. This is informational: nothing in the file is wrong, but effort
    gains tuned on ROS 1 need re-checking on ROS 2 (``txtool map`` shows both maps).

Reported example::

    <transmission name="four_bar">
      <type>transmission_interface/FourBarLinkageTransmission</type>
      ...
    </transmission>

Not reported: the same transmission in a ROS 2 ``<ros2_control>`` block, or any other type.
"""

from __future__ import annotations

from collections.abc import Iterator

from txtool.lint.context import LintContext
from txtool.lint.problem import Problem
from txtool.lint.rule_helpers import per_transmission

CODE = "TX402"
NAME = "four-bar-effort-ros1"
SEVERITY = "info"
FIXABLE = False


@per_transmission
def check(ctx: LintContext) -> Iterator[Problem]:
    for tx in ctx.facts:
        if not tx.ros1 or tx.kind != "four_bar":
            continue
        found = tx.found
        t = found.transmission
        yield ctx.problem(
            CODE,
            found.element,
            f"four-bar transmission '{t.name}': ros_control's effort map does not conserve "
            "power (ros_control#523) and differs from ros2_control's since PR #1837, so "
            "efforts change when the robot moves to ROS 2",
        )
