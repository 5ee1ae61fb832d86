"""What the fuzz suite found, one focused test per fix, with the smallest document that showed it."""

from __future__ import annotations

import textwrap
from pathlib import Path

from click.testing import CliRunner, Result

from txtool.cli import cli


def run(tmp_path: Path, xml: str, *args: str, name: str = "robot.urdf") -> tuple[Result, str]:
    """Write ``xml`` (dedented) as ``name`` and run ``txtool ARGS[0] PATH ARGS[1:]``."""
    path = tmp_path / name
    path.write_text(textwrap.dedent(xml).lstrip("\n"), encoding="utf-8")
    command, *options = args
    result = CliRunner().invoke(cli, [command, str(path), *options], catch_exceptions=True)
    assert result.exception is None or isinstance(result.exception, SystemExit), (
        f"crash: {result.exception!r}"
    )
    return result, str(path)


def test_bb_export_of_a_document_without_transmissions_says_so(tmp_path):
    result, _ = run(tmp_path, """
        <robot name="r">
          <link name="base"/>
        </robot>
    """, "convert", "--to", "bb")
    assert (result.exit_code, result.stdout) == (0, "# no transmission to export\n")
