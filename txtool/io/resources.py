"""Files that ship with txtool: the demo robots (``fixtures/``) and the JSON Schemas
(``schemas/``).

In a source checkout they are the top-level folders beside the package; an installed wheel
carries them inside the package as ``txtool/_data/fixtures`` and ``txtool/_data/schemas`` (see
``[tool.hatch.build.targets.wheel.force-include]`` in pyproject.toml).
"""

from __future__ import annotations

from pathlib import Path

from txtool.io.xmlio import InputError

REPOSITORY = "https://github.com/txtool/txtool"
_PACKAGE = Path(__file__).resolve().parents[1]
_PLACES = (_PACKAGE / "_data", _PACKAGE.parent)  # installed wheel, then source checkout


def shipped(folder: str, name: str) -> Path:
    """The shipped file ``folder/name``; :class:`InputError` if this install lacks it."""
    for place in _PLACES:
        candidate = place / folder / name
        if candidate.is_file():
            return candidate
    raise InputError(f"{folder}/{name}: not found in this txtool installation (reinstall it)")


def shipped_files(folder: str) -> dict[str, Path]:
    """Every shipped file below ``folder`` by its path relative to it (``examples/robot.urdf``);
    :class:`InputError` if this install lacks the folder."""
    for place in _PLACES:
        root = place / folder
        if root.is_dir():
            return {p.relative_to(root).as_posix(): p for p in sorted(root.rglob("*"))
                    if p.is_file() and "__pycache__" not in p.parts}
    raise InputError(f"{folder}: not found in this txtool installation (reinstall it)")


def example_layout() -> dict[str, Path]:
    """The files the documentation's examples run on, by where they go in a fresh folder: the
    demo robots as ``fixtures/NAME`` and the examples of ``fixtures/examples`` at the top
    (once: a walk of the folder finds each file once)."""
    layout: dict[str, Path] = {}
    for relative, path in shipped_files("fixtures").items():
        if relative.startswith("examples/"):
            layout[relative.removeprefix("examples/")] = path
        else:
            layout[f"fixtures/{relative}"] = path
    return layout


def install_extra(extra: str) -> str:
    """How to add an extra, as txtool is installed today: from its repository (there is no
    release on a package index yet) or, in a clone, in place."""
    return (f"pip install 'txtool[{extra}] @ git+{REPOSITORY}' "
            f"(in a clone: pip install -e '.[{extra}]')")


class MissingExtra(ModuleNotFoundError):
    """An optional dependency is not installed; the message is one line naming the extra that
    brings it (``str(error)``), as the command line prints it."""

    def __str__(self) -> str:
        return str(self.msg)
