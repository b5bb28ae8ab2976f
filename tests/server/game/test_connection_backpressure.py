"""The connection's inbound backpressure: the route stops reading a client's frames while half the
outbound queue waits, so a burst of frames is answered, not cut off; only a client that stops reading
altogether is disconnected (close 1013)."""

from __future__ import annotations

import asyncio

from server.game.connection import MAX_QUEUE, Connection, ConnState
from server.protocol.server import Pong


class SlowSocket:
    """A websocket whose sends complete only when the test lets them through."""

    def __init__(self) -> None:
        self.sent: list[str] = []
        self.gate = asyncio.Event()
        self.closed_with: int | None = None

    async def send_text(self, text: str) -> None:
        await self.gate.wait()
        self.sent.append(text)

    async def close(self, code: int = 1000) -> None:
        self.closed_with = code


def pong(i: int) -> Pong:
    return Pong(ack=i, client_time=float(i), server_time=0.0)


def test_reading_pauses_while_half_the_queue_waits_and_resumes_when_it_drains() -> None:
    async def scenario() -> tuple[bool, bool, int, int | None]:
        socket = SlowSocket()
        conn = Connection(socket)
        conn.open()
        for i in range(MAX_QUEUE // 2 + 2):  # one goes in flight, the rest wait
            assert conn.send(pong(i))
        await asyncio.sleep(0)
        paused = not await _returns_soon(conn.room())
        socket.gate.set()
        resumed = await _returns_soon(conn.room())
        await asyncio.sleep(0.05)
        conn.begin_close()
        await asyncio.wait_for(conn.wait_closed(), 2)
        return paused, resumed, len(socket.sent), socket.closed_with

    paused, resumed, sent, code = asyncio.run(scenario())
    assert paused and resumed
    assert sent == MAX_QUEUE // 2 + 2 and code == 1000, "every queued reply goes out before the close"


def test_a_client_that_stops_reading_is_disconnected_and_a_waiting_reader_wakes() -> None:
    async def scenario() -> tuple[bool, int, ConnState, int | None]:
        socket = SlowSocket()
        conn = Connection(socket)
        conn.open()
        for i in range(MAX_QUEUE // 2 + 2):
            conn.send(pong(i))
        await asyncio.sleep(0)
        waiting = asyncio.ensure_future(conn.room())
        accepted = sum(conn.send(pong(i)) for i in range(MAX_QUEUE))
        woke = await _returns_soon(waiting)
        await asyncio.wait_for(conn.wait_closed(), 2)
        return woke, accepted, conn.state, socket.closed_with

    woke, accepted, state, code = asyncio.run(scenario())
    assert woke, "a reader paused for room must not hang once the connection closes"
    assert accepted < MAX_QUEUE and state is ConnState.CLOSED and code == 1013


async def _returns_soon(awaitable: object, within: float = 0.2) -> bool:
    try:
        await asyncio.wait_for(awaitable, within)  # type: ignore[arg-type]
    except TimeoutError:
        return False
    return True
