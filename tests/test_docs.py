"""The documentation: rule pages generated from the rules, and the site building cleanly."""

from __future__ import annotations

import importlib.util
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"


def generator():
    spec = importlib.util.spec_from_file_location("generate_rules", DOCS / "generate_rules.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_rule_pages_are_current():
    pages = generator().rule_pages()
    on_disk = {f"rules/{p.name}": p.read_text() for p in (DOCS / "rules").glob("*.md")}
    assert on_disk == pages, "run: python docs/generate_rules.py"


def test_every_rule_has_a_page_and_a_catalogue_row():
    from txtool.rules import all_rules

    pages = generator().rule_pages()
    for code, rule in all_rules().items():
        page = pages[f"rules/{code}.md"]
        assert page.startswith(f"# {code} {rule.name}\n")
        assert "```xml" in page and "``" not in page.replace("```", "")
        assert f"[{code}]({code}.md)" in pages["rules/index.md"]


def test_readme_is_a_newcomers_page():
    readme = (ROOT / "README.md").read_text()
    assert len(readme.splitlines()) <= 400
    for target in ("docs/commands.md", "docs/configuration.md", "docs/ci.md", "docs/simulate.md",
                   "docs/api.md"):
        assert f"]({target})" in readme and (ROOT / target).is_file()


@pytest.mark.skipif(shutil.which("mkdocs") is None and os.environ.get("CI") != "true",
                    reason="mkdocs (extra 'docs') is not installed")
def test_the_site_builds_strictly(tmp_path):
    done = subprocess.run(
        [sys.executable, "-m", "mkdocs", "build", "--strict", "--site-dir", str(tmp_path)],
        cwd=ROOT, capture_output=True, text=True, timeout=300,
        env={**os.environ, "NO_MKDOCS_2_WARNING": "1"},
    )
    assert done.returncode == 0, done.stderr[-3000:]
    assert (tmp_path / "rules" / "TX106" / "index.html").is_file()


def test_the_site_index_is_the_readme():
    """docs/index.md is README.md with its links made relative to docs/ (regenerate it with
    ``sed 's#](docs/#](#g' README.md > docs/index.md``)."""
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    assert (DOCS / "index.md").read_text(encoding="utf-8") == readme.replace("](docs/", "](")
