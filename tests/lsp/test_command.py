"""``txtool lsp`` on the command line: its options, the extra it needs, and a session over TCP."""

from __future__ import annotations

import asyncio
import os
import socket
import subprocess
import sys
import time
from pathlib import Path

import pytest
from click.testing import CliRunner
from lsprotocol import types as lsp
from pygls.lsp.client import LanguageClient

from txtool.cli import cli

ROOT = Path(__file__).resolve().parents[2]
TOKEN = "a-token-the-test-chose"


def invoke(*args: str) -> tuple[int, str, str]:
    result = CliRunner().invoke(cli, list(args), catch_exceptions=False)
    return result.exit_code, result.stdout, result.stderr


def test_without_the_extra_it_names_the_extra_to_install(monkeypatch) -> None:
    monkeypatch.setitem(sys.modules, "pygls", None)  # as if not installed
    assert invoke("lsp") == (
        2, "", "txtool: txtool lsp needs the 'lsp' extra: pip install 'txtool[lsp] @ "
        "git+https://github.com/txtool/txtool' (in a clone: pip install -e '.[lsp]')\n")


@pytest.mark.parametrize("address", ["2087", "localhost:", "localhost:http", "[::1]:70000"])
def test_a_tcp_address_that_is_none_is_a_usage_error(address: str) -> None:
    code, out, err = invoke("lsp", "--tcp", address)
    assert (code, out) == (2, "") and "expected HOST:PORT" in err


def test_a_configuration_file_that_is_not_there_stops_it(tmp_path: Path) -> None:
    missing = tmp_path / "none.toml"
    assert invoke("lsp", "--config", str(missing)) == (2, "", f"txtool: {missing}: no such file\n")


def test_a_taken_port_is_one_line() -> None:
    with socket.socket() as taken:
        taken.bind(("127.0.0.1", 0))
        taken.listen()
        port = taken.getsockname()[1]
        code, out, err = invoke("lsp", "--tcp", f"127.0.0.1:{port}")
    assert (code, out) == (2, "") and err.startswith(f"txtool: --tcp 127.0.0.1:{port}: ")
    assert len(err.splitlines()) == 1


def test_a_session_over_tcp(tmp_path: Path) -> None:
    with socket.socket() as probe:  # a port free a moment ago
        probe.bind(("127.0.0.1", 0))
        port = probe.getsockname()[1]
    server = subprocess.Popen([sys.executable, "-m", "txtool", "lsp", "--tcp",
                               f"127.0.0.1:{port}"], cwd=ROOT, stderr=subprocess.PIPE,
                              env={**os.environ, "TXTOOL_LSP_TOKEN": TOKEN})
    try:
        found = asyncio.run(asyncio.wait_for(_session(port, tmp_path), 30))
        _, err = server.communicate(timeout=10)  # it leaves on "exit", by itself
    finally:
        if server.poll() is None:
            server.kill()
            server.communicate()
    assert (found, server.returncode, err) == (["TX106"], 0, b"")


async def _session(port: int, folder: Path) -> list[str]:
    from tests.lsp.robots import ARM, REDUCTION

    client = LanguageClient("test-editor", "1")
    published: asyncio.Queue[lsp.PublishDiagnosticsParams] = asyncio.Queue()

    @client.feature(lsp.TEXT_DOCUMENT_PUBLISH_DIAGNOSTICS)
    def on_diagnostics(params: lsp.PublishDiagnosticsParams) -> None:
        published.put_nowait(params)

    deadline = time.monotonic() + 20
    while True:  # until the server listens
        try:
            await client.start_tcp("127.0.0.1", port)
            break
        except OSError:
            if time.monotonic() > deadline:
                raise
            await asyncio.sleep(0.1)
    await client.initialize_async(lsp.InitializeParams(
        capabilities=lsp.ClientCapabilities(), root_uri=folder.as_uri(),
        initialization_options={"token": TOKEN}))
    client.initialized(lsp.InitializedParams())
    uri = (folder / "arm.urdf").as_uri()
    text = ARM.replace(">PositionJointInterface<", ">hardware_interface/PositionJointInterface<")
    assert REDUCTION in text
    client.text_document_did_open(lsp.DidOpenTextDocumentParams(text_document=lsp.TextDocumentItem(
        uri=uri, language_id="xml", version=1, text=text)))
    params = await asyncio.wait_for(published.get(), 15)
    await client.shutdown_async(None)
    client.exit(None)
    await client.stop()
    return sorted(str(d.code) for d in params.diagnostics)
