"""Lint configuration: ``[tool.txtool]`` in ``pyproject.toml`` or a ``.txtool.toml``.

The configuration is found from the run's root, not beside the files (see
:func:`~txtool.lint.config_files.applicable_config`; in each folder ``.txtool.toml`` wins over
``pyproject.toml``; a ``pyproject.toml`` without ``[tool.txtool]`` is passed over).
``--config PATH`` replaces the search. Relative package
folders are relative to the configuration file. Any mistake is a :class:`ConfigError` naming
the file and the key (exit 2).
"""

from __future__ import annotations

import dataclasses
import os
import sys
from collections.abc import Iterable
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any, NamedTuple

from txtool.io.xmlio import Source, XacroOptions
from txtool.lint.config_files import (  # noqa: F401 - this module's names before the split
    CONFIG_FILE,
    NO_XACRO_ENV,
    PYPROJECT,
    ConfigError,
    _has_txtool_table,
    applicable_config,
    find_config,
    no_xacro_from_environment,
    read_config_text,
    repository_root,
)
from txtool.lint.patterns import Excludes, absolute_folder
from txtool.lint.problem import Severity
from txtool.model.distro import parse_distro
from txtool.model.readers import Assumption, Stated, parse_readers

if TYPE_CHECKING:
    from txtool.lint.config_model import Config


SIMULATE_TABLE = "simulate"





def __getattr__(name: str) -> Any:
    # The pydantic model is only built when a configuration file is read (start-up time).
    if name == "Config":
        from txtool.lint.config_model import Config

        return Config
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


@dataclass(frozen=True)
class Values:
    """What :func:`resolve` reads: a :class:`Config`'s fields as plain values.

    Used so that a run without any configuration file never builds the pydantic model.
    """

    select: list[str] | tuple[str, ...] | None = None
    ignore: list[str] | tuple[str, ...] = ()
    severity: dict[str, Severity] = field(default_factory=dict)
    rules: dict[str, dict[str, Any]] = field(default_factory=dict)
    xacro_args: dict[str, str] = field(default_factory=dict)
    pkg_dirs: list[str] | tuple[str, ...] = ()
    pkg_paths: dict[str, str] = field(default_factory=dict)
    no_xacro: bool = False
    exclude: list[str] | tuple[str, ...] = ()
    extend_exclude: list[str] | tuple[str, ...] = ()
    respect_gitignore: bool = True
    per_file_ignores: dict[str, list[str]] = field(default_factory=dict)
    per_file_xacro_args: dict[str, dict[str, str]] = field(default_factory=dict)
    readers: list[str] | tuple[str, ...] | None = None
    ros_distro: str | None = None
    ros_distro_cli: bool = False  # ros_distro came from --ros-distro

    @classmethod
    def of(cls, config: Config | None) -> Values:
        if config is None:
            return cls()
        return cls(**{name: getattr(config, name) for name in cls.__dataclass_fields__
                      if name != "ros_distro_cli"})


@dataclass(frozen=True)
class Settings:
    """A configuration resolved against the rule registry: what the pipeline runs."""

    enabled: frozenset[str]
    severity: dict[str, Severity]
    options: dict[str, Any]
    xacro: XacroOptions
    no_xacro: bool
    origin: str = "<defaults>"
    excludes: Excludes = field(default_factory=lambda: Excludes(".", ()))
    respect_gitignore: bool = True
    # (pattern, codes no longer run, xacro arguments added) for files matching the pattern
    per_file: tuple[tuple[str, frozenset[str], tuple[tuple[str, str], ...]], ...] = ()
    # What the user said about the files' readers (see txtool.model.readers)
    stated: Stated = field(default_factory=Stated)

    def for_path(self, path: str) -> Settings:
        """These settings with the per-file entries whose pattern matches ``path`` applied."""
        if not self.per_file or path == "-":
            return self
        disabled: set[str] = set()
        args = dict(self.xacro.args)
        for pattern, codes, extra in self.per_file:
            if Excludes(self.excludes.base, (pattern,)).matches(path, False):
                disabled |= codes
                args.update(extra)
        if not disabled and args == dict(self.xacro.args):
            return self
        xacro = self.xacro._replace(args=tuple(args.items()))
        return dataclasses.replace(self, enabled=self.enabled - disabled, xacro=xacro)


def no_xacro_configured(path: str, explicit: str | None = None) -> bool:
    """``no-xacro`` of the configuration that applies to the file ``path`` (see
    :func:`~txtool.lint.config_files.applicable_config`), or of ``explicit`` (``--config``).

    Only ``true`` counts: a configuration can turn xacro off, never back on.
    """
    if explicit is not None:
        config_path: Path | None = Path(explicit)
    elif path == "-":
        config_path = applicable_config(os.getcwd()).path
    else:
        config_path = applicable_config(os.path.dirname(os.path.abspath(path))).path
    if config_path is None:
        return False
    return load_config(config_path).no_xacro


def load_config(path: Path) -> Config:
    """Read ``path`` (a ``.txtool.toml`` or a ``pyproject.toml``) into a :class:`Config`."""
    if sys.version_info >= (3, 11):
        import tomllib
    else:  # pragma: no cover - exercised on Python 3.10 only
        import tomli as tomllib

    text = read_config_text(path)  # a regular file of bounded size, else one line
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise ConfigError(f"{path}: invalid TOML: {exc}") from None
    except RecursionError:  # tomllib recurses once per level of nested arrays and tables
        raise ConfigError(f"{path}: configuration nested too deep") from None
    table: Any = data
    prefix = ""
    if path.name == PYPROJECT:
        table = data.get("tool", {}).get("txtool", {})
        prefix = "tool.txtool."
        if isinstance(table, dict):
            # [tool.txtool.simulate] belongs to `txtool simulate`, which checks it itself.
            table = {key: value for key, value in table.items() if key != SIMULATE_TABLE}
    if not isinstance(table, dict):
        raise ConfigError(f"{path}: key '{prefix.rstrip('.')}': expected a table")
    if path.name != PYPROJECT and isinstance(table.get("tool"), dict) and "txtool" in table["tool"]:
        raise ConfigError(
            f"{path}: key 'tool.txtool': this file takes txtool's keys at its top level, as "
            f"{CONFIG_FILE} does; [tool.txtool] is read only from a file named {PYPROJECT}"
        )
    if "xacro-env" in table:
        raise ConfigError(
            f"{path}: key '{prefix}xacro-env': the environment variables $(env) may read are "
            "named on the command line (--xacro-env NAME), never in a file of the repository"
        )
    from pydantic import ValidationError

    from txtool.lint.config_model import Config

    try:
        return Config.model_validate(table)
    except ValidationError as exc:
        error = exc.errors()[0]
        key = prefix + ".".join(str(part) for part in error["loc"])
        reason = (unknown_key(Config, error["loc"]) if error["type"] == "extra_forbidden"
                  else error["msg"])
        raise ConfigError(f"{path}: key '{key}': {reason}") from None


def resolve(
    config: Config | Values | None = None,
    *,
    origin: str = "<defaults>",
    base: Path | None = None,
    prefix: str = "",
) -> Settings:
    """Check ``config`` against the registry and resolve it to :class:`Settings`.

    ``prefix`` is put before key names in errors (``tool.txtool.`` for a pyproject.toml).
    """
    from txtool.rules import all_rules

    if not isinstance(config, Values):
        config = Values.of(config)
    rules = all_rules()
    selected = set(rules)
    if config.select is not None:
        selected = _expand(config.select, rules, origin, f"{prefix}select")
    ignored = _expand(config.ignore, rules, origin, f"{prefix}ignore")
    for code in config.severity:
        _exact(code, rules, origin, f"{prefix}severity.{code}")
    options: dict[str, Any] = {}
    for code, values in config.rules.items():
        options[_exact(code, rules, origin, f"{prefix}rules.{code}")] = _options(
            rules[code.upper()], values, origin, f"{prefix}rules.{code.upper()}"
        )
    folder = (base or Path(".")).absolute()  # relative folders are the config file's
    per_file = tuple(
        (
            pattern,
            frozenset(_expand(codes, rules, origin, f"{prefix}per-file-ignores.{pattern}")),
            tuple(config.per_file_xacro_args.get(pattern, {}).items()),
        )
        for pattern, codes in config.per_file_ignores.items()
    ) + tuple(
        (pattern, frozenset(), tuple(args.items()))
        for pattern, args in config.per_file_xacro_args.items()
        if pattern not in config.per_file_ignores
    )
    return Settings(
        enabled=frozenset(selected - ignored),
        severity={code.upper(): level for code, level in config.severity.items()},
        options=options,
        xacro=XacroOptions(
            args=tuple(config.xacro_args.items()),
            pkg_dirs=tuple(str(folder / d) for d in config.pkg_dirs),
            pkg_paths=tuple((name, str(folder / d)) for name, d in config.pkg_paths.items()),
        ),
        no_xacro=config.no_xacro,
        origin=origin,
        excludes=Excludes(str(folder), (*config.exclude, *config.extend_exclude)),
        respect_gitignore=config.respect_gitignore,
        per_file=per_file,
        stated=_stated(config, origin, prefix),
    )


def _stated(config: Values, origin: str, prefix: str) -> Stated:
    """``readers`` and ``ros-distro`` checked against the readers model."""
    try:
        readers = parse_readers(config.readers or ())
    except ValueError as exc:
        raise ConfigError(f"{origin}: key '{prefix}readers': {exc}") from None
    distro = None
    if config.ros_distro is not None:
        cli = origin == "command line" or config.ros_distro_cli
        try:
            distro = parse_distro(config.ros_distro)
        except ValueError as exc:
            where = "option '--ros-distro'" if cli else f"key '{prefix}ros-distro'"
            raise ConfigError(f"{origin}: {where}: {exc}") from None
    if config.readers is not None and not readers:
        raise ConfigError(f"{origin}: key '{prefix}readers': name at least one reader")
    where = "configuration" if origin in ("command line", "<defaults>") else origin
    said = None
    if distro is not None:
        said = (f"--ros-distro {distro.value}" if config.ros_distro_cli
                else f"ros-distro {distro.value} in {where}")
    return Stated(readers, distro, origin=where, distro_said=said)


def _expand(selectors: Iterable[str], rules: dict[str, Any], origin: str, key: str) -> set[str]:
    """Codes matched by ``selectors`` (exact codes, prefixes such as ``TX1``, or ``ALL``)."""
    chosen: set[str] = set()
    for selector in selectors:
        wanted = selector.strip().upper()
        matched = {code for code in rules if wanted == "ALL" or code.startswith(wanted)}
        if not wanted or not matched:
            raise ConfigError(f"{origin}: key '{key}': unknown rule code '{selector}'")
        chosen |= matched
    return chosen


def _exact(code: str, rules: dict[str, Any], origin: str, key: str) -> str:
    if code.upper() not in rules:
        raise ConfigError(f"{origin}: key '{key}': unknown rule code '{code}'")
    return code.upper()


def _options(rule: Any, values: dict[str, Any], origin: str, where: str) -> Any:
    from pydantic import ValidationError

    model = rule.options
    if model is None:
        raise ConfigError(f"{origin}: key '{where}': {rule.code} takes no options")
    try:
        return model.model_validate(values)
    except ValidationError as exc:
        error = exc.errors()[0]
        key = f"{where}." + ".".join(str(part) for part in error["loc"])
        reason = (unknown_key(model, error["loc"]) if error["type"] == "extra_forbidden"
                  else error["msg"])
        raise ConfigError(f"{origin}: key '{key}': {reason}") from None


def unknown_key(model: Any, loc: tuple[Any, ...]) -> str:
    """``unknown key``, and the known key of that table it is likely a typo of (``selct``:
    did you mean 'select'?), found among the fields of the pydantic ``model`` at ``loc``."""
    import difflib

    for part in loc[:-1]:
        field = next((f for name, f in getattr(model, "model_fields", {}).items()
                      if part in (name, f.alias)), None)
        model = getattr(field, "annotation", None)
    fields = getattr(model, "model_fields", None)
    if not isinstance(fields, dict):
        return "unknown key"
    known = [field.alias or name for name, field in fields.items()]
    close = difflib.get_close_matches(str(loc[-1]), known, n=1, cutoff=0.6)
    return "unknown key" + (f"; did you mean '{close[0]}'?" if close else "")


class Overrides(NamedTuple):
    """Command-line options that override or extend the configuration."""

    select: tuple[str, ...] | None = None
    ignore: tuple[str, ...] = ()
    xacro: XacroOptions = XacroOptions()
    no_xacro: bool = False
    exclude: tuple[str, ...] | None = None  # --exclude replaces the configuration's exclude
    extend_exclude: tuple[str, ...] = ()
    respect_gitignore: bool | None = None
    ros_distro: str | None = None  # --ros-distro, over the configuration's ros-distro


def merged(config: Config | None, overrides: Overrides) -> Values:
    """``config`` with the command line applied: select replaces, the rest extends."""
    values = Values.of(config)
    return dataclasses.replace(
        values,
        select=values.select if overrides.select is None else list(overrides.select),
        ignore=[*values.ignore, *overrides.ignore],
        xacro_args={**values.xacro_args, **dict(overrides.xacro.args)},
        no_xacro=values.no_xacro or overrides.no_xacro or no_xacro_from_environment(),
        exclude=values.exclude if overrides.exclude is None else (),
        respect_gitignore=(
            values.respect_gitignore
            if overrides.respect_gitignore is None
            else overrides.respect_gitignore
        ),
        ros_distro=overrides.ros_distro or values.ros_distro,
        ros_distro_cli=overrides.ros_distro is not None,
    )


def check_overrides(overrides: Overrides) -> None:
    """Reject unknown codes given on the command line before any file is read."""
    if not (overrides.select or overrides.ignore):
        return  # nothing to look up: the rules need not be loaded (convert, roundtrip, show)
    from txtool.rules import all_rules

    rules = all_rules()
    for option, selectors in (("--select", overrides.select or ()), ("--ignore", overrides.ignore)):
        for selector in selectors:
            wanted = selector.strip().upper()
            if not wanted or not any(wanted == "ALL" or c.startswith(wanted) for c in rules):
                raise ConfigError(f"option '{option}': unknown rule code '{selector}'")


class SettingsCache:
    """Settings per configuration file, found once per folder."""

    def __init__(self, overrides: Overrides, explicit: str | None = None,
                 root: str | None = None) -> None:
        self.overrides = overrides
        self.explicit = Path(explicit) if explicit else None
        self._by_file: dict[Path | None, Settings] = {}
        self._by_folder: dict[str, Path | None] = {}
        # The run's root (see applicable_config): the repository of the working folder, or
        # ``root`` given (an editor's workspace, whatever folder the editor started in).
        self._root = root or repository_root()
        self.notes: list[str] = []  # nested configuration files passed over, one line each
        self._noted: set[Path] = set()
        self._by_path: dict[str, Settings] = {}  # a folder walk asks first, then the linter
        self._absolute: dict[str, str] = {}  # folders made absolute (see absolute_folder)
        self._cli_excludes = Excludes(
            os.getcwd(), (*(overrides.exclude or ()), *overrides.extend_exclude)
        )
        check_overrides(overrides)
        no_xacro_from_environment()  # a bad value stops the run before any file is read

    def for_file(self, path: str, is_link: bool | None = None) -> Settings:
        """The settings for ``path``; ``is_link`` says whether it is a symbolic link when a
        folder walk already knows (None: asked here)."""
        known = self._by_path.get(path)
        if known is None:
            known = self._by_path[path] = self._for_file(path, is_link)
        return known

    def config_for(self, path: str, is_link: bool | None = None) -> Path | None:
        """The configuration file that applies to ``path`` (None: the defaults)."""
        if self.explicit is not None:
            return self.explicit
        if path == "-":
            return self._applicable(os.getcwd())
        if os.path.islink(path) if is_link is None else is_link:
            # where the file really is (realpath: a link loop is reported when the file is read)
            return self._applicable(os.path.dirname(os.path.realpath(path)))
        return self._config_of_folder(absolute_folder(path, self._absolute))

    def _for_file(self, path: str, is_link: bool | None) -> Settings:
        config_path = self.config_for(path, is_link)
        if config_path not in self._by_file:
            self._by_file[config_path] = self._settings(config_path)
        return self._by_file[config_path].for_path(path)

    def excluded(self, path: str, is_folder: bool, is_link: bool | None = None) -> bool:
        """Whether a folder walk passes over ``path``: the command line's ``--exclude`` and
        ``--extend-exclude`` (relative to the current folder), then its configuration's."""
        if self._cli_excludes.matches(path, is_folder):
            return True
        return self.for_file(path, is_link).excludes.matches(path, is_folder)

    def respects_gitignore(self, folder: str) -> bool:
        return self.for_file(os.path.join(folder, "-.urdf")).respect_gitignore

    def _config_of_folder(self, folder: str) -> Path | None:
        if folder not in self._by_folder:
            self._by_folder[folder] = self._applicable(folder)
        return self._by_folder[folder]

    def _applicable(self, folder: str) -> Path | None:
        found = applicable_config(folder, self._root)
        if found.ignored is not None and found.ignored not in self._noted:
            self._noted.add(found.ignored)
            used = f"{found.path} applies" if found.path else "the defaults apply"
            self.notes.append(
                f"{found.ignored}: not read: a configuration below the repository's root is "
                f"passed over ({used}; --config names the file to use)"
            )
        return found.path

    def _settings(self, config_path: Path | None) -> Settings:
        prefix = ""
        config: Config | None = None
        if config_path is None:
            origin, base = "command line", Path.cwd()
        else:
            if not os.path.lexists(config_path):
                raise ConfigError(f"{config_path}: no such configuration file")
            config, origin, base = load_config(config_path), str(config_path), config_path.parent
            prefix = "tool.txtool." if config_path.name == PYPROJECT else ""
        settings = resolve(merged(config, self.overrides), origin=origin, base=base, prefix=prefix)
        extra = self.overrides.xacro
        xacro = XacroOptions(  # the command line first: the first match wins
            args=settings.xacro.args,
            pkg_dirs=extra.pkg_dirs + settings.xacro.pkg_dirs,
            pkg_paths=extra.pkg_paths + settings.xacro.pkg_paths,
            # the command line only, never a file: what may leave the machine, what is trusted
            trust=extra.trust, env=extra.env, readable=extra.readable,
        )
        return dataclasses.replace(settings, xacro=xacro)


def readers_of(source: Source, ros_distro: str | None = None,
               config: str | None = None) -> Assumption:
    """The readers of ``source`` as ``validate`` decides them: the ``readers`` and ``ros-distro``
    of the configuration that applies to it (``config``, ``--config``, when given),
    ``ros_distro`` (``--ros-distro``) over them."""
    from txtool.lint.readers import assumption_of

    where = source.path if source.path not in ("", "-") else "-"
    stated = SettingsCache(Overrides(ros_distro=ros_distro), config).for_file(where).stated
    return assumption_of(source, stated)
