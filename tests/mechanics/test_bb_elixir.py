"""The Elixir that ``convert --to bb`` writes parses (``Code.string_to_quoted!``), for the test
robots and for every file of the corpus. Needs ``elixir`` (Debian package ``elixir``)."""

from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

import pytest
from click.testing import CliRunner

from tests.corpus import corpus_files
from tests.mechanics.test_bb_export import THREE, convert, robot
from tests.mechanics.test_bb_topology import ROBOT
from txtool.cli import cli

ELIXIR = shutil.which("elixir")
pytestmark = pytest.mark.skipif(
    ELIXIR is None, reason="elixir is not installed (Debian: apt-get install elixir)")

PARSE_ALL = """
for path <- System.argv() do
  try do
    Code.string_to_quoted!(File.read!(path))
  rescue
    e -> IO.puts("#{path}: #{Exception.message(e)}")
  end
end
"""


def parse_errors(tmp_path: Path, texts: dict[str, str]) -> list[str]:
    """One ``elixir`` run over all texts; the lines of those that do not parse."""
    script = tmp_path / "parse.exs"
    script.write_text(PARSE_ALL)
    paths = []
    for name, text in texts.items():
        path = tmp_path / f"{name}.exs"
        path.write_text(text)
        paths.append(str(path))
    done = subprocess.run([ELIXIR or "elixir", str(script), *paths], capture_output=True,
                          text=True, timeout=300, check=True)
    return done.stdout.splitlines()


def test_the_parser_check_can_fail(tmp_path: Path) -> None:
    errors = parse_errors(tmp_path, {"bad": "joint :a do\n  actuator :m, Driver do\nend\n"})
    assert len(errors) == 1 and errors[0].startswith(f"{tmp_path}/bad.exs: ")


def test_test_robots_parse(tmp_path: Path) -> None:
    texts = {}
    for i, options in enumerate(([], ["--bb-direction", "negative-reduction"])):
        texts[f"three{i}"] = convert(tmp_path, robot(THREE), *options)[1]
        texts[f"topology{i}"] = convert(tmp_path, ROBOT.format(body=THREE), "--bb-topology",
                                        "--allow-lossy", *options)[1]
    assert all("transmission do" in text for text in texts.values())
    assert parse_errors(tmp_path, texts) == []


def test_every_corpus_file_exports_parseable_elixir(tmp_path: Path) -> None:
    texts = {}
    for path in corpus_files():
        for mode in ([], ["--bb-topology"]):
            result = CliRunner().invoke(
                cli, ["convert", str(path), "--to", "bb", "--allow-lossy", *mode],
                catch_exceptions=False)
            # 2: a xacro file whose packages are not here (its one-line reason on stderr)
            assert result.exit_code in (0, 2), (path.name, result.stderr)
            if result.exit_code == 0:
                texts[f"{path.name}{'.topology' if mode else ''}"] = result.stdout
    with_actuators = [name for name, text in texts.items() if "actuator :" in text]
    assert len(with_actuators) >= 20  # the corpus has many robots with simple transmissions
    assert parse_errors(tmp_path, texts) == []
