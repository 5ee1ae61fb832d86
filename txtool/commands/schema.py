"""``txtool schema``: the JSON Schema of the canonical model."""

from __future__ import annotations

import click

from txtool.commands.common import exit_on_input_error


@click.command("schema")
@click.option("-o", "--output", type=click.Path(dir_okay=False),
              help="Write to a file (atomically).")
@exit_on_input_error
def command(output) -> int:
    """Print the JSON Schema of 'txtool show --format json' (schemas/transmission.schema.json)."""
    from txtool.io.xmlio import write_atomic
    from txtool.model.schema import schema_text

    text = schema_text()
    if output:
        write_atomic(output, text.encode("utf-8"), report=True)
    else:
        click.echo(text, nl=False)
    return 0
