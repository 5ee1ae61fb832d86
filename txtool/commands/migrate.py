"""``txtool migrate PATH... (--check | --diff | --write)``: argument parsing only."""

from __future__ import annotations

import click

from txtool.commands.common import (
    TARGET_HINTS,
    Choice,
    complete_codes,
    controller_configurations,
    controllers_option,
    exit_on_input_error,
    tell_controller_needs,
)
from txtool.io.printable import printable
from txtool.model.distro import CHOICES as DISTROS

TARGETS = ("ros1", "ros2-p1", "ros2-p2")


def _codes(values: tuple[str, ...]) -> tuple[str, ...]:
    return tuple(code.strip() for value in values for code in value.split(",") if code.strip())


def _mode(check: bool, diff: bool, write: bool) -> str:
    chosen = [name for name, on in (("check", check), ("diff", diff), ("write", write)) if on]
    if len(chosen) != 1:
        raise click.UsageError("give exactly one of --check, --diff, --write")
    return chosen[0]


@click.command("migrate")
@click.argument("paths", nargs=-1, required=True, type=click.Path())
@click.option("--to", "target", type=Choice(TARGETS, hints=TARGET_HINTS),
              help="Also convert the transmissions to this dialect.")
@click.option("--check", is_flag=True, help="Write nothing; exit 1 if a file would change.")
@click.option("--diff", is_flag=True,
              help="Write nothing; print a unified diff and exit 1 if a file would change.")
@click.option("--write", is_flag=True, help="Rewrite the files that change (atomically).")
@click.option("--select", multiple=True, metavar="CODES", shell_complete=complete_codes,
              help="Only these fix codes or prefixes (comma-separated, repeatable).")
@click.option("--ignore", multiple=True, metavar="CODES", shell_complete=complete_codes,
              help="Skip these fix codes or prefixes (comma-separated, repeatable).")
@click.option("--config", "config_path", type=click.Path(dir_okay=False), metavar="PATH",
              help="Use this configuration file instead of searching for one.")
@click.option("--allow-lossy", is_flag=True,
              help="Convert even when something cannot be carried (it is still reported).")
@click.option("--hardware-plugin", default=None, show_default="mock_components/GenericSystem",
              help="<plugin> of a <ros2_control> block created for ROS 1 transmissions "
                   "(the default, ros2_control's mock hardware, is a placeholder to replace).")
@click.option("--reversible", is_flag=True,
              help="With --to ros2-p1/ros2-p2: keep each transmission's original text in a "
                   "comment before it, so that migrating back gives its bytes back.")
@controllers_option("the migrated robot driving its joints")
@click.option("--ros-distro", type=click.Choice(DISTROS), default=None,
              help="The ROS distribution whose programs read the files, as validate takes it: "
                   "only what validate reports for them is fixed (over the configuration's "
                   "ros-distro and what package.xml and <gazebo> plugins say), and what is "
                   "written is checked for its loaders only (default: every ROS 2 "
                   "distribution for ros2-p1/ros2-p2, noetic for ros1).")
@click.option("--no-xacro", is_flag=True,
              help="Check a xacro file's result as written, not its expansion (the file itself "
                   "is always migrated as written).")
@click.option("--trust-xacro", is_flag=True,
              help="Expand xacro files for the check with upstream xacro in this process "
                   "(only for files you trust).")
@exit_on_input_error
def command(paths, target, check, diff, write, select, ignore, config_path, allow_lossy,
            hardware_plugin, reversible, controller_files, ros_distro, no_xacro,
            trust_xacro) -> int:
    """Apply the fixable rules (and, with --to, the conversion) to files and folders in place.

    Folders are searched like validate does (*.urdf, *.xacro, robot *.xml). xacro files are
    migrated as written: ${...} expressions, macros and comments are kept. What would be
    written is checked with validate's rules for the target's loaders (a xacro file on its
    expansion); an error there that the file did not have is a loss.

    Exit codes: 0 nothing to do (or all written), 1 changes pending (--check, --diff) or a
    file refused for losses, 2 usage, configuration or input error.
    """
    from txtool.io.xmlio import XacroOptions
    from txtool.lint.target_check import target_distro
    from txtool.transform.migrate import DEFAULT_HARDWARE_PLUGIN, MigrateOptions, migrate_paths

    if reversible and target not in ("ros2-p1", "ros2-p2"):
        raise click.UsageError("--reversible needs --to ros2-p1 or --to ros2-p2 (migrating "
                               "back to ros1 puts carried originals back by itself)")
    try:
        target_distro(target, ros_distro)
    except ValueError as exc:
        raise click.UsageError(str(exc)) from None
    controllers = controller_configurations(controller_files, target)  # before any write
    options = MigrateOptions(
        mode=_mode(check, diff, write),  # type: ignore[arg-type]
        target=target,
        select=_codes(select) or None,
        ignore=_codes(ignore),
        config=config_path,
        allow_lossy=allow_lossy,
        hardware_plugin=hardware_plugin or DEFAULT_HARDWARE_PLUGIN,
        plugin_chosen=hardware_plugin is not None,
        reversible=reversible,
        ros_distro=ros_distro,
        xacro=XacroOptions(trust=trust_xacro),
        no_xacro=no_xacro,
    )
    report = migrate_paths(paths, options)
    for diff in report.diffs:
        click.echo(diff, nl=False)
    for message in report.messages:  # each one line, whatever the file names hold
        click.echo(printable(message), err=True)
    if controllers:
        tell_controller_needs(controllers, _robots(report, options))
    return report.exit_code


def _robots(report, options) -> dict:
    """Each migrated robot file, as validate reads it (a xacro file expanded), with what the
    run wrote or would write: its root element by its path. A refused file is left out, and a
    xacro file is expanded with the files it includes as they are on disk (written, under
    --write)."""
    from txtool.io.xmlio import InputError, read_bytes
    from txtool.lint.config import Overrides, SettingsCache
    from txtool.lint.target_check import prepared

    settings = SettingsCache(Overrides(xacro=options.xacro, no_xacro=options.no_xacro,
                                       ros_distro=options.ros_distro), options.config)
    robots = {}
    for result in report.files:
        if result.refused or result.unwritten:
            continue
        try:
            data = result.data if result.changed else read_bytes(result.path)[1]
            source = prepared(result.path, result.path, data, settings.for_file(result.path))
        except InputError:  # changed on disk since: migrate said nothing of it to judge
            continue
        robots[result.path] = source.root
    return robots
