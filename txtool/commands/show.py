"""``txtool show FILE``: the transmissions of a document."""

from __future__ import annotations

import json

import click

from txtool.commands.common import (
    CONFIG_OPTION,
    FILE,
    FORMAT_OPTION,
    NO_XACRO_OPTION,
    configured_packages,
    exit_on_input_error,
    xacro_disabled,
    xacro_options,
)
from txtool.model.distro import CHOICES


@click.command("show")
@click.argument("path", metavar="FILE", type=FILE)
@FORMAT_OPTION
@click.option("--effective", is_flag=True,
              help="Show what each loader binds: parameters after its silent defaults, in its "
                   "index order, beside the joint and actuator it maps there.")
@click.option("--actuator-limits", is_flag=True,
              help="Also map each joint's URDF limits into actuator space.")
@click.option("--stdin-filename", help="Name to report for '-' (stdin).")
@click.option("--ros-distro", type=click.Choice(CHOICES), default=None,
              help="The ROS distribution whose programs read the file (--effective names the "
                   "readers; over the configuration's ros-distro).")
@NO_XACRO_OPTION
@CONFIG_OPTION
@xacro_options
@exit_on_input_error
def command(path, output_format, effective, actuator_limits, stdin_filename, ros_distro,
            no_xacro, config_path, xacro) -> int:
    """List the transmissions of FILE (URDF, xacro or a fragment; '-' for stdin).

    The JSON gives each transmission as written and, under "effective", what its loader
    binds (see --effective). Under --no-xacro a .xacro file's transmissions are listed as
    written, ${...} included.
    """
    from txtool.dialects.read import read_source
    from txtool.io.load import load
    from txtool.views.effective import bindings_of, shown_json

    expand = not xacro_disabled(no_xacro, path, config=config_path)
    if expand:
        xacro = configured_packages(xacro, path, config_path)
    source = load(path, xacro=xacro, stdin_name=stdin_filename, expand=expand)
    found = read_source(source)
    transmissions = [f.transmission for f in found]
    limits = _limits(source, transmissions) if actuator_limits else None
    readers = _readers(source, found, ros_distro, config_path) if effective else None
    if output_format == "json":
        distro = _one_ros2_distro(readers[0]) if readers is not None else None
        data: dict = {"transmissions": shown_json(transmissions, bindings_of(found, distro))}
        if readers is not None:
            from txtool.views.readers_view import readers_json

            data["readers"] = readers_json(*readers)
        if limits is not None:
            data["actuator_limits"] = [
                {"transmission": t, "actuator": a, "position": lim.position,
                 "velocity": lim.velocity, "effort": lim.effort}
                for t, a, lim in limits
            ]
        del source, found, transmissions  # the document goes before its report is written
        _echo_json(data)
        return 0
    from txtool.views.render import console as make_console
    from txtool.views.render import limits_table, print_table, transmissions_table

    console = make_console()
    verdicts = _verdicts(source, transmissions, ros_distro, config_path)
    if readers is not None:
        from txtool.views.effective import effective_text
        from txtool.views.readers_view import readers_text

        assumption, unread = readers
        click.echo(effective_text(source.path, transmissions,
                                  bindings_of(found, _one_ros2_distro(assumption)), unread,
                                  verdicts),
                   nl=False)
        click.echo(readers_text(*readers), nl=False)
    else:
        table = transmissions_table(transmissions, f"{source.path}: "
                                    f"{len(transmissions)} transmission(s)", verdicts)
        print_table(console, table)
    if limits is not None:
        print_table(console, limits_table(limits))
    return 0


_PIECES = 8192  # of the encoder's, written at a time


def _echo_json(data: dict) -> None:
    """``click.echo(json.dumps(data, indent=2))``, written a few thousand pieces at a time:
    with an indent, ``json.dumps`` joins a list of every piece of the text (a few for each
    value), which outweighs the data it encodes."""
    pieces: list[str] = []
    for piece in json.JSONEncoder(indent=2).iterencode(data):
        pieces.append(piece)
        if len(pieces) == _PIECES:
            click.echo("".join(pieces), nl=False)
            pieces.clear()
    pieces.append("\n")
    click.echo("".join(pieces), nl=False)


def _verdicts(source, transmissions, ros_distro, config_path) -> dict[str, list[str]]:
    """What ``txtool validate`` says of each transmission at error or warning (the findings
    whose message names it): ``error TX205: transmission 't' names no hardware interface
    ros_control knows ('PositionJointInterface')``, the finding's first clause."""
    from txtool.lint.api import lint_source
    from txtool.lint.config import ConfigError, Overrides, SettingsCache
    from txtool.reporters.concise import headline

    try:
        settings = SettingsCache(Overrides(ros_distro=ros_distro), config_path).for_file(
            source.path)
    except ConfigError:
        return {}  # validate says what is wrong with the configuration
    problems = [p for p in lint_source(source, settings) if p.severity in ("error", "warning")]
    verdicts: dict[str, list[str]] = {}
    for t in transmissions:
        named = f"transmission '{t.name}'"
        said = [f"{p.severity} {p.code}: {headline(p.message)}" for p in problems
                if named in p.message]
        if said:
            verdicts[t.name] = list(dict.fromkeys(said))
    return verdicts


def _readers(source, found, ros_distro, config_path):
    """The file's readers (the configuration's readers and ros-distro, --config's when given,
    --ros-distro over it) and the names of the transmissions none of them reads."""
    from txtool.lint.config import readers_of
    from txtool.views.readers_view import unread_names

    assumption = readers_of(source, ros_distro, config_path)
    return assumption, unread_names(assumption, [f.element for f in found])


def _one_ros2_distro(assumption):
    """The ROS 2 distribution whose parser reads the file, when one alone does (stated with
    --ros-distro or ros-distro): its values are shown; else every distribution's differences."""
    ros2 = [d for d in assumption.distros if d.ros2]
    return ros2[0] if len(ros2) == 1 else None


def _limits(source, transmissions):
    from txtool.mechanics.limits import actuator_limits
    from txtool.mechanics.points import from_transmission
    from txtool.model.robot import robot_joints
    from txtool.model.semantics import NotLoadable

    joints = robot_joints(source.root)
    rows = []
    for t in transmissions:
        try:
            tmap = from_transmission(t)
        except NotLoadable:
            continue
        for limit in actuator_limits(tmap, joints):
            rows.append((t.name, limit.actuator, limit))
    return rows
