"""Which of the fixable rules' fixes apply to a file under its readers: one decision for
``validate --fix`` and ``migrate``, so that both change what ``validate`` reports.

The fixes of TX300, TX301 and TX302 rewrite top-level ROS 1 transmissions, ros_control's. Where
the file's readers are decided (``--ros-distro``, the configuration's ``ros-distro`` or
``readers``, ``package.xml``, a ``<gazebo>`` plugin) and none of them reads top-level
transmissions, validate reports nothing on those (TX305 says nothing reads them), so nothing is
fixed there either. Transmissions inside ``<ros2_control>`` are never ROS 1 to these rules.
"""

from __future__ import annotations

from collections.abc import Sequence

from txtool.io.xmlio import Source
from txtool.lint.config import readers_of
from txtool.model.readers import Placement
from txtool.rules import Rule

TOP_LEVEL_FIXES = frozenset({"TX300", "TX301", "TX302"})


def fixes_read(source: Source, rules: Sequence[Rule], ros_distro: str | None = None,
               config: str | None = None) -> list[Rule]:
    """The ``rules`` whose fixes change what a reader of ``source`` reads, its readers decided
    as ``validate`` decides them (``ros_distro``: its ``--ros-distro``; ``config``: its
    ``--config``)."""
    if all(rule.code not in TOP_LEVEL_FIXES for rule in rules):
        return list(rules)
    if readers_of(source, ros_distro, config).reads(Placement.TOP_LEVEL):
        return list(rules)
    return [rule for rule in rules if rule.code not in TOP_LEVEL_FIXES]
