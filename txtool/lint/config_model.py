"""The configuration file's model (``[tool.txtool]`` or ``.txtool.toml``).

Read by :mod:`txtool.lint.config`.

Kept apart so that a run without a configuration file never builds it.
"""

from __future__ import annotations

from typing import Any

from pydantic import BaseModel, ConfigDict, Field

from txtool.lint.problem import Severity


class Config(BaseModel):
    """What a configuration file may say (and what command-line options override)."""

    model_config = ConfigDict(extra="forbid", populate_by_name=True, defer_build=True)

    select: list[str] | None = Field(
        default=None, description="Rule codes or code prefixes to run (default: all)."
    )
    ignore: list[str] = Field(default_factory=list, description="Rule codes or prefixes to skip.")
    severity: dict[str, Severity] = Field(
        default_factory=dict, description="Per-rule severity, e.g. TX300 = \"error\"."
    )
    rules: dict[str, dict[str, Any]] = Field(
        default_factory=dict, description="Per-rule options, e.g. [tool.txtool.rules.TX102]."
    )
    xacro_args: dict[str, str] = Field(default_factory=dict, alias="xacro-args")
    pkg_dirs: list[str] = Field(default_factory=list, alias="pkg-dirs")
    pkg_paths: dict[str, str] = Field(default_factory=dict, alias="pkg-paths")
    no_xacro: bool = Field(default=False, alias="no-xacro")
    exclude: list[str] = Field(
        default_factory=list,
        description="gitignore-style patterns, relative to this file's folder, that folder "
        "walks pass over (--exclude replaces them).",
    )
    extend_exclude: list[str] = Field(
        default_factory=list, alias="extend-exclude",
        description="More patterns to pass over, kept when --exclude is given.",
    )
    respect_gitignore: bool = Field(default=True, alias="respect-gitignore")
    per_file_ignores: dict[str, list[str]] = Field(
        default_factory=dict, alias="per-file-ignores",
        description="Pattern -> rule codes or prefixes not run on matching files.",
    )
    readers: list[str] | None = Field(
        default=None,
        description="The programs that read these files' transmissions (replaces detection), "
        "e.g. [\"ros2_control\", \"gz_ros2_control\"].",
    )
    ros_distro: str | None = Field(
        default=None, alias="ros-distro",
        description="The ROS distribution reading these files: noetic, humble, jazzy, kilted or "
        "rolling (--ros-distro overrides it).",
    )
    per_file_xacro_args: dict[str, dict[str, str]] = Field(
        default_factory=dict, alias="per-file-xacro-args",
        description="Pattern -> xacro arguments for matching files (over xacro-args).",
    )
