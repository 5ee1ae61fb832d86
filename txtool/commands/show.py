"""``txtool show FILE``: the transmissions of a document."""

from __future__ import annotations

import json

import click

from txtool.commands.common import (
    FORMAT_OPTION,
    NO_XACRO_OPTION,
    exit_on_input_error,
    xacro_disabled,
    xacro_options,
)


@click.command("show")
@click.argument("path", metavar="FILE")
@FORMAT_OPTION
@click.option("--actuator-limits", is_flag=True,
              help="Also map each joint's URDF limits into actuator space.")
@click.option("--stdin-filename", help="Name to report for '-' (stdin).")
@NO_XACRO_OPTION
@xacro_options
@exit_on_input_error
def command(path, output_format, actuator_limits, stdin_filename, no_xacro, xacro) -> int:
    """List the transmissions of FILE (URDF, xacro or a fragment; '-' for stdin).

    Under --no-xacro a .xacro file's transmissions are listed as written, ${...} included.
    """
    from txtool.dialects.read import read_source
    from txtool.io.load import load
    from txtool.model.core import dump

    expand = not xacro_disabled(no_xacro, path)
    source = load(path, xacro=xacro, stdin_name=stdin_filename, expand=expand)
    transmissions = [f.transmission for f in read_source(source)]
    limits = _limits(source, transmissions) if actuator_limits else None
    if output_format == "json":
        data = {"transmissions": [dump(t) for t in transmissions]}
        if limits is not None:
            data["actuator_limits"] = [
                {"transmission": t, "actuator": a, "position": lim.position,
                 "velocity": lim.velocity, "effort": lim.effort}
                for t, a, lim in limits
            ]
        click.echo(json.dumps(data, indent=2))
        return 0
    from txtool.views.render import console as make_console
    from txtool.views.render import limits_table, transmissions_table

    console = make_console()
    console.print(transmissions_table(transmissions, f"{source.path}: "
                                      f"{len(transmissions)} transmission(s)"))
    if limits is not None:
        console.print(limits_table(limits))
    return 0


def _limits(source, transmissions):
    from txtool.mechanics.limits import actuator_limits
    from txtool.mechanics.maps import from_transmission
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
