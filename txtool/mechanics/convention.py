"""Which effort map a transmission runs: the one of the loader that reads its file.

Only the four-bar linkage differs. ros_control computes joint efforts as
``jr[1] * (e_a[1] * ar[1] - e_a[0] * ar[0] * jr[0])`` (ros-controls/ros_control
transmission_interface/include/transmission_interface/four_bar_linkage_transmission.h:241-242
@133d768, ``actuatorToJointEffort``; issue #523 is open); ros2_control replaced that by a
power-conserving map (ros-controls/ros2_control PR #1837, fixing issue #1746). A ROS 1 file is
loaded by ros_control and a ROS 2 one by ros2_control, so each runs its own loader's map unless
the user asks for the other (``--effort-convention``). Pure Python: the linter may import it.
"""

from __future__ import annotations

from txtool.mechanics.linear import CONVENTIONS, Convention, check_convention
from txtool.model.core import Transmission
from txtool.model.semantics import loader_of

__all__ = ["CONVENTIONS", "Convention", "effort_convention", "source_of"]


def effort_convention(transmission: Transmission, override: str | None = None) -> Convention:
    """The effort convention ``transmission`` runs under: ``override`` when given, else that
    of its own loader (``ros1`` for a ROS 1 transmission, ``ros2`` for a ROS 2 one)."""
    if override is not None:
        check_convention(override)
        return override  # type: ignore[return-value]
    return loader_of(transmission)


def source_of(override: str | None) -> str:
    """How the convention was chosen, for captions: the option or the file's own loader."""
    return "--effort-convention" if override is not None else "the file's loader"
