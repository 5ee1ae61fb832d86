"""Which configuration file applies to a file, and whether xacro is off: without reading one.

Every command asks this before it reads its input (``--no-xacro``, ``TXTOOL_NO_XACRO``, the
``no-xacro`` of the file's configuration, :func:`txtool.lint.config.no_xacro_configured`);
:mod:`txtool.lint.config_model` (pydantic) loads only when a configuration file is found.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any, NamedTuple

from txtool.io.xmlio import InputError

CONFIG_FILE = ".txtool.toml"
PYPROJECT = "pyproject.toml"
NO_XACRO_ENV = "TXTOOL_NO_XACRO"
_ENV_TRUE = ("1", "true", "yes", "on")
_ENV_FALSE = ("0", "false", "no", "off")  # set but empty is not "off": see below


class ConfigError(InputError):
    """A bad configuration or rule selection: one line naming the file and key; exit 2."""


# Configuration files are small; anything larger is refused before it is read.
MAX_CONFIG_BYTES = 1024 * 1024
_TOP_MARK = ".git"  # a folder, or a file in a worktree or submodule


class Applicable(NamedTuple):
    """The configuration file that applies to a folder's files, and a nested one passed over."""

    path: Path | None
    ignored: Path | None = None


def find_config(folder: Path | str) -> Path | None:
    """The nearest configuration file: in ``folder`` (absolute) or the first folder above it
    holding one.

    Remembered for every folder on the way, so that the folders of a deep tree cost one look
    each, not one per folder above them.
    """
    return _upward(str(folder), _own_config, _NEAREST)


def find_config_cache_clear() -> None:
    """Forget what was found (tests write configuration files between runs)."""
    _NEAREST.clear()
    _TOPS.clear()


find_config.cache_clear = find_config_cache_clear  # type: ignore[attr-defined]


def repository_root(working: str | None = None) -> str:
    """The root of a run: the top of the git work tree holding the working folder (the nearest
    folder upward holding ``.git``), else the working folder itself.

    A pull request cannot move it: git refuses to track a path named ``.git``.
    """
    folder = working or os.getcwd()
    return _upward(folder, _git_top, _TOPS) or folder


def applicable_config(folder: Path | str, root: str | None = None) -> Applicable:
    """The configuration of the files in ``folder`` (absolute), decided from the run's root.

    Inside the root: the configuration found from the root (in it, or the first folder above
    it holding one); one in a folder below the root is not read (it is ``ignored``, for a
    note): a pull request that drops a ``.txtool.toml`` beside its files must not decide how
    they are checked. Outside the root (a file named by a path leaving it, or a link's target
    elsewhere): the nearest configuration above the file, as that file is not the run's.
    """
    root = root or repository_root()
    folder = str(folder)
    if not _inside(folder, root):
        folder = os.path.realpath(folder)
        if not _inside(folder, root):
            return Applicable(find_config(folder))
    nearest = find_config(folder)
    applies = find_config(root)
    if nearest is not None and nearest != applies and _inside(str(nearest.parent), root):
        return Applicable(applies, nearest)
    return Applicable(applies)


def _inside(folder: str, root: str) -> bool:
    """Whether ``folder`` is ``root`` or below it (both absolute and normalised)."""
    return folder == root or folder.startswith(root if root.endswith(os.sep) else root + os.sep)


def _upward(folder: str, own, known: dict[str, Any]) -> Any:  # type: ignore[no-untyped-def]
    """The first ``own(f)`` not None for ``folder`` and its parents, remembered in ``known``
    (strings, not pathlib: a Path's parents cost the whole path each time)."""
    chain = []
    found = None
    candidate = folder
    while True:
        if candidate in known:
            found = known[candidate]
            break
        chain.append(candidate)
        parent = os.path.dirname(candidate)
        if parent == candidate:
            break
        candidate = parent
    for candidate in reversed(chain):  # from the top down: each folder inherits its parent's
        found = own(candidate) or found
        known[candidate] = found
    return found


def _own_config(folder: str) -> Path | None:
    """The configuration file in ``folder`` itself: ``.txtool.toml`` (whatever it is: a link to
    a device is refused when read, not passed over), else a ``pyproject.toml`` with
    ``[tool.txtool]``."""
    own = os.path.join(folder, CONFIG_FILE)
    if os.path.lexists(own):
        return Path(own)
    pyproject = os.path.join(folder, PYPROJECT)
    if os.path.lexists(pyproject) and _has_txtool_table(pyproject):
        return Path(pyproject)
    return None


def _git_top(folder: str) -> str | None:
    return folder if os.path.lexists(os.path.join(folder, _TOP_MARK)) else None


_NEAREST: dict[str, Any] = {}
_TOPS: dict[str, Any] = {}


def read_config_text(path: Path) -> str:
    """A configuration file's text: a regular file of at most :data:`MAX_CONFIG_BYTES`, UTF-8
    (a device, a FIFO or a huge file is refused before it is read, with one line)."""
    from txtool.io.xmlio import read_regular

    try:
        return read_regular(str(path), MAX_CONFIG_BYTES).decode("utf-8")
    except InputError as exc:
        raise ConfigError(str(exc)) from None
    except UnicodeDecodeError as exc:
        raise ConfigError(f"{path}: invalid TOML: not UTF-8 ({exc.reason})") from None


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


def _has_txtool_table(pyproject: Path | str) -> bool:
    """Whether a ``pyproject.toml`` has a ``[tool.txtool]`` table (by its text; a file that is
    no regular file, or too large, is refused with one line)."""
    from txtool.io.xmlio import read_regular

    try:
        text = read_regular(str(pyproject), MAX_CONFIG_BYTES).decode("utf-8", "replace")
    except InputError as exc:
        if os.path.exists(pyproject):
            raise ConfigError(str(exc)) from None
        return False  # a dangling link: no table
    return "[tool.txtool" in text
