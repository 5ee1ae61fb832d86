"""The pydantic models of ``--format json`` of ``map``, ``roundtrip`` and ``rules``; they
generate ``schemas/<command>.schema.json``.

Regenerate the checked-in schemas with ``python -m txtool.commands.json_schemas``. The commands
write their JSON without pydantic (loading it costs more than the commands); tests validate
their real output against these models and the checked-in schemas. ``validate``'s schema is
:mod:`txtool.reporters.report_schema`'s, ``show``'s is :mod:`txtool.model.schema`'s.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path
from typing import Any, Literal

from pydantic import BaseModel, ConfigDict, Field, RootModel

Dialect = Literal["ros1", "ros2-p1", "ros2-p2"]


class _Strict(BaseModel):
    model_config = ConfigDict(extra="forbid")


class MapOutput(_Strict):
    """The output of 'txtool map --format json': each quantity given, mapped, its values in
    the role order of the output members (actuator1, actuator2 or joint1, joint2); a quantity
    not given is left out."""

    position: list[float] = Field(default_factory=list, description="Positions (rad or m).")
    velocity: list[float] = Field(default_factory=list, description="Velocities.")
    effort: list[float] = Field(default_factory=list, description="Efforts (N m or N).")


class RoundtripCycle(_Strict):
    """One transmission through one cycle of dialects; each field is true when it survives."""

    transmission: str
    cycle: list[Dialect] = Field(description="The dialects in order, back to the first.")
    reduction: bool
    offset: bool
    direction: bool
    roles: bool
    interfaces: bool
    equivalent: str = Field(description="\"yes\", \"no: REASON\" (the first conversion drives "
                                        "the actuators differently) or \"n/a: REASON\".")
    details: list[str] = Field(description="What was lost or changed, one line each.")


class AgainstRow(_Strict):
    """One pair of transmissions, matched by the joints they drive."""

    joints: list[str]
    a: str | None = Field(description="FILE's transmission, null when it has none there.")
    b: str | None = Field(description="OTHER's transmission, null when it has none there.")
    status: Literal["equivalent", "differs", "missing", "not loadable"]
    differences: dict[str, float | None] = Field(
        description="Largest absolute difference per quantity (position, velocity, effort); "
                    "null where it is not a finite number.")
    reason: str


class RoundtripJson(_Strict):
    """'txtool roundtrip FILE --format json': one shape, with or without '--against OTHER'.
    Without it, FILE's cycles through the dialects (``cycles``, ``skipped``); with it, the
    comparison of FILE with OTHER (``transmissions``, ``bb_exporter_dropped``); the other
    mode's lists are empty."""

    path: str = Field(description="FILE as given.")
    against: str | None = Field(description="OTHER as given; null without --against.")
    ok: bool = Field(description="Without --against: every cycle keeps every field and "
                                 "behaviour; with it: every transmission pair drives the "
                                 "actuators alike. The exit code is 0 exactly then.")
    cycles: list[RoundtripCycle]
    skipped: list[str] = Field(description="Transmissions of custom types, passed through "
                                           "untouched.")
    transmissions: list[AgainstRow]
    bb_exporter_dropped: list[str] = Field(
        description="What Beam Bots' URDF exporter left out of OTHER, when it wrote it.")


class RuleRow(_Strict):
    """One rule, as 'txtool rules' prints it, without markup."""

    code: str = Field(pattern=r"^TX\d{3}$")
    name: str = Field(description="kebab-case, e.g. invalid-number.")
    severity: Literal["error", "warning", "info"] = Field(description="Default severity.")
    fixable: bool = Field(description="Whether `txtool migrate` fixes it.")
    summary: str = Field(description="The first sentence, plain text.")
    doc: str = Field(description="The documentation, plain text.")
    markdown: str = Field(description="The documentation as Markdown (the rule's page).")


class RulesOutput(RootModel[list[RuleRow]]):
    """'txtool rules [CODE] --format json': every rule, or the one named, always a list."""


SCHEMAS: dict[str, tuple[type[BaseModel], str]] = {
    "map.schema.json": (MapOutput, "txtool map --format json"),
    "roundtrip.schema.json": (RoundtripJson, "txtool roundtrip --format json"),
    "rules.schema.json": (RulesOutput, "txtool rules --format json"),
}


def schema(file_name: str) -> dict[str, Any]:
    model, command = SCHEMAS[file_name]
    generated = model.model_json_schema()
    generated["$schema"] = "https://json-schema.org/draft/2020-12/schema"
    generated["title"] = f"{command} output"
    return generated


def schema_text(file_name: str) -> str:
    return json.dumps(schema(file_name), indent=2, sort_keys=True) + "\n"


def write_all(folder: Path) -> None:
    for file_name in SCHEMAS:
        (folder / file_name).write_text(schema_text(file_name), encoding="utf-8")


if __name__ == "__main__":
    write_all(Path(sys.argv[1]) if len(sys.argv) > 1 else Path("schemas"))
