"""The pydantic models of the ``json`` report; they generate ``schemas/report.schema.json``.

Regenerate the checked-in schema with ``python -m txtool.reporters.report_schema``. The report
itself is written by :mod:`txtool.reporters.json_format` without pydantic (loading pydantic
costs more than checking many files); a test holds the two together.
"""

from __future__ import annotations

import json
from typing import Any, Literal

from pydantic import BaseModel, ConfigDict, Field


class ReportNote(BaseModel):
    """A place related to a finding: where the xacro macro whose expansion holds it is
    written (innermost first), or the call a finding in a macro's body was expanded from."""

    model_config = ConfigDict(extra="forbid")

    path: str
    line: int = Field(ge=1)
    column: int = Field(ge=1)
    message: str = Field(description="e.g. \"in expansion of macro 'arm' defined at "
                         "urdf/arm.xacro:3\".")


class ReportProblem(BaseModel):
    """One finding; positions are 1-based, ``end_column`` is exclusive."""

    model_config = ConfigDict(extra="forbid")

    path: str = Field(description="The file as given on the command line (or --stdin-filename).")
    line: int = Field(ge=1)
    column: int = Field(ge=1)
    end_line: int = Field(ge=1)
    end_column: int = Field(ge=1)
    severity: Literal["error", "warning", "info"]
    code: str = Field(pattern=r"^TX\d{3}$", description="Stable rule code, e.g. TX105.")
    name: str = Field(description="The rule's kebab-case name, e.g. invalid-number.")
    message: str
    fixable: bool = Field(description="Whether `txtool validate --fix` fixes it (with the fixes "
                          "of `txtool migrate`).")
    related: list[ReportNote] = Field(description="The xacro call chain of a finding in an "
                                      "expansion; empty elsewhere.")


class ReportUnreadable(BaseModel):
    """A file that could not be read or checked (the run exits 2)."""

    model_config = ConfigDict(extra="forbid")

    path: str = Field(description="The file as given on the command line (or --stdin-filename).")
    message: str = Field(description="The one-line reason, as printed on stderr.")


class ReportReaders(BaseModel):
    """The programs a file's transmissions were judged for (see "Readers" in docs/loaders.md)."""

    model_config = ConfigDict(extra="forbid")

    path: str = Field(description="The file as given on the command line (or --stdin-filename).")
    readers: list[str] = Field(
        description="Reader names, e.g. ros2_control (jazzy), gz_ros2_control, ros_control."
    )
    because: list[str] = Field(
        description="Why each reader was assumed, in the same order, e.g. \"package.xml: "
        "ament_cmake\", \"<gazebo> plugin libgazebo_ros2_control.so\", \"--ros-distro jazzy\"."
    )
    decided: bool = Field(
        description="True when the readers are known (no other program reads the file); false "
        "when nothing said, and each transmission was judged by the loader of its dialect."
    )


class ReportSummary(BaseModel):
    model_config = ConfigDict(extra="forbid")

    files: int = Field(ge=0, description="Files read.")
    errors: int = Field(ge=0)
    warnings: int = Field(ge=0)
    infos: int = Field(ge=0)
    not_expanded: int = Field(
        ge=0, description="xacro files whose expansion failed (TX002), so checked as written "
        "only: an argument or package to give, or an error in the file."
    )


class Report(BaseModel):
    """The output of ``txtool validate --format json``."""

    model_config = ConfigDict(extra="forbid")

    problems: list[ReportProblem]
    unreadable: list[ReportUnreadable] = Field(
        description="Files that could not be read or checked (summary.errors counts error "
        "findings, not these)."
    )
    readers: list[ReportReaders] = Field(
        description="For each file holding transmissions, the readers it was judged for."
    )
    summary: ReportSummary


def report_schema() -> dict[str, Any]:
    schema = Report.model_json_schema()
    schema["$schema"] = "https://json-schema.org/draft/2020-12/schema"
    schema["title"] = "txtool validate report (txtool validate --format json)"
    return schema


def schema_text() -> str:
    return json.dumps(report_schema(), indent=2, sort_keys=True) + "\n"


if __name__ == "__main__":
    print(schema_text(), end="")
