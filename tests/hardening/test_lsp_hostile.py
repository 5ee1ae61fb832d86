"""``txtool lsp`` against hostile clients and documents, spoken to as raw JSON-RPC.

Over TCP any local process can connect: only the client that sends the session's token in
``initialize`` is served, one at a time, and only documents inside the folders it declared.
A document the client never opened is never read (pygls would read it from disk: a FIFO
blocked the server for good, ``/dev/zero`` was read to exhaustion, a missing file was a
traceback). A message's size is bounded without ending the server; a burst of keystrokes is
checked once, at its newest version; every edit names the version it was made for.
"""

from __future__ import annotations

import asyncio
import contextlib
import json
import os
import signal
import socket
import sys
from pathlib import Path
from typing import Any

import pytest

pytest.importorskip("pygls", reason="txtool lsp needs the 'lsp' extra")

from tests.lsp.robots import ARM  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
TOKEN = "hostile-test-token-0123456789"
WAIT = 20.0  # seconds for one answer
ENV = {**os.environ, "PYTHONPATH": str(ROOT), "TXTOOL_LSP_TOKEN": TOKEN}


STARTED: list[asyncio.subprocess.Process] = []  # the servers a test started


@pytest.fixture(autouse=True)
def no_server_left() -> Any:
    """A server a failed test left (blocked, or waiting for its client) is killed, if the
    process of that number is still one of these servers."""
    yield
    while STARTED:
        process = STARTED.pop()
        if process.returncode is not None:
            continue
        with contextlib.suppress(OSError):
            command = Path(f"/proc/{process.pid}/cmdline").read_bytes()
            if b"txtool\x00lsp" in command and str(ROOT).encode() in Path(
                    f"/proc/{process.pid}/environ").read_bytes():
                os.kill(process.pid, signal.SIGKILL)


def frame(message: dict[str, Any]) -> bytes:
    body = json.dumps(message).encode()
    return b"Content-Length: %d\r\n\r\n%s" % (len(body), body)


class Raw:
    """A client that writes bytes and reads framed messages."""

    def __init__(self, reader: asyncio.StreamReader, writer: Any) -> None:
        self.reader, self.writer = reader, writer
        self.notifications: list[dict[str, Any]] = []
        self.next_id = 0

    def send(self, data: bytes | dict[str, Any]) -> None:
        self.writer.write(data if isinstance(data, bytes) else frame(data))

    async def message(self) -> dict[str, Any] | None:
        length = None
        while True:
            line = await asyncio.wait_for(self.reader.readline(), WAIT)
            if not line:
                return None
            if line.lower().startswith(b"content-length:"):
                length = int(line.split(b":")[1])
            elif not line.strip() and length is not None:
                return json.loads(await self.reader.readexactly(length))

    async def request(self, method: str, params: Any) -> Any:
        self.next_id += 1
        self.send({"jsonrpc": "2.0", "id": self.next_id, "method": method, "params": params})
        while True:
            message = await self.message()
            assert message is not None, f"the server ended before answering {method}"
            if message.get("id") == self.next_id and "method" not in message:
                return message.get("result")
            if "method" in message and "id" in message:  # a request of the server's
                self.send({"jsonrpc": "2.0", "id": message["id"], "result": None})
            elif "method" in message:
                self.notifications.append(message)

    def notify(self, method: str, params: Any) -> None:
        self.send({"jsonrpc": "2.0", "method": method, "params": params})

    async def initialize(self, folder: Path, token: str | None = TOKEN) -> Any:
        options = {"token": token} if token is not None else None
        result = await self.request("initialize", {
            "processId": None, "capabilities": {}, "rootUri": None,
            "workspaceFolders": [{"uri": folder.as_uri(), "name": "robot"}],
            "initializationOptions": options})
        self.notify("initialized", {})
        return result

    def open(self, path: Path, text: str, version: int = 1) -> str:
        uri = path.as_uri()
        self.notify("textDocument/didOpen", {"textDocument": {
            "uri": uri, "languageId": "xml", "version": version, "text": text}})
        return uri

    async def published(self, uri: str) -> list[dict[str, Any]]:
        """Every publication for ``uri`` received so far, after a round trip (a request
        answered after everything sent before it was handled)."""
        await self.request("textDocument/hover", {
            "textDocument": {"uri": uri}, "position": {"line": 0, "character": 0}})
        return [n["params"] for n in self.notifications
                if n["method"] == "textDocument/publishDiagnostics" and n["params"]["uri"] == uri]

    async def leave(self) -> None:
        await self.request("shutdown", None)
        self.notify("exit", None)
        self.close()

    def close(self) -> None:
        self.writer.close()


async def stdio_server() -> tuple[asyncio.subprocess.Process, Raw]:
    process = await asyncio.create_subprocess_exec(
        sys.executable, "-m", "txtool", "lsp", cwd=str(ROOT), env=ENV,
        stdin=asyncio.subprocess.PIPE, stdout=asyncio.subprocess.PIPE,
        stderr=asyncio.subprocess.PIPE, limit=2**24)
    STARTED.append(process)
    assert process.stdin is not None and process.stdout is not None
    return process, Raw(process.stdout, process.stdin)


async def ended(process: asyncio.subprocess.Process) -> tuple[int, str]:
    assert process.stderr is not None
    _, err = await asyncio.wait_for(process.communicate(), WAIT)
    return process.returncode or 0, err.decode()


def session(coroutine: Any) -> Any:
    return asyncio.run(asyncio.wait_for(coroutine, 120))


@pytest.fixture
def repository(tmp_path: Path) -> Path:
    (tmp_path / ".git").mkdir()
    (tmp_path / "arm.urdf").write_text(ARM)
    return tmp_path


# --- never-opened documents: nothing is read -------------------------------------------

@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="FIFOs are POSIX")
def test_a_never_opened_document_is_never_read(repository: Path, tmp_path: Path):
    fifo = repository / "blocks.urdf"
    os.mkfifo(fifo)
    targets = [fifo, Path("/dev/zero"), repository / "missing.urdf", repository / "arm.urdf"]

    async def run() -> tuple[list[Any], int, str]:
        process, client = await stdio_server()
        await client.initialize(repository)
        answers = []
        for path in targets:
            uri = path.as_uri()
            client.notify("textDocument/didSave", {"textDocument": {"uri": uri}})
            answers.append(await client.request("textDocument/hover", {
                "textDocument": {"uri": uri}, "position": {"line": 60, "character": 5}}))
            answers.append(await client.request("textDocument/codeAction", {
                "textDocument": {"uri": uri},
                "range": {"start": {"line": 0, "character": 0},
                          "end": {"line": 1, "character": 0}},
                "context": {"diagnostics": []}}))
        assert not [n for n in client.notifications
                    if n["method"] == "textDocument/publishDiagnostics"]
        await client.leave()
        return (answers, *await ended(process))

    answers, code, err = session(run())
    assert answers == [None, []] * len(targets)
    assert (code, err) == (0, "")


def test_hover_of_an_opened_document_still_answers(repository: Path):
    async def run() -> tuple[Any, int, str]:
        process, client = await stdio_server()
        await client.initialize(repository)
        uri = client.open(repository / "arm.urdf", ARM)
        line = next(i for i, text in enumerate(ARM.splitlines()) if "<transmission" in text)
        hover = await client.request("textDocument/hover", {
            "textDocument": {"uri": uri}, "position": {"line": line, "character": 4}})
        await client.leave()
        return (hover, *await ended(process))

    hover, code, err = session(run())
    assert hover is not None and "SimpleTransmission" in hover["contents"]["value"]
    assert (code, err) == (0, "")


# --- message sizes -----------------------------------------------------------------------

def test_a_message_over_the_limit_is_read_past_and_the_server_goes_on(repository: Path):
    from txtool.commands.lsp_transport import MAX_MESSAGE

    size = MAX_MESSAGE + 1
    filler = {"jsonrpc": "2.0", "method": "$/noise", "params": {"x": ""}}
    body = json.dumps(filler).encode()
    body = body.replace(b'"x": ""', b'"x": "' + b"a" * (size - len(body)) + b'"')
    assert len(body) == size

    async def run() -> tuple[Any, int, str]:
        process, client = await stdio_server()
        client.send(b"Content-Length: %d\r\n\r\n" % size + body)
        result = await client.initialize(repository)
        await client.leave()
        return (result, *await ended(process))

    result, code, err = session(run())
    assert result["serverInfo"]["name"] == "txtool"
    assert (code, err) == (0, f"txtool lsp: a message of {size} bytes was refused "
                              f"(at most {MAX_MESSAGE})\n")


@pytest.mark.parametrize("header", [
    b"Content-Length: " + b"9" * 40 + b"\r\n\r\n",  # more than any memory
    b"Content-Length: 1\r\n" + b"X-Padding: " + b"p" * 10_000_000 + b"\r\n\r\n",  # a long line
])
def test_an_absurd_header_ends_no_server_by_an_error(header: bytes):
    async def run() -> tuple[int, str]:
        process, client = await stdio_server()
        client.send(header)
        client.writer.close()  # the client leaves: the server ends as at any end of input
        return await ended(process)

    code, err = session(run())
    assert code == 0 and "Traceback" not in err and "Error" not in err, err


# --- debounce and versions ---------------------------------------------------------------

def test_a_burst_of_keystrokes_is_checked_once_at_its_newest_version(repository: Path):
    burst = 40

    async def run() -> tuple[list[Any], Any]:
        process, client = await stdio_server()
        await client.initialize(repository)
        uri = client.open(repository / "arm.urdf", ARM)
        first = await client.published(uri)
        burst_bytes = b""  # typing "0" then rubbing it out, 20 times: sent in one write
        for version in range(2, burst + 2):
            text = ARM if version % 2 else ARM.replace("<mechanicalReduction>", "<mechanical"
                                                       "Reduction>0", 1)
            burst_bytes += frame({"jsonrpc": "2.0", "method": "textDocument/didChange",
                                  "params": {"textDocument": {"uri": uri, "version": version},
                                             "contentChanges": [{"text": text}]}})
        client.send(burst_bytes)
        while len(await client.published(uri)) == len(first):
            await asyncio.sleep(0.2)
        await asyncio.sleep(1.0)  # anything later would show now
        published = await client.published(uri)
        diagnostics = published[-1]["diagnostics"]
        fix_all = await client.request("textDocument/codeAction", {
            "textDocument": {"uri": uri}, "range": {"start": {"line": 0, "character": 0},
                                                     "end": {"line": 0, "character": 0}},
            "context": {"diagnostics": diagnostics}})
        await client.leave()
        await ended(process)
        return [p["version"] for p in published], fix_all

    versions, actions = session(run())
    # The opened version, then the newest (a pause longer than PAUSE in reading the burst,
    # on a starved machine, may add one or two in between; each version in turn was 41).
    assert versions[0] == 1 and versions[-1] == burst + 1 and len(versions) <= 4, versions
    assert actions, "the arm's findings have fixes"
    for action in actions:
        [change] = action["edit"]["documentChanges"]
        assert change["textDocument"]["version"] == burst + 1


# --- TCP: a token, one client, the declared folders ---------------------------------------

def free_port() -> int:
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return probe.getsockname()[1]


async def tcp_server(port: int, env: dict[str, str] = ENV) -> asyncio.subprocess.Process:
    process = await asyncio.create_subprocess_exec(
        sys.executable, "-m", "txtool", "lsp", "--tcp", f"127.0.0.1:{port}", cwd=str(ROOT),
        env=env, stdout=asyncio.subprocess.PIPE, stderr=asyncio.subprocess.PIPE)
    STARTED.append(process)
    return process


async def connect(port: int) -> Raw:
    for _ in range(200):
        try:
            reader, writer = await asyncio.open_connection("127.0.0.1", port)
            return Raw(reader, writer)
        except OSError:
            await asyncio.sleep(0.1)
    raise AssertionError("the server never listened")


@pytest.mark.parametrize("token", [None, "", "hostile-test-token-012345678", TOKEN + "x"])
def test_a_client_without_the_token_is_not_served(repository: Path, token: str | None):
    port = free_port()

    async def run() -> tuple[Any, int, str]:
        server = await tcp_server(port)
        try:
            intruder = await connect(port)
            options = {"token": token} if token is not None else None
            intruder.send({"jsonrpc": "2.0", "id": 1, "method": "initialize", "params": {
                "processId": None, "capabilities": {}, "rootUri": repository.as_uri(),
                "initializationOptions": options}})
            refused = await intruder.message()
            intruder.close()
            # The editor, told the token, is served after it.
            editor = await connect(port)
            result = await editor.initialize(repository)
            await editor.leave()
            return (refused, result["serverInfo"]["name"], *await ended(server))
        finally:
            if server.returncode is None:
                server.kill()

    assert session(run()) == (None, "txtool", 0, "")


def test_a_second_client_is_not_served_while_one_is(repository: Path):
    port = free_port()

    async def run() -> tuple[Any, list[Any]]:
        server = await tcp_server(port)
        try:
            editor = await connect(port)
            await editor.initialize(repository)
            second = await connect(port)
            second.send({"jsonrpc": "2.0", "id": 1, "method": "initialize", "params": {
                "processId": None, "capabilities": {}, "rootUri": None,
                "initializationOptions": {"token": TOKEN}}})
            refused = await second.message()
            second.close()
            uri = editor.open(repository / "arm.urdf", ARM)
            published = await editor.published(uri)
            await editor.leave()
            await ended(server)
            return refused, published
        finally:
            if server.returncode is None:
                server.kill()

    refused, published = session(run())
    assert refused is None and published and published[0]["diagnostics"]


def test_over_tcp_a_document_outside_the_declared_folders_is_not_served(tmp_path: Path):
    inside, outside = tmp_path / "repo", tmp_path / "elsewhere"
    for folder in (inside, outside):
        folder.mkdir()
        (folder / ".git").mkdir()
    (outside / "secret.txt").write_text("not for the client\n")
    made_up = ARM.replace('<robot name="arm">', '<robot name="arm" '
                          'xmlns:xacro="http://www.ros.org/wiki/xacro">'
                          '<xacro:include filename="secret.txt"/>')
    port = free_port()

    async def run() -> tuple[list[Any], list[Any], Any]:
        server = await tcp_server(port)
        try:
            editor = await connect(port)
            await editor.initialize(inside)
            far = editor.open(outside / "arm.urdf.xacro", made_up)
            near = editor.open(inside / "arm.urdf", ARM)
            hover = await editor.request("textDocument/hover", {
                "textDocument": {"uri": far}, "position": {"line": 1, "character": 3}})
            result = (await editor.published(far), await editor.published(near), hover)
            await editor.leave()
            await ended(server)
            return result
        finally:
            if server.returncode is None:
                server.kill()

    far, near, hover = session(run())
    assert (far, hover) == ([], None) and near and near[0]["diagnostics"]


def test_without_a_token_given_one_is_made_and_said_once_listening(repository: Path):
    port = free_port()
    env = {k: v for k, v in ENV.items() if k != "TXTOOL_LSP_TOKEN"}

    async def run() -> tuple[str, Any]:
        server = await tcp_server(port, env)
        try:
            assert server.stderr is not None
            line = (await asyncio.wait_for(server.stderr.readline(), WAIT)).decode()
            editor = await connect(port)
            token = line.rsplit(" ", 1)[-1].strip()
            result = await editor.initialize(repository, token)
            await editor.leave()
            await asyncio.wait_for(server.wait(), WAIT)
            return line, result
        finally:
            if server.returncode is None:
                server.kill()

    line, result = session(run())
    assert line.startswith("txtool lsp: the client sends initializationOptions.token = ")
    assert len(line.rsplit(" ", 1)[-1].strip()) >= 32 and result["serverInfo"]["name"]
