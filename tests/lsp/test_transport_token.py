"""`txtool lsp --tcp` serves only a client whose first message is an ``initialize`` request
carrying the token: every other first message is refused."""

from __future__ import annotations

import json

import pytest

from txtool.commands.lsp_transport import authentic, frame

TOKEN = "s3cret-token"


def initialize(options: object) -> bytes:
    return json.dumps({"jsonrpc": "2.0", "id": 1, "method": "initialize",
                       "params": {"initializationOptions": options}}).encode()


@pytest.mark.parametrize(("body", "served"), [
    (initialize({"token": TOKEN}), True),
    (initialize({"token": TOKEN + "x"}), False),
    (initialize({"token": TOKEN[:-1]}), False),
    (initialize({"token": 42}), False),
    (initialize({}), False),
    (initialize("token"), False),
    (json.dumps({"method": "initialize", "params": []}).encode(), False),
    (json.dumps({"method": "shutdown", "params": {"initializationOptions": {"token": TOKEN}}})
     .encode(), False),
    (json.dumps([1, 2]).encode(), False),
    (b"{not json", False),
    (b"", False),
    (None, False),
])
def test_only_an_initialize_request_with_the_token_is_served(body, served):
    assert authentic(body, TOKEN) is served


def test_a_message_is_framed_by_its_length_in_bytes():
    body = json.dumps({"name": "bras é"}).encode()
    assert frame(body) == b"Content-Length: %d\r\n\r\n" % len(body) + body
