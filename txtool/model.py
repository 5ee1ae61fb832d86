"""The canonical, format-neutral transmission model.

Every reader produces these values and every writer consumes them. Values are stored where the
document wrote them (a joint's reduction on the joint, an actuator's on the actuator); what a
ROS loader actually uses from them is the business of :mod:`txtool.semantics`.
"""

from __future__ import annotations

from typing import Literal

from pydantic import BaseModel, ConfigDict, Field

Kind = Literal["simple", "differential", "four_bar", "other"]
Dialect = Literal["ros1", "ros2-p1", "ros2-p2"]
DIALECTS: tuple[Dialect, ...] = ("ros1", "ros2-p1", "ros2-p2")

STANDARD_TYPES: dict[str, Kind] = {
    "SimpleTransmission": "simple",
    "DifferentialTransmission": "differential",
    "FourBarLinkageTransmission": "four_bar",
}
TYPE_PREFIX = "transmission_interface/"


class Frozen(BaseModel):
    model_config = ConfigDict(frozen=True, extra="forbid")


class Location(Frozen):
    """Where an element is written: 1-based line and column; path as the user gave it."""

    path: str
    line: int = 0
    column: int = 0


class Number(Frozen):
    """A numeric field: its value (None when the text is not a number) and the text as written.

    Keeping the text lets writers reproduce an unchanged value byte for byte (``325.949``)
    and lets the linter report text that a loader would reject or silently replace.
    """

    value: float | None
    text: str | None = None


class Member(Frozen):
    """A joint or an actuator of a transmission."""

    name: str
    role: str | None = None
    mechanical_reduction: Number | None = None
    offset: Number | None = None
    interfaces: tuple[str, ...] = ()
    state_interfaces: tuple[str, ...] = ()
    read_only: bool = False
    location: Location | None = None


class Transmission(Frozen):
    """One ``<transmission>`` element in any dialect."""

    name: str
    type: str = Field(description="The type string as written (<type>, <plugin> or type=).")
    kind: Kind
    joints: tuple[Member, ...] = ()
    actuators: tuple[Member, ...] = ()
    parameters: tuple[tuple[str, str], ...] = Field(
        default=(), description="Free <param name=...> values, in document order."
    )
    dialect: Dialect
    location: Location | None = None
    ros2_control: str | None = Field(
        default=None, description="Name of the enclosing <ros2_control> element (ROS 2)."
    )
    xml: str | None = Field(
        default=None, description="The element's XML, kept for custom types passed through."
    )


class Document(Frozen):
    """What ``txtool show`` prints: the transmissions of one document, in document order."""

    transmissions: tuple[Transmission, ...] = ()


def kind_of(type_string: str) -> Kind:
    """Classify a type string; custom and misspelt types are ``other``."""
    text = type_string.strip()
    if text.startswith(TYPE_PREFIX):
        text = text[len(TYPE_PREFIX) :]
    return STANDARD_TYPES.get(text, "other")


def standard_type(kind: Kind) -> str:
    """The plugin name of a standard kind, as both ROS loaders register it."""
    for short, k in STANDARD_TYPES.items():
        if k == kind:
            return TYPE_PREFIX + short
    raise ValueError(f"kind {kind!r} has no standard type")
