"""``txtool lsp``: the language server for editors (the ``lsp`` extra): argument parsing only."""

from __future__ import annotations

import os
import sys
from collections.abc import Callable

import click

from txtool.commands.common import (
    CONFIG_OPTION,
    NO_XACRO_OPTION,
    exit_on_input_error,
    require_extra,
    xacro_options,
)
from txtool.io import signals
from txtool.io.xmlio import InputError
from txtool.model.distro import CHOICES


def _address(value: str | None) -> tuple[str, int] | None:
    if value is None:
        return None
    host, _, port = value.rpartition(":")
    if not host or not port.isdigit() or not 0 < int(port) < 65536:
        raise click.BadParameter(f"expected HOST:PORT, got {value!r}", param_hint="--tcp")
    return host, int(port)


@click.command("lsp")
@click.option("--tcp", "tcp", metavar="HOST:PORT",
              help="Listen on this address instead of speaking on standard input and output; "
                   "the client is served if its initialize request carries the session's "
                   "token in initializationOptions.token (TXTOOL_LSP_TOKEN, else one made "
                   "and printed on standard error).")
@click.option("--ros-distro", type=click.Choice(CHOICES), default=None,
              help="The ROS distribution whose programs read the files (over the "
                   "configuration's ros-distro).")
@NO_XACRO_OPTION
@CONFIG_OPTION
@xacro_options
@exit_on_input_error
def command(tcp, ros_distro, no_xacro, config_path, xacro) -> int:
    """Run the language server: diagnostics as you type in .urdf, .xacro and robot .xml files,
    quick fixes for the fixable rules, and on a <transmission> a hover showing what each loader
    reads of it (show --effective).

    The editor's unsaved text is checked as validate checks the saved file: the same rules,
    configuration (decided from the repository of the editor's workspace) and suppressions;
    xacro runs in its sandbox unless --trust-xacro. Needs the 'lsp' extra
    (see docs/editors.md).
    """
    address = _address(tcp)
    for module in ("pygls", "lsprotocol"):
        require_extra(module, "lsp", "txtool lsp")
    from txtool.commands.lsp_document import Options
    from txtool.commands.lsp_server import build

    if config_path is not None and not os.path.isfile(config_path):
        raise InputError(f"{config_path}: no such file")
    server = build(Options(xacro=xacro, no_xacro=no_xacro, config=config_path,
                           ros_distro=ros_distro))
    if address is not None:
        token, said = _token()
        _quiet_exit_over_tcp()
        try:
            server.start_tcp(*address, token, said)
        except OSError as exc:  # the address is taken, or not this machine's
            raise InputError(f"--tcp {tcp}: {(exc.strerror or str(exc)).lower()}") from None
        return 0
    # The protocol owns standard output: anything else printed goes to standard error.
    stdin, stdout = sys.stdin.buffer, sys.__stdout__.buffer
    sys.stdout = sys.stderr
    with signals.left_to_the_main_thread():
        server.thread_pool.submit(int).result()  # the one thread that reads, made now
    server.start_io(stdin, stdout)
    return 0


def _token() -> tuple[str, Callable[[], None]]:
    """The session's token: ``TXTOOL_LSP_TOKEN``, else a new one said on standard error once
    the server listens (any local process can connect to a port: only the client that was
    told the token is served); and what to do once listening."""
    given = os.environ.get("TXTOOL_LSP_TOKEN", "")
    if given:
        if len(given) < 16:
            raise InputError("TXTOOL_LSP_TOKEN: at least 16 characters")
        return given, lambda: None
    import secrets

    token = secrets.token_urlsafe(24)

    def say() -> None:
        print(f"txtool lsp: the client sends initializationOptions.token = {token}",
              file=sys.stderr, flush=True)

    return token, say


def _quiet_exit_over_tcp() -> None:
    """pygls leaves on the ``exit`` notification by raising SystemExit in the connection's
    task, which asyncio logs with a traceback before it ends the process: not an error."""
    import logging

    def not_the_exit(record: logging.LogRecord) -> bool:
        return not (record.exc_info and isinstance(record.exc_info[1], SystemExit))

    logging.getLogger("asyncio").addFilter(not_the_exit)
