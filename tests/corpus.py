"""Access to the shared corpus of real robot descriptions (read in place, never copied).

Tests that need it skip when ``../shared/corpus`` is absent (a user's clone); under
``TXTOOL_REQUIRE_CORPUS=1`` (set by ``.ci/run``) a missing corpus fails instead.
"""

from __future__ import annotations

import os
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
CORPUS = ROOT.parent / "shared" / "corpus"
WORKSPACE = ROOT.parent / "shared" / "workspace"


def corpus_dir() -> Path:
    if CORPUS.is_dir() and (CORPUS / "MANIFEST.tsv").is_file():
        return CORPUS
    reason = f"corpus not found at {CORPUS} (expected ../shared/corpus beside the repository)"
    if os.environ.get("TXTOOL_REQUIRE_CORPUS") == "1":
        pytest.fail(reason + " and TXTOOL_REQUIRE_CORPUS=1")
    pytest.skip(reason)


def corpus_names() -> list[str]:
    """File names for parametrising (an empty list when the corpus is absent)."""
    if not CORPUS.is_dir():
        return ["<corpus missing>"]
    return sorted(p.name for p in CORPUS.iterdir() if p.name != "MANIFEST.tsv")


def corpus_file(name: str) -> Path:
    path = corpus_dir() / name
    if not path.is_file():
        pytest.fail(f"{name} is not in the corpus")
    return path


def corpus_files() -> list[Path]:
    return [corpus_dir() / name for name in corpus_names()]


def workspace_dir() -> Path:
    """The shared ROS package tree (``src/rrbot_description``), read in place."""
    if (WORKSPACE / "src").is_dir():
        return WORKSPACE
    reason = f"workspace not found at {WORKSPACE} (expected ../shared/workspace)"
    if os.environ.get("TXTOOL_REQUIRE_CORPUS") == "1":
        pytest.fail(reason + " and TXTOOL_REQUIRE_CORPUS=1")
    pytest.skip(reason)
