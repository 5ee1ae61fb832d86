"""A transmission type that is not a standard one, with a suggestion for near-misses.

Both loaders look the type up by its exact pluginlib name:
``transmission_interface/SimpleTransmission``, ``transmission_interface/DifferentialTransmission``
or ``transmission_interface/FourBarLinkageTransmission``. A misspelt name (``SimpleTansmission``,
a missing or wrong ``transmission_interface/`` prefix) makes ros_control fail with
"Unsupported type"; ros2_control's parser accepts any text, so the mistake only shows when the
hardware plugin looks for a loader. Types of known custom families (``pr2_mechanism_model/``,
``sr_mechanism_model/``, ``franka_hw/``, plus the ``known-families`` option) are not
reported; other custom types are reported once, since txtool cannot check them.

Applies to ``<type>`` (ROS 1) and ``<plugin>`` (ROS 2); the pre-Hydro ``type=`` attribute
alone is TX302's business.

Options (``[tool.txtool.rules.TX102]``):

``known-families``
    extra type prefixes to accept, e.g. ``["my_robot_hw/"]`` (default: none).

Failing example::

    <transmission name="t">
      <plugin>transmission_interface/SimpleTansmission</plugin>
    </transmission>

Passing example::

    <transmission name="t">
      <plugin>transmission_interface/SimpleTransmission</plugin>
    </transmission>
"""

from __future__ import annotations

from collections.abc import Iterator
from functools import cache, lru_cache
from typing import Any

from txtool.lint.context import LintContext
from txtool.lint.problem import Problem
from txtool.lint.support import KNOWN_FAMILIES, label, type_element
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


def check(ctx: LintContext) -> Iterator[Problem]:
    options = ctx.option(CODE)
    families = KNOWN_FAMILIES + tuple(options.known_families if options else ())
    for found in ctx.transmissions():
        element = type_element(found)
        if element is None:
            continue
        text = (element.text or "").strip()
        if not text or ctx.unknown(text) or text in STANDARD_NAMES or text.startswith(families):
            continue
        ros1 = found.transmission.dialect == "ros1"
        suggestion = nearest_standard(text)
        if suggestion is not None:
            effect = (
                "ros_control fails with \"Unsupported type\""
                if ros1
                else "ros2_control parses it but finds no loader for it"
            )
            message = f"{label(found)} has type '{text}' ({effect}); did you mean '{suggestion}'?"
        else:
            message = (
                f"{label(found)} has type '{text}', not a standard transmission_interface type: "
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
