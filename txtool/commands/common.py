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


def _pairs(values: tuple[str, ...], option: str) -> tuple[tuple[str, str], ...]:
    pairs = []
    for value in values:
        name, sep, rest = value.partition(":=")
        if not sep or not name:
            raise click.BadParameter(f"expected NAME:=VALUE, got {value!r}", param_hint=option)
        pairs.append((name, rest))
    return tuple(pairs)


def xacro_options(function: Callable[..., Any]) -> Callable[..., Any]:
    """``--xacro-arg``, ``--pkg-dir``, ``--pkg-path``, gathered into ``xacro=XacroOptions``."""

    @click.option("--xacro-arg", "xacro_args", multiple=True, metavar="NAME:=VALUE",
                  help="A xacro argument (repeatable).")
    @click.option("--pkg-dir", "pkg_dirs", multiple=True, metavar="DIR",
                  type=click.Path(file_okay=False),
                  help="A folder holding packages, for $(find pkg) (repeatable).")
    @click.option("--pkg-path", "pkg_paths", multiple=True, metavar="NAME:=DIR",
                  help="Where one package is, for $(find NAME) (repeatable).")
    @functools.wraps(function)
    def wrapper(*args: Any, xacro_args, pkg_dirs, pkg_paths, **kwargs: Any) -> Any:
        options = XacroOptions(  # folders relative to where the command runs, not to the file
            args=_pairs(xacro_args, "--xacro-arg"),
            pkg_dirs=tuple(os.path.abspath(d) for d in pkg_dirs),
            pkg_paths=tuple(
                (name, os.path.abspath(d)) for name, d in _pairs(pkg_paths, "--pkg-path")
            ),
        )
        return function(*args, xacro=options, **kwargs)

    return wrapper


NO_XACRO_OPTION = click.option(
    "--no-xacro", is_flag=True,
    help="Never run xacro: read .xacro files as written (also TXTOOL_NO_XACRO=1, or "
         "no-xacro = true in the configuration).",
)


def xacro_disabled(flag: bool, *paths: str | None) -> bool:
    """Whether xacro must not run for these inputs.

    ``--no-xacro``, ``TXTOOL_NO_XACRO`` or the configuration of any input turns it off for the
    whole run. None of them can turn it back on: a pull request may edit the repository's
    configuration, but not the runner's command line or environment.
    """
    from txtool.lint.config_files import no_xacro_configured, no_xacro_from_environment

    if no_xacro_from_environment() or flag:
        return True
    return any(no_xacro_configured(path) for path in paths if path is not None)


def refuse_unexpanded(command: str, *paths: str | None) -> None:
    """For commands that need a xacro file's expansion: one line and exit 2 under --no-xacro."""
    for path in paths:
        if path is not None and is_xacro(path):
            raise InputError(f"{path}: {command} needs the xacro expansion, and xacro is off "
                             "(--no-xacro, TXTOOL_NO_XACRO or no-xacro in the configuration); "
                             "expand it with xacro first")


def require_extra(module: str, extra: str, what: str) -> None:
    """One line and exit 2 when an optional dependency is not installed."""
    import importlib.util

    if importlib.util.find_spec(module) is None:
        raise InputError(f"{what} needs the '{extra}' extra: pip install 'txtool[{extra}]'")


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
        ["--color"], type=click.Choice(COLOR_MODES), default="auto", show_default=True,
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
    "--format", "output_format", type=click.Choice(["text", "json"]), default="text",
    show_default=True, help="Output format.",
)
