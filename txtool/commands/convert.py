"""``txtool convert INPUT --to DIALECT``: the whole document in another dialect."""

from __future__ import annotations

import os
import sys

import click

from txtool.commands.common import (
    CONFIG_OPTION,
    FILE,
    NO_XACRO_OPTION,
    TARGET_HINTS,
    Choice,
    configured_packages,
    controller_configurations,
    controllers_option,
    exit_on_input_error,
    tell_controller_needs,
    xacro_disabled,
    xacro_options,
)
from txtool.io.printable import printable
from txtool.model.distro import CHOICES as DISTROS

TARGETS = ("ros1", "ros2-p1", "ros2-p2", "bb")


@click.command("convert")
@click.argument("path", metavar="INPUT", type=FILE)
@click.option("--to", "target", type=Choice(TARGETS, hints=TARGET_HINTS), required=True,
              help="Target dialect (bb: Beam Bots DSL blocks for simple transmissions).")
@click.option("-o", "--output", type=click.Path(dir_okay=False),
              help="Write here (atomically) instead of stdout.")
@click.option("--write", "in_place", is_flag=True, help="Allow OUTPUT to be INPUT itself.")
@click.option("--allow-lossy", is_flag=True,
              help="Exit 0 even when something cannot be carried (it is still reported).")
@click.option("--hardware-plugin", default=None, show_default="mock_components/GenericSystem",
              help="<plugin> of a <ros2_control> block created for ROS 1 transmissions "
                   "(the default, ros2_control's mock hardware, is a placeholder to replace).")
@click.option("--reversible", is_flag=True,
              help="To ROS 2: keep each transmission's original text in a comment before it, "
                   "so that converting back gives its bytes back.")
@controllers_option("the converted robot")
@click.option("--stdin-filename", help="Name to report for '-' (stdin).")
@click.option("--ros-distro", type=click.Choice(DISTROS), default=None,
              help="Check what is written for this distribution's loaders only (default: "
                   "every ROS 2 distribution for ros2-p1/ros2-p2, noetic for ros1).")
# --- Beam Bots (--to bb) options ---
@click.option("--bb-direction", type=Choice(["reversed", "negative-reduction"]),
              help="bb: write a reversed joint as 'reversed? true' (default) or as a negative "
                   "reduction (which BB's URDF exporter keeps).")
@click.option("--bb-topology", is_flag=True,
              help="bb: write a whole 'topology do ... end' of the robot's links and joints.")
# --- end of Beam Bots options ---
@NO_XACRO_OPTION
@CONFIG_OPTION
@xacro_options
@exit_on_input_error
def command(path, target, output, in_place, allow_lossy, hardware_plugin, reversible,
            controller_files, stdin_filename, ros_distro, bb_direction, bb_topology, no_xacro,
            config_path, xacro) -> int:
    """Convert the transmissions of INPUT to another dialect, keeping the rest of the document.

    The result is read back and converted back; anything that does not survive, or that the
    target loader would read differently, is reported; what is written is checked with
    validate's rules for the target's loaders (ros2_control of every ROS 2 distribution, or
    --ros-distro's; ros_control for ros1), and an error there is a loss. Exit 1 if anything
    would be lost (unless --allow-lossy), 2 on unreadable input. A xacro INPUT is converted
    after expansion; under --no-xacro its source is converted as written, ${...} kept.
    """
    from txtool.io.load import load
    from txtool.io.xmlio import InputError, replace_if_unchanged, write_atomic

    controllers = controller_configurations(controller_files, target)  # before any write
    if target != "bb" and (bb_direction or bb_topology):
        raise InputError("--bb-direction and --bb-topology apply to --to bb only")
    if target == "bb" and ros_distro:
        raise InputError("--ros-distro applies to robot dialects, not --to bb")
    distro = _distro(target, ros_distro)
    if reversible and target in ("ros1", "bb"):
        raise InputError("--reversible applies to --to ros2-p1 and ros2-p2 (converting back to "
                         "ros1 puts carried originals back by itself)")
    in_place_target = bool(output) and path != "-" and _same_file(path, output)
    if target == "bb" and in_place_target:
        raise InputError(f"{output}: is the input file; --to bb writes Elixir, not a robot")
    if in_place_target and not in_place:
        raise InputError(f"{output}: is the input file; add --write to convert it in place")
    expand = not xacro_disabled(no_xacro, path, config=config_path)
    if expand:
        xacro = configured_packages(xacro, path, config_path)
    source = load(path, xacro=xacro, stdin_name=stdin_filename, expand=expand)
    if in_place_target and source.expanded:
        raise InputError(f"{path}: converting a xacro file in place would replace it with its "
                         "expansion; use 'txtool migrate --write --to TARGET' (or --no-xacro)")
    to_bb = target == "bb"  # Elixir, not a robot: kept off robot descriptions as a report is
    placeholder = None  # the placeholder plugin a generated block names, said once written
    if to_bb:
        data, losses, notes = _bb(source, bb_direction or "reversed", bb_topology)
    else:
        from txtool.transform.convert import convert_source
        from txtool.transform.edits.declaration import without_late_declaration
        from txtool.transform.placement.placer import DEFAULT_HARDWARE_PLUGIN

        result = convert_source(source, target, consume=True, reversible=reversible,
                                hardware_plugin=hardware_plugin or DEFAULT_HARDWARE_PLUGIN)
        # Well-formed even where nothing changed: a declaration after a comment or spaces
        # (which txtool reads) is not printed there.
        data = without_late_declaration(result.data)
        # Not needed here: released before the check lints what is written (the edits hold
        # the bytes the conversion adds).
        result.edits = None
        judged = _judged(data, source, target, distro, path, xacro, stdin_filename)
        if source.expanded:  # xacro's text: a few long lines, this machine's paths
            from txtool.io.expansion_text import readable

            data = readable(data, source.path)
        losses, notes = [*result.losses, *judged.losses], result.notes
        for left in [*result.warnings, *judged.warnings]:
            click.echo(f"warning: {printable(left)}", err=True)
        # (one named on the command line was chosen: not a placeholder)
        placeholder = result.placeholder if hardware_plugin is None else None
        if not result.converted and not result.losses:
            held = (f"{result.found} found, {result.already} already {target}; the document is "
                    "unchanged" if result.found else "the document has no transmission")
            click.echo(f"txtool: {printable(source.path)}: 0 transmissions converted ({held})",
                       err=True)
    for note in notes:
        click.echo(f"note: {printable(note)}", err=True)
    for loss in losses:
        click.echo(f"{'warning' if allow_lossy else 'error'}: {printable(loss)}", err=True)
    if losses and not allow_lossy:
        click.echo(f"txtool: {len(losses)} item(s) would be lost; nothing written "
                   "(use --allow-lossy to accept)", err=True)
        return 1
    if in_place_target:
        replace_if_unchanged(output, source.data, data, "conversion")
    elif output:
        write_atomic(output, data, report=to_bb, inputs=(path,))
    else:
        sys.stdout.flush()
        sys.stdout.buffer.write(data)
        sys.stdout.buffer.flush()
    if placeholder is not None:
        click.echo(f"warning: {printable(placeholder)}", err=True)
    if controllers:
        from txtool.io.xmlio import parse_bytes

        tell_controller_needs(controllers, {source.path: parse_bytes(data, source.path).getroot()})
    return 0


def _distro(target: str, ros_distro: str | None):
    from txtool.io.xmlio import InputError
    from txtool.lint.target_check import target_distro

    try:
        return target_distro(None if target == "bb" else target, ros_distro)  # type: ignore[arg-type]
    except ValueError as exc:
        raise InputError(str(exc)) from None


def _judged(data: bytes, source, target: str, distro, path: str, xacro, stdin_filename):
    """What the target's loaders say of ``data`` that they did not say of the input."""
    from txtool.io.load import load
    from txtool.lint.target_check import judge_converted

    def reload():
        return load(path, xacro=xacro, stdin_name=stdin_filename, expand=True)

    return judge_converted(data, source, target, distro=distro,  # type: ignore[arg-type]
                           reload=reload if path != "-" else None)


def _same_file(a: str, b: str) -> bool:
    """Whether ``b`` names the file ``a`` (any spelling, symbolic or hard link)."""
    try:
        return os.path.samefile(a, b)
    except OSError:  # either one missing or unreadable: not the same existing file
        return False


def _bb(source, direction: str, topology: bool) -> tuple[bytes, list[str], list[str]]:
    from txtool.transform.bb.export import export_bb

    exported = export_bb(source, direction=direction, topology=topology)  # type: ignore[arg-type]
    return exported.text.encode("utf-8"), exported.losses, exported.notes
