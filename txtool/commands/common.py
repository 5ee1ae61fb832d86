"""Options and error handling shared by the commands (light: click only)."""

from __future__ import annotations

import contextlib
import functools
import os
import sys
from collections.abc import Callable, Iterator
from typing import Any

import click

from txtool.io.printable import printable
from txtool.io.xmlio import InputError, XacroOptions, is_xacro


class Choice(click.Choice):
    """A choice given in any case; a value that is none of them gets the nearest as a hint."""

    def __init__(self, choices: tuple[str, ...] | list[str],
                 hints: dict[str, str] | None = None) -> None:
        super().__init__(choices, case_sensitive=False)
        self.hints = hints or {}

    def convert(self, value: Any, param: click.Parameter | None,
                ctx: click.Context | None) -> Any:
        try:
            return super().convert(value, param, ctx)
        except click.BadParameter:
            import difflib

            text = str(value)
            close = difflib.get_close_matches(text.lower(), list(self.choices), n=1, cutoff=0.6)
            hint = self.hints.get(text.lower()) or (repr(close[0]) if close else "")
            message = f"{text!r} is not one of {', '.join(map(repr, self.choices))}"
            self.fail(message + (f"; did you mean {hint}?" if hint else ""), param, ctx)


class RenamedOption(click.Option):
    """An option whose former spellings (``old_names``) still work: hidden from help and
    completion, warning once on stderr that they are deprecated."""

    def __init__(self, *args: Any, old_names: tuple[str, ...], **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self.old_names = tuple(old_names)

    @property
    def _old_dest(self) -> str:
        return f"{self.name}.deprecated"

    def add_to_parser(self, parser: Any, ctx: click.Context) -> None:
        super().add_to_parser(parser, ctx)
        parser.add_option(obj=self, opts=self.old_names, dest=self._old_dest,
                          action="append" if self.multiple else "store", nargs=self.nargs)

    def consume_value(self, ctx: click.Context, opts: Any) -> Any:
        if self._old_dest in opts:
            old = opts[self._old_dest]
            opts = dict(opts)
            if self.multiple:  # the values of the new spelling first, then the old one's
                opts[self.name] = [*opts.get(self.name, ()), *old]
            else:  # given both ways, the new spelling wins
                opts.setdefault(self.name, old)
            click.echo(f"txtool: warning: {'/'.join(self.old_names)} is deprecated; use "
                       f"{'/'.join(self.opts)}", err=True)  # once, however often given
        return super().consume_value(ctx, opts)


# A file argument: any text, checked when read (one line naming it, not click's message), and
# completed as a file name by `txtool completion`.
FILE = click.Path(readable=False)


# A target dialect said the short way: both ROS 2 forms, the one ros2_control parses first.
TARGET_HINTS = {"ros2": "'ros2-p2' (role attributes, the form ros2_control parses) or 'ros2-p1'",
                "ros": "'ros1'", "ros2_control": "'ros2-p2'", "ros_control": "'ros1'"}


def _pairs(values: tuple[str, ...], option: str) -> tuple[tuple[str, str], ...]:
    pairs = []
    for value in values:
        name, sep, rest = value.partition(":=")
        if not sep or not name:
            raise click.BadParameter(f"expected NAME:=VALUE, got {value!r}", param_hint=option)
        pairs.append((name, rest))
    return tuple(pairs)


def xacro_options(function: Callable[..., Any]) -> Callable[..., Any]:
    """``--xacro-arg``, ``--pkg-dir``, ``--pkg-path``, ``--xacro-env``, ``--trust-xacro``,
    gathered into ``xacro=XacroOptions``.

    ``--trust-xacro`` exists only here, on the command line: a pull request can add a
    configuration file, never change the runner's command.
    """

    @click.option("--trust-xacro", "trust_xacro", is_flag=True,
                  help="Run upstream xacro with full Python evaluation, environment and file "
                       "access: only for files you trust (default: a restricted evaluator in "
                       "a bounded process; see docs/security.md).")
    @click.option("--xacro-env", "xacro_env", multiple=True, metavar="NAME",
                  help="An environment variable $(env NAME) and $(optenv NAME) may read "
                       "(repeatable; only here: never from a file of the repository).")
    @click.option("--xacro-arg", "xacro_args", multiple=True, metavar="NAME:=VALUE",
                  help="A xacro argument (repeatable).")
    @click.option("--pkg-dir", "pkg_dirs", multiple=True, metavar="DIR",
                  type=click.Path(file_okay=False),
                  help="A folder holding packages, for $(find pkg) (repeatable).")
    @click.option("--pkg-path", "pkg_paths", multiple=True, metavar="NAME:=DIR",
                  help="Where one package is, for $(find NAME) (repeatable).")
    @functools.wraps(function)
    def wrapper(*args: Any, xacro_args, pkg_dirs, pkg_paths, xacro_env, trust_xacro,
                **kwargs: Any) -> Any:
        dirs = tuple(os.path.abspath(d) for d in pkg_dirs)
        paths = tuple((name, os.path.abspath(d)) for name, d in _pairs(pkg_paths, "--pkg-path"))
        options = XacroOptions(  # folders relative to where the command runs, not to the file
            args=_pairs(xacro_args, "--xacro-arg"), pkg_dirs=dirs, pkg_paths=paths,
            trust=trust_xacro, env=tuple(xacro_env),
            readable=dirs + tuple(folder for _, folder in paths),
        )
        if not (trust_xacro or kwargs.get("no_xacro")) and _names_a_xacro_file(kwargs.values()):
            _prestart_sandbox()
        return function(*args, xacro=options, **kwargs)

    return wrapper


def _prestart_sandbox() -> None:
    """Boot the xacro worker while the command loads (unless the environment turns xacro off:
    then nothing of xacro is even imported)."""
    from txtool.lint.config_files import ConfigError, no_xacro_from_environment

    with contextlib.suppress(ConfigError):
        if no_xacro_from_environment():
            return
        from txtool.io.xacro_sandbox import prestart

        prestart()


def _names_a_xacro_file(values: Any) -> bool:
    for value in values:
        names = value if isinstance(value, tuple | list) else (value,)
        if any(isinstance(name, str) and is_xacro(name) for name in names):
            return True
    return False


NO_XACRO_OPTION = click.option(
    "--no-xacro", is_flag=True,
    help="Never run xacro: read .xacro files as written (also TXTOOL_NO_XACRO=1, or "
         "no-xacro = true in the configuration).",
)


CONFIG_OPTION = click.option(
    "--config", "config_path", type=click.Path(dir_okay=False), metavar="PATH",
    help="Use this configuration file instead of the repository root's.",
)


def xacro_disabled(flag: bool, *paths: str | None, config: str | None = None) -> bool:
    """Whether xacro must not run for these inputs.

    ``--no-xacro``, ``TXTOOL_NO_XACRO`` or the configuration of any input (``config``, the
    ``--config`` file, if given) turns it off for the whole run. None of them can turn it back
    on: a pull request may edit the repository's configuration, but not the runner's command
    line or environment.
    """
    from txtool.lint.config_files import no_xacro_from_environment

    if no_xacro_from_environment() or flag:
        return True
    from txtool.lint.config import no_xacro_configured

    return any(no_xacro_configured(path, config) for path in paths if path is not None)


def configured_packages(xacro: XacroOptions, path: str, config: str | None) -> XacroOptions:
    """``xacro`` with the configuration's ``pkg-dirs`` and ``pkg-paths`` after the command
    line's ``--pkg-dir`` and ``--pkg-path`` (the first match wins): the configuration that
    applies to ``path``, or ``config`` (``--config``)."""
    from txtool.lint.config import Overrides, SettingsCache

    settings = SettingsCache(Overrides(), config)
    if settings.config_for(path) is None:
        return xacro  # the defaults add no folder (and the rules' settings need not be read)
    configured = settings.for_file(path).xacro
    return xacro._replace(pkg_dirs=xacro.pkg_dirs + configured.pkg_dirs,
                          pkg_paths=xacro.pkg_paths + configured.pkg_paths)


def refuse_unexpanded(command: str, *paths: str | None) -> None:
    """For commands that need a xacro file's expansion: one line and exit 2 under --no-xacro.

    A xacro file is one named ``*.xacro`` or one that uses xacro (see txtool.io.load)."""
    from txtool.io.load import file_needs_expansion

    for path in paths:
        if path is not None and path != "-" and file_needs_expansion(path):
            raise InputError(f"{path}: {command} needs the xacro expansion, and xacro is off "
                             "(--no-xacro, TXTOOL_NO_XACRO or no-xacro in the configuration); "
                             "expand it with xacro first")


def require_extra(module: str, extra: str, what: str) -> None:
    """One line and exit 2 when an optional dependency is not installed."""
    import importlib.util

    if importlib.util.find_spec(module) is None:
        from txtool.io.resources import install_extra

        raise InputError(f"{what} needs the '{extra}' extra: {install_extra(extra)}")


COLOR_MODES = ("auto", "always", "never")


def color_wanted(mode: str, stream_is_terminal: bool) -> bool:
    """``--color``: ``auto`` colours a terminal unless ``NO_COLOR`` is set (non-empty);
    ``FORCE_COLOR`` colours a pipe too; ``NO_COLOR`` wins over it, as rich has it."""
    if mode != "auto":
        return mode == "always"
    if os.environ.get("NO_COLOR") or os.environ.get("TERM") == "dumb":
        return False
    return bool(os.environ.get("FORCE_COLOR")) or stream_is_terminal


@contextlib.contextmanager
def color_environment(mode: str) -> Iterator[None]:
    """Tell rich what ``--color`` chose, through the variables every rich console reads
    (``never`` also sets ``TERM=dumb``: NO_COLOR alone still lets rich write bold and italic)."""
    if mode == "auto":
        yield
        return
    saved = {name: os.environ.get(name) for name in ("NO_COLOR", "FORCE_COLOR", "TERM")}
    if mode == "always":
        os.environ.pop("NO_COLOR", None)
        os.environ["FORCE_COLOR"] = "1"
    else:
        os.environ.pop("FORCE_COLOR", None)
        os.environ.update(NO_COLOR="1", TERM="dumb")
    try:
        yield
    finally:
        for name, value in saved.items():
            if value is None:
                os.environ.pop(name, None)
            else:
                os.environ[name] = value


def with_color(command: click.Command) -> None:
    """Give a command that colours through rich a ``--color auto|always|never`` option."""
    if any(param.name == "color" for param in command.params) or command.callback is None:
        return
    command.params.append(click.Option(
        ["--color"], type=Choice(COLOR_MODES), default="auto", show_default=True,
        help="Colour the output: auto colours a terminal unless NO_COLOR is set "
             "(FORCE_COLOR colours a pipe too).",
    ))
    callback = command.callback

    @functools.wraps(callback)
    def coloured(*args: Any, color: str = "auto", **kwargs: Any) -> Any:
        with color_environment(color):
            return callback(*args, **kwargs)

    command.callback = coloured


def exit_on_input_error(function: Callable[..., int | None]) -> Callable[..., None]:
    """Run a command body; an :class:`InputError` is one line on stderr and exit 2."""

    @functools.wraps(function)
    def wrapper(*args: Any, **kwargs: Any) -> None:
        from txtool.io.targets import forget_inputs

        forget_inputs()
        try:
            _working_folder()
            code = function(*args, **kwargs)
        except InputError as exc:
            click.echo(f"txtool: {printable(str(exc))}", err=True)
            sys.exit(2)
        except OSError as exc:
            if exc.filename is None:
                raise
            # A file or folder the command had to look at (a configuration file in an
            # unreadable folder, say), refused by the system: named, as an input error is.
            reason = (exc.strerror or str(exc)).lower()
            click.echo(f"txtool: {printable(os.fsdecode(exc.filename))}: {reason}", err=True)
            sys.exit(2)
        sys.exit(code or 0)

    return wrapper


def _working_folder() -> None:
    """Refuse to start in a working folder that was deleted (or cannot be read): relative
    paths, configuration discovery and folder walks all start from it."""
    try:
        os.getcwd()
    except OSError as exc:
        raise InputError(f"the working folder cannot be used ({(exc.strerror or str(exc)).lower()}"
                         "; was it deleted?): change to an existing folder") from None


FORMAT_OPTION = click.option(
    "--format", "output_format", type=Choice(["text", "json"]), default="text",
    show_default=True, help="Output format.",
)


def complete_codes(ctx: click.Context, param: click.Parameter, incomplete: str) -> list:
    """Shell completion of rule codes for ``--select``/``--ignore`` (the last of a
    comma-separated list: ``TX1,TX30`` offers ``TX1,TX300``...), each with its rule's name."""
    from click.shell_completion import CompletionItem

    from txtool.rules import all_rules

    head, comma, last = incomplete.rpartition(",")
    prefix = head + comma
    return [CompletionItem(prefix + code, help=rule.name)
            for code, rule in sorted(all_rules().items()) if code.startswith(last.upper())]


def complete_rules(ctx: click.Context, param: click.Parameter, incomplete: str) -> list:
    """Shell completion of a rule's code or name (``txtool rules CODE``)."""
    from click.shell_completion import CompletionItem

    from txtool.rules import all_rules

    rules = sorted(all_rules().values(), key=lambda rule: rule.code)
    return ([CompletionItem(rule.code, help=rule.name) for rule in rules
             if rule.code.startswith(incomplete.upper())]
            + [CompletionItem(rule.name, help=rule.code) for rule in rules
               if incomplete and rule.name.startswith(incomplete.lower())])


def controllers_option(what: str) -> Callable[[Callable[..., Any]], Callable[..., Any]]:
    """``--controllers FILE`` (repeatable) of convert and migrate: ``what`` is converted."""
    return click.option(
        "--controllers", "controller_files", multiple=True, type=click.Path(dir_okay=False),
        metavar="FILE",
        help=f"A ROS 1 controller configuration (YAML): say what each controller is in ROS 2 "
             f"and whether the <ros2_control> of {what} provides what it claims "
             f"(--to ros2-p1/ros2-p2; repeatable).")


def controller_configurations(paths: tuple[str, ...], target: str | None) -> list:
    """The ROS 1 controller configurations ``--controllers`` names, read before anything is
    written; an :class:`InputError` for a target other than ROS 2 or a file that is no ROS 1
    controller configuration."""
    if not paths:
        return []
    if target not in ("ros2-p1", "ros2-p2"):
        raise InputError("--controllers applies to --to ros2-p1 and ros2-p2")
    from txtool.lint.controller_files import ros1_controller_file

    return [ros1_controller_file(path) for path in paths]


def tell_controller_needs(controllers: list, robots: dict[str, Any]) -> None:
    """Each ROS 1 controller's ROS 2 form, against the converted robot (``robots``: each
    converted robot's root element by its path) having most of the joints the file's
    controllers claim; a note for a file that no converted robot fits."""
    from txtool.lint.controller_files import (
        controllers_of,
        pick_robot,
        provision_of,
        ros2_needs,
    )

    provisions = {path: provision_of(root) for path, root in robots.items()}
    for file in controllers:
        chosen = pick_robot(controllers_of(file), "ros2", provisions)  # type: ignore[arg-type]
        if chosen is None and len(robots) == 1:  # the one robot named: judged all the same
            chosen = next(iter(robots))
        if chosen is None:
            click.echo(f"note: {printable(file.path)}: no robot converted to ROS 2 here drives "
                       "the joints its controllers claim; not checked", err=True)
            continue
        if len(robots) > 1:
            click.echo(f"note: {printable(file.path)}: against {printable(chosen)}, the robot "
                       "driving most of the joints its controllers claim", err=True)
        notes, warnings = ros2_needs(file, robots[chosen])
        for note in notes:
            click.echo(f"note: {printable(note)}", err=True)
        for warning in warnings:
            click.echo(f"warning: {printable(warning)}", err=True)
