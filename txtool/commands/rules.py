"""``txtool rules [CODE]``: the rule catalogue, or one rule's documentation."""

from __future__ import annotations

import json

import click

from txtool.commands.common import Choice, complete_rules, exit_on_input_error


@click.command("rules")
@click.argument("code", required=False, shell_complete=complete_rules)
@click.option("--format", "output_format", type=Choice(["text", "json"]), default="text",
              show_default=True, help="Output format.")
@exit_on_input_error
def command(code: str | None, output_format: str) -> int:
    """List every rule, or show the documentation of CODE (a code such as TX105, or a name)."""
    from txtool.io.xmlio import InputError
    from txtool.lint.ruledoc import markdown, plain
    from txtool.rules import UnknownRule, all_rules, get

    if code is None:
        rules = list(all_rules().values())
    else:
        try:
            rules = [get(code)]
        except UnknownRule as exc:
            raise InputError(f"{exc} (see 'txtool rules')") from None
    if output_format == "json":
        rows = [
            {"code": r.code, "name": r.name, "severity": r.severity, "fixable": r.fixable,
             "summary": plain(r.summary), "doc": plain(r.doc),
             "markdown": markdown(r, heading="#")}
            for r in rules
        ]
        click.echo(json.dumps(rows, indent=2))  # one shape: a list, of one rule for CODE
    elif code is None:
        width = max(len(r.name) for r in rules)
        for r in rules:
            fix = "fix" if r.fixable else "   "
            click.echo(f"{r.code}  {r.name:<{width}}  {r.severity:<7}  {fix}  {plain(r.summary)}")
    else:
        rule = rules[0]
        fixable = (", fixable by 'txtool validate --fix' and 'txtool migrate'" if rule.fixable
                   else "")
        click.echo(f"{rule.code} {rule.name} (default severity: {rule.severity}{fixable})\n")
        click.echo(plain(rule.doc))
    return 0
