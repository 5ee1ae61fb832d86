"""Suppression comments with a mistake in them: what they still silence, and what is said."""

from __future__ import annotations

from tests.lint.test_suppress import fill
from tests.rules.helpers import check


def test_a_directive_with_a_token_that_is_no_code_still_silences_its_codes():
    """The token is reported (TX005), the codes beside it keep working: a typo in a reason
    written without ';' does not bring back the findings the comment was written for."""
    found = check(fill(next="<!-- txtool: disable-next-line TX106 on purpose -->"))
    assert found == [(7, 5, "TX005", "warning")]


def test_a_code_written_in_lower_case_silences_its_rule():
    assert check(fill(next="<!-- txtool: disable-next-line tx106 -->")) == []
