"""mkdocs hook: one page per lint rule, generated from the rule modules' docstrings (the rule
catalogue in ``rules/index.md`` links them), as ruff's documentation is made."""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))


def rule_pages() -> dict[str, str]:
    """``rules/TXnnn.md`` -> Markdown, and the catalogue ``rules/index.md``."""
    from txtool.lint.ruledoc import markdown
    from txtool.rules import all_rules

    pages: dict[str, str] = {}
    intro = ("Every rule has a stable code and a kebab-case name; `txtool rules CODE` prints the "
             "same text in a terminal. The severity is the default (configurable per rule); "
             "*fix* marks the rules `txtool migrate` fixes.")
    rows = ["# Rules", "", intro, "",
            "| code | name | severity | fix | what |", "|---|---|---|---|---|"]
    for rule in all_rules().values():
        fix = "fix" if rule.fixable else ""
        rows.append(f"| [{rule.code}]({rule.code}.md) | `{rule.name}` | {rule.severity} | {fix} "
                    f"| {rule.summary} |")
        header = (f"*Default severity: {rule.severity}"
                  + ("; fixed by `txtool migrate`" if rule.fixable else "") + ".*\n\n")
        body = markdown(rule, heading="#")
        title, _, rest = body.partition("\n\n")
        pages[f"rules/{rule.code}.md"] = f"{title}\n\n{header}{rest}\n"
    pages["rules/index.md"] = "\n".join(rows) + "\n"
    return pages


def on_files(files: Any, config: Any) -> Any:
    from mkdocs.structure.files import File

    for path, content in rule_pages().items():
        existing = files.get_file_from_path(path)
        if existing is not None:
            files.remove(existing)
        files.append(File.generated(config, path, content=content))
    return files
