"""Every rule's findings silenced by directives placed before each of their lines, after a first
directive of the same code that silences nothing (reported as unused at its own line).
The documents are the severity table's (test_severities.py), one per rule."""

from __future__ import annotations

import pytest

from tests.rules.helpers import problems
from tests.rules.test_severities import OPTIONS, TABLE

# The syntax error, xacro's failure and the rules about suppressions and XML declarations are
# not silenced by comments placed between lines; TX006 is reported only for named files; the
# controller rules (TX5xx) find in a controller YAML file, not in the robot's XML.
LEFT_OUT = {"TX001", "TX002", "TX003", "TX004", "TX005", "TX006",
            *(code for code in TABLE if code.startswith("TX5"))}


def found(text: str, filename: str, code: str) -> list[tuple[int, str]]:
    return sorted((p.line, p.code) for p in problems(text, filename=filename,
                                                     **OPTIONS.get(code, {})))


@pytest.mark.parametrize("code", sorted(set(TABLE) - LEFT_OUT))
def test_each_finding_line_of_every_rule_is_silenced_by_its_own_directive(code):
    _, document, filename = TABLE[code]
    lines = document.splitlines(keepends=True)
    if not lines[-1].endswith("\n"):
        lines[-1] += "\n"
    marked = sorted({line for line, c in found("".join(lines), filename, code) if c == code})
    assert marked, f"{code} did not fire on its table snippet"
    # the first line without it: its directive comes before the others, which must still
    # silence their own next lines
    spare = next(n for n in range(1, len(lines) + 1) if n not in marked)
    directive = f"<!-- txtool: disable-next-line {code} -->\n"
    silenced = list(lines)
    for line in sorted([*marked, spare], reverse=True):  # bottom up: line numbers hold above
        silenced.insert(line - 1, directive)
    unused_at = spare + sum(1 for line in marked if line < spare)  # the spare's directive
    after = found("".join(silenced), filename, code)
    assert [c for _, c in after].count(code) == 0, after
    assert [line for line, c in after if c == "TX003"] == [unused_at]
