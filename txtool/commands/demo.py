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
    for name, source in layout.items():
        (root / name).parent.mkdir(parents=True, exist_ok=True)
        write_atomic(str(root / name), source.read_bytes())
    click.echo(f"wrote {len(layout)} files into {folder}: cd there to follow the examples "
               "of the documentation")
    return 0
