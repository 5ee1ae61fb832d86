"""Which files give the simulation parameters, each read by its kind.

``--params FILE...`` in order (controller YAML by its suffix, :mod:`txtool.simulation.yaml_gains`;
TOML otherwise, :mod:`txtool.simulation.params`), else ``[tool.txtool.simulate]`` in the nearest
pyproject.toml.
"""

from __future__ import annotations

from pathlib import Path

from txtool.simulation.params import (
    YAML_SUFFIXES,
    Params,
    find_pyproject,
    merge,
    parse_params,
    parse_toml,
    read_text,
)
from txtool.simulation.yaml_gains import parse_yaml


def load_params(explicit: str | tuple[str, ...] | None, robot_path: str) -> Params:
    """``--params FILE...`` if given, else the nearest pyproject.toml with the section."""
    if isinstance(explicit, str):
        explicit = (explicit,)
    if explicit:
        return merge([load_file(path) for path in explicit])
    found = find_pyproject(robot_path)
    if found is None:
        return Params()
    path, data, text = found
    return parse_params(data, path, text, prefix="tool.txtool.simulate.")


def load_file(given: str) -> Params:
    """One ``--params`` file: controller YAML by its suffix (``FILE.yaml#NAME``: only controller
    NAME), else TOML."""
    path, only = given, None
    base, mark, name = given.rpartition("#")
    if mark and base.lower().endswith(YAML_SUFFIXES) and not Path(given).exists():
        path, only = base, name
    text = read_text(path)
    if path.lower().endswith(YAML_SUFFIXES):
        return parse_yaml(text, path, only)
    return parse_params(parse_toml(text, path), path, text)
