"""``txtool convert INPUT --to DIALECT``: the whole document in another dialect."""

from __future__ import annotations

import os
import sys

import click

from txtool.commands.common import exit_on_input_error, xacro_options

TARGETS = ("ros1", "ros2-p1", "ros2-p2", "bb")


@click.command("convert")
@click.argument("path", metavar="INPUT")
@click.option("--to", "target", type=click.Choice(TARGETS), required=True,
              help="Target dialect (bb: Beam Bots DSL blocks for simple transmissions).")
@click.option("-o", "--output", type=click.Path(dir_okay=False),
              help="Write here (atomically) instead of stdout.")
@click.option("--write", "in_place", is_flag=True, help="Allow OUTPUT to be INPUT itself.")
@click.option("--allow-lossy", is_flag=True,
              help="Exit 0 even when something cannot be carried (it is still reported).")
@click.option("--hardware-plugin", default="mock_components/GenericSystem", show_default=True,
              help="<plugin> of a <ros2_control> block created for ROS 1 transmissions.")
@click.option("--stdin-filename", help="Name to report for '-' (stdin).")
@xacro_options
@exit_on_input_error
def command(path, target, output, in_place, allow_lossy, hardware_plugin, stdin_filename,
            xacro) -> int:
    """Convert the transmissions of INPUT to another dialect, keeping the rest of the document.

    The result is read back and converted back; anything that does not survive, or that the
    target loader would read differently, is reported. Exit 1 if anything would be lost
    (unless --allow-lossy), 2 on unreadable input.
    """
    from txtool.xmlio import InputError, load, write_atomic

    if output and path != "-" and _same_file(path, output) and not in_place:
        raise InputError(f"{output}: is the input file; add --write to convert it in place")
    source = load(path, xacro=xacro, stdin_name=stdin_filename)
    if target == "bb":
        data, losses, notes = _bb(source)
    else:
        from txtool.convert import convert_source

        result = convert_source(source, target, hardware_plugin=hardware_plugin)
        data, losses, notes = result.data, result.losses, result.notes
    for note in notes:
        click.echo(f"note: {note}", err=True)
    for loss in losses:
        click.echo(f"{'warning' if allow_lossy else 'error'}: {loss}", err=True)
    if losses and not allow_lossy:
        click.echo(f"txtool: {len(losses)} item(s) would be lost; nothing written "
                   "(use --allow-lossy to accept)", err=True)
        return 1
    if output:
        write_atomic(output, data)
    else:
        sys.stdout.flush()
        sys.stdout.buffer.write(data)
        sys.stdout.buffer.flush()
    return 0


def _same_file(a: str, b: str) -> bool:
    return os.path.exists(b) and os.path.realpath(a) == os.path.realpath(b)


def _bb(source) -> tuple[bytes, list[str], list[str]]:
    from txtool.bb import export_bb
    from txtool.reader import read_source
    from txtool.robot import robot_joints

    exported = export_bb([f.transmission for f in read_source(source)],
                         robot_joints(source.root))
    return exported.text.encode("utf-8"), list(exported.not_representable), []
