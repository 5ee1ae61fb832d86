"""``txtool schema [NAME]``: the JSON Schema of a command's JSON output (or input file)."""

from __future__ import annotations

import click

from txtool.commands.common import Choice, exit_on_input_error

# Each schema by the name it is chosen by: the file shipped in schemas/ and what it describes.
SCHEMAS = {
    "show": ("transmission.schema.json", "txtool show --format json"),
    "validate": ("report.schema.json", "txtool validate --format json"),
    "map": ("map.schema.json", "txtool map --format json"),
    "roundtrip": ("roundtrip.schema.json", "txtool roundtrip --format json"),
    "rules": ("rules.schema.json", "txtool rules --format json"),
    "simulate": ("simulate.schema.json", "txtool simulate --format json"),
    "campaign": ("campaign.schema.json", "a txtool simulate --campaign file (TOML)"),
}


@click.command("schema")
@click.argument("name", type=Choice(tuple(SCHEMAS)), default="show", required=False)
@click.option("--list", "listing", is_flag=True, help="List the schemas: name, file, what.")
@click.option("-o", "--output", type=click.Path(dir_okay=False),
              help="Write to a file (atomically).")
@exit_on_input_error
def command(name, listing, output) -> int:
    """Print the JSON Schema NAME: show (the default), validate, map, roundtrip, rules,
    simulate or campaign (--list says what each describes)."""
    from txtool.io.xmlio import write_atomic

    if listing:
        width = max(map(len, SCHEMAS))
        files = max(len(file_name) for file_name, _ in SCHEMAS.values())
        for each, (file_name, what) in SCHEMAS.items():
            click.echo(f"{each:<{width}}  schemas/{file_name:<{files}}  {what}")
        return 0
    text = _text(name)
    if output:
        write_atomic(output, text.encode("utf-8"), report=True)
    else:
        click.echo(text, nl=False)
    return 0


def _text(name: str) -> str:
    if name == "show":  # generated from the model, as before NAME was an argument
        from txtool.model.schema import schema_text

        return schema_text()
    from txtool.io.resources import shipped

    return shipped("schemas", SCHEMAS[name][0]).read_text(encoding="utf-8")
