"""One page per lint rule, generated from the rule modules' docstrings, and the catalogue
``docs/rules/index.md`` that links them, as ruff's documentation is made.

Run ``python docs/generate_rules.py`` after changing a rule; a test holds the pages current.
"""

from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))


def rule_pages() -> dict[str, str]:
    """``rules/TXnnn.md`` -> Markdown, and the catalogue ``rules/index.md``."""
    from txtool.lint.ruledoc import markdown
    from txtool.rules import all_rules

    pages: dict[str, str] = {}
    intro = ("Every rule has a stable code and a kebab-case name; `txtool rules CODE` prints the "
             "same text in a terminal. The severity is the default (configurable per rule); "
             "*fix* marks the rules `txtool validate --fix` and `txtool migrate` fix "
             "(`[*]` in validate's text output).")
    rows = ["# Rules", "", intro, "",
            "| code | name | severity | fix | what |", "|---|---|---|---|---|"]
    for rule in all_rules().values():
        fix = "fix" if rule.fixable else ""
        rows.append(f"| [{rule.code}]({rule.code}.md) | `{rule.name}` | {rule.severity} | {fix} "
                    f"| {rule.summary} |")
        header = (f"*Default severity: {rule.severity}"
                  + ("; fixed by `txtool validate --fix` and `txtool migrate`" if rule.fixable
                     else "") + ".*\n\n")
        body = markdown(rule, heading="#")
        title, _, rest = body.partition("\n\n")
        pages[f"rules/{rule.code}.md"] = f"{title}\n\n{header}{rest}\n"
    pages["rules/index.md"] = "\n".join(rows) + "\n"
    return pages


def write(folder: Path) -> None:
    """Write the pages into ``folder`` (``docs/``), removing pages of rules that are gone."""
    pages = rule_pages()
    rules = folder / "rules"
    rules.mkdir(exist_ok=True)
    for old in rules.glob("TX*.md"):
        if f"rules/{old.name}" not in pages:
            old.unlink()
    for path, content in pages.items():
        (folder / path).write_text(content, encoding="utf-8")


if __name__ == "__main__":
    write(Path(__file__).resolve().parent)
