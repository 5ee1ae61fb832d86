"""Files that ship with txtool: the demo robots (``fixtures/``) and the JSON Schemas
(``schemas/``).

In a source checkout they are the top-level folders beside the package; an installed wheel
carries them inside the package as ``txtool/_data/fixtures`` and ``txtool/_data/schemas`` (see
``[tool.hatch.build.targets.wheel.force-include]`` in pyproject.toml).
"""

from __future__ import annotations

from pathlib import Path

from txtool.io.xmlio import InputError

_PACKAGE = Path(__file__).resolve().parents[1]
_PLACES = (_PACKAGE / "_data", _PACKAGE.parent)  # installed wheel, then source checkout


def shipped(folder: str, name: str) -> Path:
    """The shipped file ``folder/name``; :class:`InputError` if this install lacks it."""
    for place in _PLACES:
        candidate = place / folder / name
        if candidate.is_file():
            return candidate
    raise InputError(f"{folder}/{name}: not found in this txtool installation (reinstall it)")
