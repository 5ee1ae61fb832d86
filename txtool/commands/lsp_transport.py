"""How ``txtool lsp`` reads its messages: bounded, and over TCP only from a client that knows
the session's token.

pygls's own loop reads a message of any ``Content-Length`` into memory (a huge one ended the
server) and lines of any length; its TCP server serves whoever connects, last one first.
Here a message over :data:`MAX_MESSAGE` bytes is read past in pieces and refused with one line
on standard error, a header line is cut at :data:`MAX_LINE` bytes, and over TCP a connection
is served only when its first message is ``initialize`` with the token in
``initializationOptions.token`` (one session at a time; anything else is closed unanswered).
"""

from __future__ import annotations

import asyncio
import hmac
import json
import re
import sys
import threading
from collections.abc import Awaitable, Callable
from typing import Any, BinaryIO, Protocol

MAX_MESSAGE = 64 * 1024 * 1024  # bytes of one message (a document at the input limit)
MAX_LINE = 64 * 1024  # bytes of one header line
MAX_FIRST = 1024 * 1024  # bytes of the first message over TCP, read before the token is known
FIRST_WAIT = 10.0  # seconds a TCP client has to send its first message
_CHUNK = 1024 * 1024
_LENGTH = re.compile(rb"Content-Length: *(\d+)\r\n", re.IGNORECASE)


class Reader(Protocol):
    def readline(self) -> Awaitable[bytes]: ...

    def readexactly(self, n: int) -> Awaitable[bytes]: ...


class StdinReader:
    """Standard input read in the server's one reading thread, lines cut at :data:`MAX_LINE`
    (the rest of a longer line comes as further lines, which are no header)."""

    def __init__(self, stdin: BinaryIO, executor: Any) -> None:
        self.stdin = stdin
        self.executor = executor

    def readline(self) -> Awaitable[bytes]:
        return asyncio.get_running_loop().run_in_executor(self.executor, self.stdin.readline,
                                                          MAX_LINE)

    def readexactly(self, n: int) -> Awaitable[bytes]:
        return asyncio.get_running_loop().run_in_executor(self.executor, self.stdin.read, n)


class StreamReader:
    """An asyncio stream: a line over its limit is dropped, an end of stream ends a read."""

    def __init__(self, reader: asyncio.StreamReader, replay: bytes = b"") -> None:
        self.reader = reader
        self.replay = replay  # what was read before (the first message), to be read again

    async def readline(self) -> bytes:
        if self.replay:
            line, found, self.replay = self.replay.partition(b"\n")
            return line + found
        try:
            return await self.reader.readline()
        except ValueError:  # longer than the stream's limit: it was dropped
            return b"(dropped)\r\n"

    async def readexactly(self, n: int) -> bytes:
        if self.replay:
            data, self.replay = self.replay[:n], self.replay[n:]
            if len(data) == n:
                return data
            return data + await self.readexactly(n - len(data))
        try:
            return await self.reader.readexactly(n)
        except asyncio.IncompleteReadError as short:
            return short.partial


async def read_message(reader: Reader, limit: int) -> tuple[bytes | None, int | None]:
    """(body, None) of the next message; (None, length) when its length is over ``limit`` (the
    body is not read); (None, None) at the end of the stream."""
    length = None
    while True:
        header = await reader.readline()
        if not header:
            return None, None
        if length is None and (match := _LENGTH.fullmatch(header)) is not None:
            length = int(match.group(1))
            continue
        if header.strip() or length is None:
            continue  # another header, or a blank line before any length
        if length > limit:
            return None, length
        body = await reader.readexactly(length)
        return (body if len(body) == length else None), None


async def read_past(reader: Reader, length: int) -> bool:
    """Read ``length`` bytes and drop them; False when the stream ends first."""
    while length > 0:
        piece = await reader.readexactly(min(length, _CHUNK))
        if not piece:
            return False
        length -= len(piece)
    return True


async def serve(reader: Reader, protocol: Any, stop: threading.Event,
                on_error: Callable[[Exception, type], Any]) -> None:
    """pygls's message loop, bounded."""
    from pygls.exceptions import JsonRpcException

    while not stop.is_set():
        body, too_long = await read_message(reader, MAX_MESSAGE)
        if too_long is not None:
            if not await read_past(reader, too_long):
                return
            print(f"txtool lsp: a message of {too_long} bytes was refused (at most "
                  f"{MAX_MESSAGE})", file=sys.stderr, flush=True)
            continue
        if body is None:
            return
        try:
            protocol.handle_message(json.loads(body, object_hook=protocol.structure_message))
        except Exception as exc:  # as pygls's loop: a bad message is reported, not fatal
            print(f"txtool lsp: a message was refused: {type(exc).__name__}: {exc}"[:500],
                  file=sys.stderr, flush=True)
            on_error(exc, JsonRpcException)


def authentic(body: bytes | None, token: str) -> bool:
    """Whether ``body`` is an ``initialize`` request carrying ``token``."""
    try:
        message = json.loads(body) if body is not None else None
    except ValueError:
        return False
    if not isinstance(message, dict) or message.get("method") != "initialize":
        return False
    params = message.get("params")
    options = params.get("initializationOptions") if isinstance(params, dict) else None
    given = options.get("token") if isinstance(options, dict) else None
    return isinstance(given, str) and hmac.compare_digest(given.encode(), token.encode())


def frame(body: bytes) -> bytes:
    return b"Content-Length: %d\r\n\r\n%s" % (len(body), body)


async def first_message(reader: asyncio.StreamReader) -> bytes | None:
    """The first message of a TCP client, if it sends one of at most :data:`MAX_FIRST` bytes
    within :data:`FIRST_WAIT` seconds."""
    try:
        body, _ = await asyncio.wait_for(read_message(StreamReader(reader), MAX_FIRST),
                                         FIRST_WAIT)
    except (asyncio.TimeoutError, OSError):
        return None
    return body
