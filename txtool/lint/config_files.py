"""Which configuration file applies to a file, and whether xacro is off: without reading one.

Every command asks this before it reads its input (``--no-xacro``, ``TXTOOL_NO_XACRO``, the
``no-xacro`` of the file's configuration); :mod:`txtool.lint.config` and its dataclasses load
only when a configuration file is found.
"""

from __future__ import annotations

import os
from functools import lru_cache
from pathlib import Path

from txtool.io.xmlio import InputError

CONFIG_FILE = ".txtool.toml"
PYPROJECT = "pyproject.toml"
NO_XACRO_ENV = "TXTOOL_NO_XACRO"
_ENV_TRUE = ("1", "true", "yes", "on")
_ENV_FALSE = ("0", "false", "no", "off")  # set but empty is not "off": see below


class ConfigError(InputError):
    """A bad configuration or rule selection: one line naming the file and key; exit 2."""


@lru_cache(maxsize=256)
def find_config(folder: Path) -> Path | None:
    """The configuration file that applies to files in ``folder`` (searching upward)."""
    for candidate in (folder, *folder.parents):
        own = candidate / CONFIG_FILE
        if own.is_file():
            return own
        pyproject = candidate / PYPROJECT
        if pyproject.is_file() and _has_txtool_table(pyproject):
            return pyproject
    return None


def no_xacro_from_environment() -> bool:
    """``TXTOOL_NO_XACRO``: a CI runner's way to forbid xacro whatever the repository says.

    A value that is neither true nor false is an error rather than a guess: this is a
    safety switch, and a typo must not leave xacro on. So is an empty value (``TXTOOL_NO_XACRO=``,
    or ``${{ vars.NO_XACRO }}`` naming an unset variable): unset means on, set means decide.
    """
    raw = os.environ.get(NO_XACRO_ENV)
    if raw is None:
        return False
    value = raw.strip().lower()
    if value in _ENV_TRUE:
        return True
    if value in _ENV_FALSE:
        return False
    raise ConfigError(f"{NO_XACRO_ENV}: expected 1 or 0 (or true/false, "
                      f"yes/no, on/off), got {raw!r}")


def no_xacro_configured(path: str) -> bool:
    """``no-xacro`` of the configuration that applies to the file ``path`` (found upward).

    Only ``true`` counts: a configuration can turn xacro off, never back on.
    """
    if path == "-":
        return False
    config_path = find_config(Path(path).resolve().parent)
    if config_path is None:
        return False
    from txtool.lint.config import load_config

    return load_config(config_path).no_xacro


def _has_txtool_table(pyproject: Path) -> bool:
    try:
        text = pyproject.read_text(encoding="utf-8", errors="replace")
    except OSError:
        return False
    return "[tool.txtool" in text
