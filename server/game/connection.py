"""One participant's websocket, as an explicit state machine with an outbound queue.

States: ``connecting`` → ``open`` (after ``hello``) → ``closing`` → ``closed``, with ``waiting`` between
``connecting`` and ``open`` while the participant waits for a free slot (``server.game.admission``: only
``waiting`` messages are sent then); any state may go to ``closed`` when the socket breaks. Other
transitions raise. Messages are numbered (``seq`` 1, 2, …) when
queued and sent by one sender task, so a slow client never delays the game loop; a client that falls
``MAX_QUEUE`` messages behind is disconnected (it can reconnect and resume).

Backpressure on the way in: the route reads the client's next frame only once :meth:`Connection.room`
says at most ``MAX_QUEUE // 2`` replies wait to be sent. A burst of client frames (a script, or a browser
flushing what it buffered) is then answered frame for frame instead of overflowing the queue, and only a
client that stops *reading* is disconnected.
"""

from __future__ import annotations

import asyncio
import contextlib
import logging
from enum import Enum
from typing import Any

from server.protocol.server import ServerMessage

log = logging.getLogger(__name__)
MAX_QUEUE = 256
CLOSE_TIMEOUT_S = 2.0


class ConnState(str, Enum):
    CONNECTING = "connecting"
    WAITING = "waiting"
    OPEN = "open"
    CLOSING = "closing"
    CLOSED = "closed"


_NEXT: dict[ConnState, frozenset[ConnState]] = {
    ConnState.CONNECTING: frozenset({ConnState.WAITING, ConnState.OPEN, ConnState.CLOSING, ConnState.CLOSED}),
    ConnState.WAITING: frozenset({ConnState.OPEN, ConnState.CLOSING, ConnState.CLOSED}),
    ConnState.OPEN: frozenset({ConnState.CLOSING, ConnState.CLOSED}),
    ConnState.CLOSING: frozenset({ConnState.CLOSED}),
    ConnState.CLOSED: frozenset(),
}


class IllegalConnectionTransition(RuntimeError):
    pass


class Connection:
    def __init__(self, websocket: Any) -> None:
        self.websocket = websocket
        self.state = ConnState.CONNECTING
        self.sent = 0
        self._queue: asyncio.Queue[str | None] = asyncio.Queue(MAX_QUEUE)
        self._sender: asyncio.Task[None] | None = None
        self.closed = asyncio.Event()
        self.close_code = 1000
        self._room = asyncio.Event()
        self._room.set()

    def _move(self, target: ConnState) -> None:
        if target not in _NEXT[self.state]:
            raise IllegalConnectionTransition(f"connection cannot go from {self.state.value} to {target.value}")
        self.state = target
        if target in (ConnState.CLOSING, ConnState.CLOSED):
            self._room.set()
        if target is ConnState.CLOSED:
            self.closed.set()

    def wait(self) -> None:
        """Start sending (``waiting`` messages) before the game opens the connection."""
        self._move(ConnState.WAITING)
        self._sender = asyncio.create_task(self._send_loop(), name="ws-sender")

    def open(self) -> None:
        was_waiting = self.state is ConnState.WAITING
        self._move(ConnState.OPEN)
        if not was_waiting:
            self._sender = asyncio.create_task(self._send_loop(), name="ws-sender")

    @property
    def is_open(self) -> bool:
        return self.state is ConnState.OPEN

    def send(self, message: ServerMessage) -> bool:
        """Number and queue ``message``; ``False`` if the connection is not open (nothing is sent)."""
        if self.state not in (ConnState.OPEN, ConnState.WAITING):
            return False
        self.sent += 1
        message.seq = self.sent
        try:
            self._queue.put_nowait(message.model_dump_json())
            if self._queue.qsize() > MAX_QUEUE // 2:
                self._room.clear()
        except asyncio.QueueFull:
            log.warning("client too slow (%d messages queued); disconnecting it", MAX_QUEUE)
            self.sent -= 1
            self.begin_close(1013)
            return False
        return True

    def begin_close(self, code: int = 1000) -> None:
        """Stop accepting messages; the queued ones are sent, then the socket is closed with ``code``."""
        if self.state in (ConnState.CLOSING, ConnState.CLOSED):
            return
        self.close_code = code
        if self.state is ConnState.CONNECTING:
            self._move(ConnState.CLOSING)
            asyncio.get_running_loop().create_task(self._close_socket())
            return
        self._move(ConnState.CLOSING)
        with contextlib.suppress(asyncio.QueueFull):
            self._queue.put_nowait(None)
        if self._queue.full() and self._sender is not None:
            self._sender.cancel()

    def broken(self) -> None:
        """The socket failed or the client left: nothing more can be sent."""
        if self.state is not ConnState.CLOSED:
            self._move(ConnState.CLOSED)
        if self._sender is not None and self._sender is not asyncio.current_task():
            self._sender.cancel()

    async def _send_loop(self) -> None:
        try:
            while True:
                text = await self._queue.get()
                if self._queue.qsize() <= MAX_QUEUE // 2:
                    self._room.set()
                if text is None:
                    break
                await self.websocket.send_text(text)
        except asyncio.CancelledError:
            pass
        except Exception:
            self.broken()
            return
        await self._close_socket()

    async def _close_socket(self) -> None:
        with contextlib.suppress(Exception):
            await asyncio.wait_for(self.websocket.close(code=self.close_code), CLOSE_TIMEOUT_S)
        if self.state is not ConnState.CLOSED:
            self._move(ConnState.CLOSED)

    async def room(self) -> None:
        """Return once at most ``MAX_QUEUE // 2`` messages wait to be sent (at once when not open)."""
        if self.state is ConnState.OPEN:
            await self._room.wait()

    async def wait_closed(self) -> None:
        await self.closed.wait()
