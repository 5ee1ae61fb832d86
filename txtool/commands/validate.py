"""``txtool validate``: lint transmission configurations (argument parsing only)."""

from __future__ import annotations

import os
import sys

import click

from txtool.commands.common import (
    COLOR_MODES,
    Choice,
    RenamedOption,
    color_wanted,
    exit_on_input_error,
    xacro_options,
)
from txtool.io.printable import printable
from txtool.model.distro import CHOICES

FORMATS = ("text", "json", "github", "sarif")



def _codes(values: tuple[str, ...]) -> tuple[str, ...]:
    return tuple(code.strip() for value in values for code in value.split(",") if code.strip())


def default_format() -> str:
    return "github" if os.environ.get("GITHUB_ACTIONS") == "true" else "text"


def use_color(mode: str, output_file: str | None = None) -> bool:
    return color_wanted(mode, output_file is None and sys.stdout.isatty())


@click.command("validate")
@click.argument("paths", nargs=-1, type=click.Path())
@click.option("--format", "output_format", type=Choice(FORMATS), default=None,
              help="Output format [default: text; github when GITHUB_ACTIONS=true].")
@click.option("--select", multiple=True, metavar="CODES",
              help="Only these rule codes or prefixes (comma-separated, repeatable).")
@click.option("--ignore", multiple=True, metavar="CODES",
              help="Skip these rule codes or prefixes (comma-separated, repeatable).")
@click.option("--strict", is_flag=True, help="Warnings fail too (exit 1).")
@click.option("--exit-zero", is_flag=True, help="Exit 0 even when there are findings.")
@click.option("--config", "config_path", type=click.Path(dir_okay=False), metavar="PATH",
              help="Use this configuration file instead of searching for one.")
@click.option("--no-xacro", is_flag=True,
              help="Do not expand xacro; check .xacro files as written.")
@click.option("--stdin-filename", metavar="NAME",
              help="The name to report (and find the configuration by) for '-'.")
@click.option("-j", "--jobs", type=click.IntRange(min=0), default=0, show_default=True,
              help="Processes checking many files (0: one per CPU; 1: only this one).")
@click.option("--color", type=Choice(COLOR_MODES), default="auto", show_default=True,
              help="Colour the text output: auto colours a terminal unless NO_COLOR is set "
                   "(FORCE_COLOR colours a pipe too).")
@click.option("-o", "--output", "output_file", cls=RenamedOption, old_names=("--output-file",),
              type=click.Path(dir_okay=False), metavar="FILE",
              help="Write the report to FILE (replaced whole, atomically) instead of stdout.")
@click.option("-q", "--quiet", is_flag=True,
              help="Text format: print the findings only, no summary line.")
@click.option("--statistics", is_flag=True,
              help="Text format: count the findings per rule instead of listing them.")
@click.option("--exclude", multiple=True, metavar="PATTERN",
              help="gitignore-style pattern of files and folders that folder walks pass over, "
                   "relative to this folder; replaces the configuration's exclude (repeatable).")
@click.option("--extend-exclude", multiple=True, metavar="PATTERN",
              help="Like --exclude, but kept beside the configuration's exclude (repeatable).")
@click.option("--respect-gitignore/--no-respect-gitignore", default=None,
              help="Pass over what .gitignore files ignore in folder walks [default: respect].")
@click.option("--ros-distro", type=click.Choice(CHOICES), default=None,
              help="The ROS distribution whose programs read the files (over the "
                   "configuration's ros-distro and what package.xml and <gazebo> plugins say).")
@xacro_options
@exit_on_input_error
def command(paths, output_format, select, ignore, strict, exit_zero, config_path, no_xacro,
            stdin_filename, jobs, color, output_file, quiet, statistics, exclude,
            extend_exclude, respect_gitignore, ros_distro, xacro) -> int:
    """Check transmissions in files and folders (*.urdf, *.xacro, robot *.xml; '-' is stdin).

    Exit codes: 0 nothing at the failing level, 1 findings at it (errors; warnings too with
    --strict; infos never), 2 usage, configuration or input error.
    """
    from txtool.lint.api import LintOptions, exit_code, lint_paths
    from txtool.reporters import Summary

    options = LintOptions(
        select=_codes(select) or None,
        ignore=_codes(ignore),
        config=config_path,
        xacro=xacro,
        no_xacro=no_xacro,
        stdin_filename=stdin_filename,
        strict=strict,
        exit_zero=exit_zero,
        jobs=jobs,
        exclude=exclude or None,
        extend_exclude=extend_exclude,
        respect_gitignore=respect_gitignore,
        ros_distro=ros_distro,
    )
    if xacro.args:
        _warn_unused_args(list(paths), no_xacro)
    from txtool.commands.progress import file_progress

    with file_progress() as progress:
        result = lint_paths(list(paths) or ["."], options, progress)
    for note in result.notes:
        click.echo(f"txtool: note: {printable(note)}", err=True)
    for error in result.errors:
        click.echo(f"txtool: {printable(error.message)}", err=True)
    fmt = output_format or default_format()
    if (quiet or statistics) and fmt != "text":
        raise click.UsageError(f"--quiet and --statistics go with --format text, not {fmt}")
    summary = Summary.of(result.problems, result.files, failures=result.errors,
                         readers=result.readers)
    colored = fmt == "text" and use_color(color, output_file)
    report = _report(fmt, result.problems, summary, colored, quiet, statistics)
    if output_file is None:
        click.echo(report, nl=False, color=True)
    else:
        from txtool.io.xmlio import write_atomic

        write_atomic(output_file, report.encode("utf-8"), inputs=tuple(paths), report=True)
    return exit_code(result, options)


def _warn_unused_args(paths: list[str], no_xacro: bool) -> None:
    """``--xacro-arg`` never silently dropped: xacro off by the command line or environment,
    or only files named, none of which xacro expands."""
    from txtool.commands.common import xacro_disabled
    from txtool.io.load import OFF, PLAIN, STDIN, file_needs_expansion, warn_unused_args

    if xacro_disabled(no_xacro):
        warn_unused_args("validate", OFF)
        return
    only_files = paths and all(p == "-" or os.path.isfile(p) for p in paths)
    if only_files and all(p == "-" or file_needs_expansion(p) is False for p in paths):
        for path in paths:
            warn_unused_args("<stdin>" if path == "-" else path, STDIN if path == "-" else PLAIN)


def _report(fmt: str, problems, summary, colored: bool, quiet: bool, statistics: bool) -> str:
    from txtool.reporters import render, text

    if statistics:
        return text.statistics(problems, summary)
    if quiet:
        return text.render_quiet(problems, color=colored)
    return render(fmt, problems, summary, color=colored)
