"""``txtool demo``: what txtool does, on the bundled example robot."""

from __future__ import annotations

import click

from txtool.commands.common import exit_on_input_error


@click.command("demo")
@exit_on_input_error
def command() -> int:
    """Show, convert, round-trip, validate and simulate the bundled demo robot."""
    from txtool.commands.demo_runner import run_demo
    from txtool.views.render import console

    return run_demo(console())
