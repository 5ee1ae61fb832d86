"""The ``txtool`` command line: argument parsing only; every command calls into the core.

Each command lives in ``txtool/commands/<name>.py`` as a click command named ``command``; the
modules import nothing heavy at module level, so ``txtool validate`` never loads pinocchio.
"""

from __future__ import annotations

import contextlib
import errno
import gc
import importlib
import os
import sys
from types import ModuleType
from typing import Any

import click

from txtool import __version__
from txtool.io import signals
from txtool.io.printable import printable

# Commands whose output rich may colour: each gets --color (see commands.common.with_color).
COLOURING = frozenset({"show", "roundtrip", "demo", "simulate"})

COMMAND_MODULES = (
    "show",
    "convert",
    "roundtrip",
    "validate",
    "migrate",
    "rules",
    "map",
    "simulate",
    "schema",
    "demo",
    "lsp",
    "completion",
)


# Shown at the end of each command's --help ("\b" keeps click from re-wrapping the lines).
EXAMPLES: dict[str, tuple[str, ...]] = {
    "validate": (
        "txtool validate .                       # a repository or workspace",
        "txtool validate urdf/ --select TX1 --strict",
        "txtool validate --format github --format sarif:txtool.sarif .   # both, one run",
        "txtool validate urdf/ --fix              # apply the fixes of the [*] findings",
        "txtool validate - --stdin-filename urdf/robot.urdf < generated.urdf",
    ),
    "show": (
        "txtool show robot.urdf",
        "txtool show robot.urdf.xacro --effective   # what each loader binds",
        "txtool show robot.urdf --format json --actuator-limits",
    ),
    "convert": (
        "txtool convert robot.urdf --to ros2-p2 -o robot.ros2.urdf",
        "txtool convert robot.urdf --to ros2-p1 -o robot.urdf --write   # in place",
        "txtool convert robot.urdf --to bb --bb-topology",
    ),
    "migrate": (
        "txtool migrate urdf/ --diff",
        "txtool migrate urdf/ --check          # CI: exit 1 when a fix is pending",
        "txtool migrate urdf/ --to ros2-p2 --write",
    ),
    "roundtrip": (
        "txtool roundtrip robot.urdf",
        "txtool roundtrip robot.urdf --against robot.ros2.urdf",
    ),
    "map": (
        "txtool map robot.urdf -t shoulder_trans --to actuator --position 0.5",
        "txtool map robot.urdf -t wrist_trans --to joint --effort 1,1 --format json",
    ),
    "simulate": (
        "txtool simulate robot.urdf                       # the robot's own config",
        "txtool simulate robot.urdf --candidate candidate.urdf --plot run.png",
        "txtool simulate robot.urdf --params controllers.yaml --format json",
        "txtool simulate robot.urdf --campaign campaign.toml   # perturbed robots, on Dask",
    ),
    "rules": ("txtool rules", "txtool rules TX106", "txtool rules zero-reduction --format json"),
    "schema": ("txtool schema -o transmission.schema.json",),
    "demo": ("txtool demo",),
    "lsp": ("txtool lsp                          # stdio, started by the editor",
            "txtool lsp --tcp 127.0.0.1:2087"),
    "completion": (
        "txtool completion bash > ~/.local/share/bash-completion/completions/txtool",
        "txtool completion zsh > ~/.zfunc/_txtool   # fpath+=~/.zfunc before compinit",
        "txtool completion fish > ~/.config/fish/completions/txtool.fish",
    ),
}


class LazyGroup(click.Group):
    """Loads a command's module only when that command runs (or help lists it)."""

    def list_commands(self, ctx: click.Context) -> list[str]:
        return sorted(name for name in COMMAND_MODULES if self._load(name) is not None)

    def resolve_command(
        self, ctx: click.Context, args: list[str]
    ) -> tuple[str | None, click.Command | None, list[str]]:
        name = args[0] if args else ""
        if name and not name.startswith("-") and name not in COMMAND_MODULES:
            import difflib

            near = difflib.get_close_matches(name, COMMAND_MODULES, n=1)
            if near:
                ctx.fail(f"No such command '{name}'. Did you mean '{near[0]}'?")
        return super().resolve_command(ctx, args)

    def format_commands(self, ctx: click.Context, formatter: click.HelpFormatter) -> None:
        """The commands and the first sentence of each one's help, whole: click cuts it to
        the line's room with "...", here the sentence goes on over the next lines."""
        rows = [(name, command.get_short_help_str(limit=1000))
                for name in self.list_commands(ctx)
                if (command := self.get_command(ctx, name)) is not None and not command.hidden]
        if rows:
            with formatter.section("Commands"):
                formatter.write_dl(rows)

    def get_command(self, ctx: click.Context, cmd_name: str) -> click.Command | None:
        if cmd_name not in COMMAND_MODULES:
            return None
        return self._load(cmd_name)

    def invoke(self, ctx: click.Context) -> object:
        try:
            return super().invoke(ctx)
        except KeyboardInterrupt:  # not click's "Aborted!" and exit 1, the code of findings
            click.echo("txtool: interrupted", err=True)
            sys.exit(130)

    @staticmethod
    def _load(name: str) -> click.Command | None:
        module_name = f"txtool.commands.{name}"
        try:
            module = importlib.import_module(module_name)
        except ModuleNotFoundError as exc:
            if exc.name == module_name:
                return None
            raise
        command: click.Command = module.command
        if name in EXAMPLES and not command.epilog:
            lines = "\n".join(f"  $ {example}" for example in EXAMPLES[name])
            command.epilog = f"\b\nExamples:\n{lines}"
        if name in COLOURING:
            from txtool.commands.common import with_color

            with_color(command)
        return command


@click.group(cls=LazyGroup, context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(__version__, prog_name="txtool")
@click.option("--debug", is_flag=True, help="Show the traceback of internal errors.")
@click.pass_context
def cli(ctx: click.Context, debug: bool) -> None:
    """Lint, convert and verify robot transmission configurations (ros_control, ros2_control)."""
    ctx.ensure_object(dict)
    ctx.obj["debug"] = debug


def main() -> None:
    # What is loaded so far lives as long as the process: the garbage collector need not walk
    # it in every full collection (nor at exit).
    gc.freeze()
    # The first signal raises Stopped wherever it lands between the two swaps of handlers
    # (while either is being installed too), and always inside this try: none ends in a
    # traceback. Before the first swap and after the second, a signal ends the process at once.
    try:
        _stopping_on_signals()
    except signals.Stopped as stop:  # a signal while leaving: nothing is left to clean up
        _leave(stop.line, stop.exit_code)


def _stopping_on_signals() -> None:
    signals.stop_on_signals()
    try:
        _main()
    finally:
        signals.exit_on_signals()  # until the process ends


def _main() -> None:
    debug = "--debug" in sys.argv[1:]
    xmlio = _xmlio_if_loaded()
    if xmlio is not None:
        xmlio.forget_reading()
    _escape_what_cannot_be_encoded()
    sys.stdout = GuardedStdout(sys.stdout)  # type: ignore[assignment]
    try:
        try:
            cli.main(prog_name="txtool", standalone_mode=True)
        finally:
            sys.stdout.flush()  # a full disk shows here, not as a warning at exit
    except signals.Stopped as stop:
        _leave(stop.line, stop.exit_code)
    except ClosedPipe:
        _leave("", CLOSED_PIPE)
    except OutputError as exc:
        _leave(f"txtool: cannot write standard output: {exc}", 2)
    except SystemExit:
        if signals.received() is not None:
            _stopped()
        raise
    except BaseException as exc:  # the last line of defence: one line, exit 2
        if signals.received() is not None:  # a library turned the interrupt into an error
            _stopped()
        if debug or not isinstance(exc, Exception):
            raise
        click.echo(internal_error_line(exc), err=True)
        sys.exit(2)


def _stopped() -> None:
    stop = signals.Stopped(signals.received() or 2)
    _leave(stop.line, stop.exit_code)


def _leave(line: str, code: int) -> None:
    """Print ``line`` (if any) on stderr and exit ``code``; what is left for stdout goes
    nowhere."""
    with contextlib.suppress(Exception):
        if line:
            sys.stderr.write(line + "\n")
            sys.stderr.flush()
    # What stdout still buffers would fail again when Python flushes it at exit.
    with contextlib.suppress(Exception):
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.__stdout__.fileno() if sys.__stdout__ else 1)
    raise SystemExit(code)


def _escape_what_cannot_be_encoded() -> None:
    """Under an encoding that cannot hold every character (``PYTHONIOENCODING=ascii``, a C
    locale), print the others as ``\\u2192`` escapes rather than fail: a name from a file may
    hold any character, and the tables draw arrows and ticks."""
    for stream in (sys.stdout, sys.stderr):
        reconfigure = getattr(stream, "reconfigure", None)
        if reconfigure is not None and (getattr(stream, "encoding", "") or "").lower() not in (
                "utf-8", "utf8"):
            with contextlib.suppress(Exception):
                reconfigure(errors="backslashreplace")


class OutputError(Exception):
    """Standard output could not be written (a full disk): one line, exit 2."""


class ClosedPipe(OutputError):
    """The reader of standard output went away (``| head``): txtool ends quietly, as a Unix
    tool that SIGPIPE stops does, with that exit code (128 + 13)."""


CLOSED_PIPE = 141


class GuardedStdout:
    """``sys.stdout`` whose write errors are :class:`OutputError`, told apart from the
    errors of reading inputs (which name their file); ``buffer`` is guarded the same way."""

    def __init__(self, stream: Any) -> None:
        self._stream = stream

    def write(self, data: Any) -> int:
        try:
            return self._stream.write(data)  # type: ignore[no-any-return]
        except OSError as exc:
            raise _output_error(exc) from None

    def flush(self) -> None:
        try:
            self._stream.flush()
        except OSError as exc:
            raise _output_error(exc) from None
        except ValueError:  # closed
            pass

    @property
    def buffer(self) -> Any:
        return GuardedStdout(self._stream.buffer)

    def __getattr__(self, name: str) -> Any:
        return getattr(self._stream, name)


def _output_error(exc: OSError) -> OutputError:
    if exc.errno == errno.EPIPE:
        return ClosedPipe()
    return OutputError(exc.strerror or str(exc))


def internal_error_line(exc: BaseException) -> str:
    """``txtool: internal error: Type: message (while reading PATH; please report)``."""
    xmlio = _xmlio_if_loaded()
    message = printable(" ".join(str(exc).split())) or "(no message)"
    path = xmlio.reading() if xmlio is not None else None
    if path is not None:
        path = printable(path)
    where = f"while reading {path}; " if path else ""
    return f"txtool: internal error: {type(exc).__name__}: {message} ({where}please report)"


def _xmlio_if_loaded() -> ModuleType | None:
    # Not imported here: commands that read no file (--version, rules, schema) skip lxml.
    return sys.modules.get("txtool.io.xmlio")
