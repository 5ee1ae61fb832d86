"""``txtool completion SHELL``: the shell completion script (click's)."""

from __future__ import annotations

import click

from txtool.commands.common import Choice

SHELLS = ("bash", "zsh", "fish")


@click.command("completion")
@click.argument("shell", type=Choice(SHELLS))
def command(shell: str) -> None:
    """Print the completion script for SHELL (bash, zsh or fish): commands, options, choices,
    and files for file arguments."""
    from click.shell_completion import get_completion_class

    root = click.get_current_context().find_root()
    completion_class = get_completion_class(shell)
    assert completion_class is not None  # the three of SHELLS are click's own
    script = completion_class(root.command, {}, "txtool", "_TXTOOL_COMPLETE").source()
    click.echo(script.rstrip("\n"))
