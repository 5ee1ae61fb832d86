"""``txtool demo``: what txtool does, on the bundled example robot."""

from __future__ import annotations

import click

from txtool.commands.common import exit_on_input_error


@click.command("demo")
@click.option("--copy", "copy_to", metavar="DIR", default=None,
              help="Write the demo robots and the documentation's example files into DIR "
                   "(created if need be) to follow the docs there, instead of the tour.")
@exit_on_input_error
def command(copy_to: str | None) -> int:
    """Show, convert, round-trip, validate and simulate the bundled demo robot."""
    if copy_to is not None:
        return _copy(copy_to)
    from txtool.commands.demo_runner import run_demo
    from txtool.views.render import console

    return run_demo(console())


def _copy(folder: str) -> int:
    """The example files into ``folder``; nothing is written where a file would be replaced."""
    from pathlib import Path

    from txtool.io.resources import example_layout
    from txtool.io.xmlio import InputError, write_atomic

    layout = example_layout()
    root = Path(folder)
    if root.exists() and not root.is_dir():
        raise InputError(f"{folder}: not a folder")
    taken = sorted(name for name in layout if (root / name).exists())
    if taken:
        raise InputError(f"{root / taken[0]}: exists; nothing written (choose an empty folder)")
    if (root / CONFIG).exists():
        raise InputError(f"{root / CONFIG}: exists; nothing written (choose an empty folder)")
    for name, source in layout.items():
        (root / name).parent.mkdir(parents=True, exist_ok=True)
        write_atomic(str(root / name), source.read_bytes())
    write_atomic(str(root / CONFIG), configuration(layout).encode("utf-8"))
    click.echo(f"wrote {len(layout) + 1} files into {folder}: cd there to follow the examples "
               "of the documentation")
    return 0


CONFIG = ".txtool.toml"
# The examples that hold mistakes (or need what a fresh folder lacks) on purpose: the
# documentation runs txtool on each by name, and `txtool validate .` passes them over.
ON_PURPOSE = {
    "arm.urdf.xacro": "a xacro macro with legacy spellings (validate, migrate)",
    "robot.urdf": "ROS 1 legacy spellings (validate --fix, migrate)",
    "rrbot.urdf.xacro": "$(find rrbot_description), a package this folder lacks",
    "untrusted.urdf.xacro": "a xacro file that tries to run code (security)",
    "fixtures/broken_robot.urdf": "a robot with four errors (getting started)",
    "fixtures/four_bar.ros1.urdf": "a four-bar linkage whose notes explain ros_control (TX4xx)",
}


def configuration(layout) -> str:
    """The folder's ``.txtool.toml``: exclude what holds mistakes on purpose, and the ROS 2
    proposal P1 files (``<role>`` elements, which no loader reads), so that the folder
    passes its own ``txtool validate .``."""
    purposeful = {name: why for name, why in ON_PURPOSE.items() if name in layout}
    purposeful.update({name: "proposal P1 (<role> elements): no loader reads it"
                       for name in sorted(layout) if ".ros2-p1." in name})
    lines = ["# The documentation's examples. The files below hold mistakes on purpose: the",
             "# examples run txtool on each by name, and `txtool validate .` passes them over.",
             "exclude = ["]
    lines += [f'    "{name}",  # {why}' for name, why in purposeful.items()]
    return "\n".join([*lines, "]", ""])
