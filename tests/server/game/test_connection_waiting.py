"""The connection's ``waiting`` state: messages go out numbered before the game opens it, and opening it
then keeps the same numbering and sender; a waiting connection cannot go back."""

from __future__ import annotations

import asyncio
from typing import Any

import pytest
from steakhouse_live_parts import Socket

from server.game.connection import Connection, ConnState, IllegalConnectionTransition
from server.protocol.server import Pong, Waiting


def test_waiting_messages_come_first_and_the_numbering_goes_on_after_opening() -> None:
    async def scenario() -> list[dict[str, Any]]:
        socket = Socket()
        conn = Connection(socket)
        assert not conn.send(Waiting(position=1, eta_s=5))  # not yet started: nothing is sent
        conn.wait()
        assert conn.send(Waiting(position=2, eta_s=10)) and conn.send(Waiting(position=1, eta_s=5))
        assert not conn.is_open
        conn.open()
        assert conn.is_open and conn.send(Pong(ack=1, client_time=0.0, server_time=0.0))
        conn.begin_close(1000)
        await asyncio.wait_for(conn.wait_closed(), 2)
        return socket.sent

    sent = asyncio.run(scenario())
    assert [(m["type"], m["seq"]) for m in sent] == [("waiting", 1), ("waiting", 2), ("pong", 3)]


def test_a_connection_cannot_wait_once_open() -> None:
    async def scenario() -> None:
        conn = Connection(Socket())
        conn.open()
        assert conn.state is ConnState.OPEN
        with pytest.raises(IllegalConnectionTransition):
            conn.wait()
        conn.broken()

    asyncio.run(scenario())
