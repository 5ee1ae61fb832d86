"""A transmission type outside ``transmission_interface/`` that txtool does not know.

What it does: reports a ``<type>`` (ROS 1) or ``<plugin>`` (ROS 2) in another namespace than
``transmission_interface/``: a near-miss of a standard name (``SimpleTransmission`` without its
``transmission_interface/`` prefix) with a suggestion; other custom types once, since txtool
cannot check them. Types of known custom families (``pr2_mechanism_model/``,
``sr_mechanism_model/``, ``franka_hw/``, plus the ``known-families`` option) are not reported,
nor are types a package registers with pluginlib (its ``package.xml`` exports
``<transmission_interface plugin="..."/>``; packages of the workspace, ``AMENT_PREFIX_PATH`` and
``ROS_PACKAGE_PATH`` are read): the loaders find those. A type under
``transmission_interface/`` that is not one of the three standard ones is TX113's business;
the pre-Hydro ``type=`` attribute alone is TX302's. Options
(``[tool.txtool.rules.TX102]``): ``known-families``, extra type prefixes to accept, e.g.
``["my_robot_hw/"]`` (default: none).

Why it matters: both loaders look the type up by its exact pluginlib name and refuse a name
nobody registered ("Unsupported type"). A type in another namespace may be a plugin installed
on the robot, so it is a warning.

Loader: ros_control (ros-controls/ros_control
transmission_interface/src/transmission_interface_loader.cpp:139-147 @0a09467); ros2_control's
hardware plugins look the loader up with pluginlib the same way (ros-controls/ros2_control
hardware_interface/src/component_parser.cpp ``parse_transmission_from_xml`` copies the name).

Failing example::

    <robot name="r">
      <transmission name="t">
        <type>SimpleTransmission</type>
        <joint name="j">
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
        </joint>
        <actuator name="m"><mechanicalReduction>50</mechanicalReduction></actuator>
      </transmission>
    </robot>

Expected finding: ``3:5 warning TX102 transmission 't' has type 'SimpleTransmission': no loader
knows it unless a plugin of that name is installed; did you mean
'transmission_interface/SimpleTransmission'?``

Passing example::

    <robot name="r">
      <transmission name="t">
        <type>transmission_interface/SimpleTransmission</type>
        <joint name="j">
          <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
        </joint>
        <actuator name="m"><mechanicalReduction>50</mechanicalReduction></actuator>
      </transmission>
    </robot>

Fix: write the full pluginlib name (``transmission_interface/SimpleTransmission``), or add the
family of a type your robot's packages provide to ``known-families``.
"""

from __future__ import annotations

from collections.abc import Iterator
from functools import cache, lru_cache
from typing import Any

from txtool.lint.context import LintContext
from txtool.lint.problem import Problem
from txtool.lint.rule_helpers import KNOWN_FAMILIES, per_transmission
from txtool.model.core import STANDARD_TYPES, TYPE_PREFIX

CODE = "TX102"
NAME = "unknown-type"
SEVERITY = "warning"
FIXABLE = False

STANDARD_NAMES = tuple(TYPE_PREFIX + short for short in STANDARD_TYPES)
MAX_DISTANCE = 3


@cache
def options_model() -> Any:
    """The pydantic model of this rule's options (built when a configuration names them)."""
    from pydantic import BaseModel, ConfigDict, Field

    class Options(BaseModel):
        model_config = ConfigDict(extra="forbid", populate_by_name=True)

        known_families: list[str] = Field(default_factory=list, alias="known-families")

    return Options


@per_transmission
def check(ctx: LintContext) -> Iterator[Problem]:
    options = ctx.option(CODE)
    families = KNOWN_FAMILIES + tuple(options.known_families if options else ())
    prefixes = (*families, TYPE_PREFIX)
    for tx in ctx.facts:
        text = tx.type_text
        if not text or text.startswith(prefixes) or ctx.unknown(text):
            continue  # no type element, or an empty one: TX101; transmission_interface/...: TX113
        if ctx.readers.known_type(text) is not None:
            continue  # a plugin a package exports: the loaders find it
        element = tx.type_element
        suggestion = nearest_standard(text)
        if suggestion is not None:
            message = (
                f"{tx.label} has type '{text}': no loader knows it unless a plugin of that "
                f"name is installed; did you mean '{suggestion}'?"
            )
        else:
            message = (
                f"{tx.label} has type '{text}', not a standard transmission_interface type: "
                "txtool cannot check it (add its family to known-families if it is a plugin)"
            )
        yield ctx.problem(CODE, element, message)


@lru_cache(maxsize=256)
def nearest_standard(text: str) -> str | None:
    """The standard type ``text`` is a near-miss of (by its class name), or None."""
    wanted = text.lower()
    short = wanted.rsplit("/", 1)[-1]
    best: tuple[int, str] | None = None
    for full, name in zip(STANDARD_NAMES, STANDARD_TYPES, strict=True):
        if abs(len(short) - len(name)) > MAX_DISTANCE:
            continue
        distance = edit_distance(short, name.lower())
        if best is None or distance < best[0]:
            best = (distance, full)
    if best is not None and best[0] <= MAX_DISTANCE:
        return best[1]
    # A standard name followed by stray text (``.../SimpleTransmission name=""``).
    return next((full for full in STANDARD_NAMES if wanted.startswith(full.lower())), None)


def edit_distance(a: str, b: str) -> int:
    """Levenshtein distance (insertions, deletions, substitutions)."""
    previous = list(range(len(b) + 1))
    for i, char_a in enumerate(a, 1):
        current = [i]
        for j, char_b in enumerate(b, 1):
            cost = 0 if char_a == char_b else 1
            current.append(min(previous[j] + 1, current[j - 1] + 1, previous[j - 1] + cost))
        previous = current
    return previous[-1]
