"""``txtool map``: joint <-> actuator values of one transmission (argument parsing only)."""

from __future__ import annotations

import click

from txtool.commands.common import (
    CONFIG_OPTION,
    FILE,
    NO_XACRO_OPTION,
    Choice,
    configured_packages,
    refuse_unexpanded,
    xacro_disabled,
    xacro_options,
)
from txtool.io.printable import printable
from txtool.io.xmlio import InputError


@click.command("map")
@click.argument("file", type=FILE)
@click.option("--transmission", "-t", "name", required=True, help="Name of the transmission.")
@click.option("--to", "to", required=True, type=Choice(["actuator", "joint"]),
              help="actuator: map joint values to the actuators; joint: the reverse.")
@click.option("--position", metavar="V[,V]", help="Positions, in role order.")
@click.option("--velocity", metavar="V[,V]", help="Velocities, in role order.")
@click.option("--effort", metavar="V[,V]", help="Efforts (torques or forces), in role order.")
@click.option("--effort-convention", "convention", type=Choice(["ros2", "ros1"]),
              help="Four-bar effort map: ros2_control's (power-conserving) or ros_control's. "
                   "Default: that of the loader reading FILE's transmission.")
@click.option("--format", "fmt", type=Choice(["text", "json"]), default="text",
              show_default=True)
@NO_XACRO_OPTION
@CONFIG_OPTION
@xacro_options
def command(
    file: str,
    name: str,
    to: str,
    position: str | None,
    velocity: str | None,
    effort: str | None,
    convention: str | None,
    fmt: str,
    no_xacro: bool,
    config_path: str | None,
    xacro,
) -> None:
    """Map positions, velocities or efforts through transmission NAME of FILE.

    Values are comma-separated in role order (joint1,joint2 or actuator1,actuator2) and are
    printed in the same order, whatever order ros2_control gives the handles (by name).
    A .xacro FILE is refused under --no-xacro.
    """
    from txtool.mechanics.mapcmd import render_text, run_map

    try:
        if xacro_disabled(no_xacro, file, config=config_path):
            refuse_unexpanded("map", file)
        else:
            xacro = configured_packages(xacro, file, config_path)
    except InputError as exc:
        click.echo(f"txtool: {printable(str(exc))}", err=True)
        raise SystemExit(2) from None

    outcome = run_map(file, name, to, position=position, velocity=velocity, effort=effort,
                      convention=convention, xacro=xacro)
    if outcome.exit_code:
        click.echo(f"txtool: {printable(outcome.error)}", err=True)
        raise SystemExit(outcome.exit_code)
    click.echo(outcome.to_json() if fmt == "json" else render_text(outcome), nl=fmt == "json")
