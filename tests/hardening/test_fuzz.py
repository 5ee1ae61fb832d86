"""No traceback, ever: every command on mutated fixtures and corpus files ends as promised.

Each example is one mutated document (see ``fuzz_inputs.py``) run through one command in-process
with click's CliRunner, which, unlike ``txtool``'s ``main()``, lets an internal error surface
as an exception. The run must exit 0, 1 or 2 with a message and no traceback, exit 2 with a
``txtool:`` line on stderr, never exit 2 from ``validate`` on a readable file, and print valid
JSON when asked for JSON. ``bench/fuzz.py`` runs the same documents for longer.
"""

from __future__ import annotations

import tempfile

import pytest
from click.testing import CliRunner
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from tests.hardening.fuzz_inputs import (
    COMMANDS,
    FuzzDocument,
    documents,
    extra_arguments,
    run_failure,
    write_inputs,
)
from txtool.cli import cli

EXAMPLES_PER_COMMAND = 120  # x 19 commands: 2,280 examples


@pytest.mark.parametrize("command", sorted(COMMANDS))
@settings(max_examples=EXAMPLES_PER_COMMAND, deadline=None,
          suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large,
                                  HealthCheck.large_base_example])
@given(document=documents(), data=st.data())
def test_every_run_ends_with_an_exit_code_and_a_message(
    command: str, document: FuzzDocument, data: st.DataObject,
    tmp_path_factory: pytest.TempPathFactory,
) -> None:
    extra = data.draw(extra_arguments(command, document), label="arguments")
    with tempfile.TemporaryDirectory(dir=tmp_path_factory.getbasetemp()) as folder:
        run = write_inputs(folder, command, document, extra)
        result = CliRunner().invoke(cli, run.argv, input=run.stdin, catch_exceptions=True)
    failure = run_failure(command, run.path, result)
    assert failure is None, f"{failure}\nstdout: {result.stdout[:2000]}\nstderr: {result.stderr[:2000]}"
