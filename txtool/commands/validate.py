"""``txtool validate``: lint transmission configurations (argument parsing only)."""

from __future__ import annotations

import os
import sys
from typing import NamedTuple

import click

from txtool.commands.common import (
    COLOR_MODES,
    Choice,
    RenamedOption,
    color_wanted,
    complete_codes,
    exit_on_input_error,
    xacro_options,
)
from txtool.io.printable import printable
from txtool.model.distro import CHOICES

FORMATS = ("text", "concise", "json", "github", "sarif", "junit", "gitlab")


class OutputFormat(Choice):
    """``NAME`` (the report on stdout, or in ``--output``) or ``NAME:FILE`` (that report
    written to FILE too), as pylint's ``--output-format=json:report.json``."""

    name = "format"

    def convert(self, value, param, ctx) -> tuple[str, str | None]:
        name, colon, path = str(value).partition(":")
        if colon and not path:
            self.fail(f"{value!r}: no file name after ':'", param, ctx)
        return super().convert(name, param, ctx), path or None


def _codes(values: tuple[str, ...]) -> tuple[str, ...]:
    return tuple(code.strip() for value in values for code in value.split(",") if code.strip())


def default_format() -> str:
    return "github" if os.environ.get("GITHUB_ACTIONS") == "true" else "text"


def use_color(mode: str, output_file: str | None = None) -> bool:
    return color_wanted(mode, output_file is None and sys.stdout.isatty())


def terminal_width(output_file: str | None) -> int | None:
    """The width the text report wraps to: a terminal's (COLUMNS if set), else None."""
    if output_file is not None or not sys.stdout.isatty():
        return None
    import shutil

    return shutil.get_terminal_size().columns


@click.command("validate")
@click.argument("paths", nargs=-1, type=click.Path())
@click.option("--format", "output_formats", type=OutputFormat(FORMATS), multiple=True,
              metavar="[" + "|".join(FORMATS) + "][:FILE]",
              help="Output format [default: text; github when GITHUB_ACTIONS=true]; "
                   "NAME:FILE writes that report to FILE as well (repeatable, e.g. "
                   "--format github --format sarif:txtool.sarif).")
@click.option("--select", multiple=True, metavar="CODES", shell_complete=complete_codes,
              help="Only these rule codes or prefixes (comma-separated, repeatable).")
@click.option("--ignore", multiple=True, metavar="CODES", shell_complete=complete_codes,
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
@click.option("--fix", is_flag=True,
              help="Apply the fixable rules' fixes (as txtool migrate does) to the files "
                   "holding fixable findings [*], then report what remains.")
@click.option("--diff", is_flag=True,
              help="Write nothing; print the unified diff --fix would make and exit 1 if it "
                   "would change a file.")
@click.option("-q", "--quiet", is_flag=True,
              help="Text format: print the findings only, no summary line.")
@click.option("--statistics", is_flag=True,
              help="Text format: count the findings per rule instead of listing them.")
@click.option("--exclude", multiple=True, metavar="PATTERN",
              help="gitignore-style pattern of files and folders that folder walks pass over, "
                   "relative to this folder; replaces the configuration's exclude (repeatable).")
@click.option("--extend-exclude", multiple=True, metavar="PATTERN",
              help="Like --exclude, but kept beside the configuration's exclude (repeatable).")
@click.option("--force-exclude", is_flag=True,
              help="Exclude patterns pass over files named on the command line too (as "
                   "pre-commit names every staged .xml file).")
@click.option("--respect-gitignore/--no-respect-gitignore", default=None,
              help="Pass over what .gitignore files ignore in folder walks [default: respect].")
@click.option("--ros-distro", type=click.Choice(CHOICES), default=None,
              help="The ROS distribution whose programs read the files (over the "
                   "configuration's ros-distro and what package.xml and <gazebo> plugins say).")
@click.option("--controllers", "controller_files", multiple=True,
              type=click.Path(dir_okay=False), metavar="FILE",
              help="A controller configuration (YAML) to check against the robot files "
                   "(TX5xx; repeatable). Folder walks pair a package's robot with its own.")
@xacro_options
@exit_on_input_error
def command(paths, output_formats, select, ignore, strict, exit_zero, config_path, no_xacro,
            stdin_filename, jobs, color, output_file, fix, diff, quiet, statistics, exclude,
            extend_exclude, force_exclude, respect_gitignore, ros_distro, controller_files,
            xacro) -> int:
    """Check transmissions in files and folders (*.urdf, *.xacro, robot *.xml; '-' is stdin).

    A file named whose root element is no robot description's (a launch file, package.xml,
    an SDF world) is passed over.

    Exit codes: 0 nothing at the failing level, 1 findings at it (errors; warnings too with
    --strict; infos never), 2 usage, configuration or input error.
    """
    from txtool.commands.validate_fix import FixSelection, apply_fixes, print_diff
    from txtool.lint.api import LintOptions, exit_code, lint_paths

    main, files = _outputs(output_formats, output_file)
    if (quiet or statistics) and main not in ("text", "concise"):
        raise click.UsageError("--quiet and --statistics go with --format text or concise, "
                               f"not {main}")
    if diff and (output_formats or output_file or quiet or statistics):
        raise click.UsageError("--diff prints a diff: it takes no --format, --output, "
                               "--quiet or --statistics")
    if (fix or diff) and "-" in paths:
        raise click.UsageError(f"--{'diff' if diff else 'fix'} rewrites files in place; "
                               "standard input ('-') cannot be fixed")
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
        force_exclude=force_exclude,
        respect_gitignore=respect_gitignore,
        ros_distro=ros_distro,
        controllers=tuple(controller_files),
    )
    if xacro.args:
        _warn_unused_args(list(paths), no_xacro)
    targets = list(paths) or ["."]
    selection = FixSelection(options.select, options.ignore, config_path, ros_distro,
                             options.xacro, options.no_xacro, options.jobs)
    from txtool.commands.progress import file_progress

    with file_progress() as progress:
        result = lint_paths(targets, options, progress)
    fix_failed = refused = False
    if diff:
        tell(result)
        return print_diff(result, selection)
    if fix:
        fixed, fix_failed, refused = apply_fixes(result, selection)
        if fixed:
            result = lint_paths(targets, options)
    tell(result)
    stdin_name = (stdin_filename or "<stdin>") if "-" in paths else None
    code = _report_all(result, main, files, output_file, stdin_name, selection,
                       _Look(use_color(color, output_file), quiet, statistics,
                             ("error", "warning") if strict else ("error",),
                             terminal_width(output_file)), paths)
    return 2 if fix_failed else max(code, exit_code(result, options), int(refused))


class _Look(NamedTuple):
    color: bool
    quiet: bool
    statistics: bool
    failing: tuple[str, ...]  # the severities that fail the run (JUnit failures)
    width: int | None = None  # a terminal's: the text report wraps to it


def _outputs(formats: tuple[tuple[str, str | None], ...],
             output_file: str | None) -> tuple[str, list[tuple[str, str]]]:
    """The report on stdout (or in --output) and the reports written to files."""
    shown = [name for name, path in formats if path is None]
    if len(shown) > 1:
        raise click.UsageError("--format without a FILE names the report on stdout (or in "
                               f"--output): give one, not {len(shown)}")
    files = [(name, path) for name, path in formats if path is not None]
    paths = [os.path.abspath(path) for _, path in files] + (
        [os.path.abspath(output_file)] if output_file else [])
    if len(set(paths)) < len(paths):
        raise click.UsageError("two reports named the same file")
    return (shown[0] if shown else default_format()), files


def tell(result) -> None:
    """The notes and input errors of a lint run, on stderr."""
    for note in result.notes:
        click.echo(f"txtool: note: {printable(note)}", err=True)
    for error in result.errors:
        click.echo(f"txtool: {printable(error.message)}", err=True)


def _report_all(result, main: str, files: list[tuple[str, str]], output_file: str | None,
                stdin_name: str | None, selection, look: _Look, inputs: tuple[str, ...]) -> int:
    """Print (or write to ``output_file``) the ``main`` report, then write the ``files``
    reports; 2 if one could not be written (the others still are), else 0."""
    from txtool.commands.validate_fix import confirmed
    from txtool.io.xmlio import InputError, write_atomic
    from txtool.reporters import Summary

    wants_edits = any(name == "sarif" for name in [main, *(name for name, _ in files)])
    problems, edits = confirmed(result.problems, stdin_name, selection, with_edits=wants_edits)
    summary = Summary.of(problems, result.files, failures=result.errors, readers=result.readers,
                         edits=edits, failing=look.failing)
    colored = main == "text" and look.color
    outputs = [(output_file, _report(main, problems, summary, colored, look))]
    plain = _Look(False, False, False, look.failing)
    outputs += [(path, _report(name, problems, summary, False, plain)) for name, path in files]
    code = 0
    for path, report in outputs:
        if path is None:
            click.echo(report, nl=False, color=True)
            continue
        try:
            write_atomic(path, report.encode("utf-8"), inputs=tuple(inputs), report=True)
        except InputError as exc:
            click.echo(f"txtool: {printable(str(exc))}", err=True)
            code = 2
    return code


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


def _report(fmt: str, problems, summary, colored: bool, look: _Look) -> str:
    from txtool.reporters import concise, render, text

    if look.statistics:
        return text.statistics(problems, summary)
    if look.quiet and fmt == "concise":
        return "".join(concise.line_of(p) + "\n" for p in problems)
    if look.quiet:
        return text.render_quiet(problems, color=colored, width=look.width)
    return render(fmt, problems, summary, color=colored, width=look.width)
