"""gitignore-style path patterns, for exclusions and per-file settings.

pathspec (loaded lazily) says what a pattern means; :mod:`txtool.lint.wildmatch` matches it
without backtracking, so that no pattern a pull request writes can stall a walk.
"""

from __future__ import annotations

import os
from typing import NamedTuple

from txtool.lint.wildmatch import GitIgnore


class Excludes(NamedTuple):
    """gitignore-style patterns relative to ``base``: a pattern without ``/`` matches a name
    at any depth, one with ``/`` is anchored at ``base``, ``dir/`` matches folders only."""

    base: str
    patterns: tuple[str, ...]

    def matches(self, path: str, is_folder: bool) -> bool:
        if not self.patterns:
            return False
        relative = os.path.relpath(os.path.abspath(path), self.base)
        if relative.startswith(".."):
            return False
        return _spec(self.patterns).match_file(relative + ("/" if is_folder else ""))


def _spec(patterns: tuple[str, ...]) -> GitIgnore:
    spec = _SPECS.get(patterns)
    if spec is None:
        spec = _SPECS[patterns] = GitIgnore(patterns)
    return spec


_SPECS: dict[tuple[str, ...], GitIgnore] = {}


def absolute_folder(path: str, known: dict[str, str]) -> str:
    """``os.path.dirname(os.path.abspath(path))``, each folder normalised once (``known`` keeps
    them, for one walk: the working folder does not change during it). The same answer where
    the last part of ``path`` is a name (not ``.``, ``..`` or empty)."""
    head, name = os.path.split(path)
    if name in ("", ".", ".."):
        return os.path.dirname(os.path.abspath(path))
    folder = known.get(head)
    if folder is None:
        folder = known[head] = os.path.abspath(head)
    return folder
