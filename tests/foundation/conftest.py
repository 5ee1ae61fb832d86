from __future__ import annotations

from pathlib import Path

import pytest
from click.testing import CliRunner

from txtool.cli import cli

FIXTURES = Path(__file__).resolve().parents[2] / "fixtures"


@pytest.fixture
def run():
    """Run ``txtool ARGS``; returns (exit code, stdout, stderr)."""

    def invoke(*args: str, input: str | None = None):
        result = CliRunner().invoke(cli, list(args), input=input, catch_exceptions=False)
        return result.exit_code, result.stdout, result.stderr

    return invoke


@pytest.fixture
def fixtures() -> Path:
    return FIXTURES
