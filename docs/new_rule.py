"""Start a new lint rule: ``python docs/new_rule.py TX123 kebab-name [--severity warning]``.

Writes ``txtool/rules/tx123_kebab_name.py`` with its documentation in the layout every rule's
has (see docs/contributing.md) and a ``check`` that finds nothing yet, and registers it in
``RULE_MODULES`` (``txtool/rules/__init__.py``) in code order. Run from the repository's root.
Then write the check, the examples and the sections, a test in ``tests/rules/``, and
``python docs/generate_rules.py``.
"""

from __future__ import annotations

import argparse
import re
import sys
from pathlib import Path

RULES = Path("txtool") / "rules"
TEMPLATE = '''"""{summary}

What it does: what the rule reports, and where (the element, the attribute).

Why it matters: what the loader does with such a file: refuses it, reads something other than
what is written (an error), loads something risky (a warning), or reads nothing of it (info).

Loader: which program reads it, with its source: ros-controls/ros2_control
hardware_interface/src/component_parser.cpp ``parse_transmission_from_xml`` (the repository,
the file, and the line or function, at a commit).

Failing example::

    <robot name="r">
      <transmission name="t"/>
    </robot>

Expected finding: ``2:3 {severity} {code} the message txtool prints``

Passing example::

    <robot name="r"/>

Fix: what to write instead.
"""

from __future__ import annotations

from collections.abc import Iterator

from txtool.lint.context import LintContext
from txtool.lint.problem import Problem
from txtool.lint.rule_helpers import per_transmission

CODE = "{code}"
NAME = "{name}"
SEVERITY = "{severity}"
FIXABLE = False


@per_transmission
def check(ctx: LintContext) -> Iterator[Problem]:
    yield from ()
'''


def fail(message: str) -> None:
    sys.stderr.write(f"new_rule.py: {message}\n")
    raise SystemExit(2)


def register(init: Path, module: str) -> None:
    """Add ``module`` to RULE_MODULES before the first module of a higher code."""
    text = init.read_text(encoding="utf-8")
    start = text.index("RULE_MODULES")
    end = text.index("\n)", start)
    later = [m for m in re.finditer(r'^    "(tx\d{3})_\w+",$', text[start:end], re.M)
             if m.group(1) > module[:5]]
    at = start + later[0].start() if later else end + 1
    text = text[:at] + f'    "{module}",\n' + text[at:]
    init.write_text(text, encoding="utf-8")


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(prog="new_rule.py", description=__doc__.split("\n")[0])
    parser.add_argument("code", help="TX followed by three digits")
    parser.add_argument("name", help="kebab-case name, e.g. zero-reduction")
    parser.add_argument("--severity", choices=("error", "warning", "info"), default="warning")
    args = parser.parse_args(argv)
    code, name = args.code.upper(), args.name
    if not re.fullmatch(r"TX\d{3}", code):
        fail(f"{args.code!r}: a code is TX and three digits")
    if not re.fullmatch(r"[a-z][a-z0-9]*(?:-[a-z0-9]+)*", name):
        fail(f"{name!r}: a name is kebab-case (lowercase words joined by '-')")
    module = f"{code.lower()}_{name.replace('-', '_')}"
    path = RULES / f"{module}.py"
    init = RULES / "__init__.py"
    if not init.is_file():
        fail(f"{init}: not found (run from the repository's root)")
    if path.exists():
        fail(f"{path}: exists already")
    if re.search(rf'"{code.lower()}_\w+"', init.read_text(encoding="utf-8")):
        fail(f"{code}: registered already")
    summary = f"One line: what {code} {name} finds, and what the loader does with it."
    path.write_text(TEMPLATE.format(summary=summary, code=code, name=name,
                                    severity=args.severity), encoding="utf-8")
    register(init, module)
    print(f"wrote {path.as_posix()} (registered)")


if __name__ == "__main__":
    main()
