"""The participant's link to one live trial: their current connection, every frame they send checked and answered,
and the signals the game loop waits on (connected, woken, answered).

A newer connection replaces an older one (told ``replaced`` and closed). Every accepted message is answered by
``ack`` (``pong`` for heartbeats), every rejected one by a typed ``error`` with nothing changed; at most
``MAX_LOGGED_ERRORS`` rejections a trial are stored as ``error`` events. Messages past the trial's event budget are
refused as ``rate_limited`` (``server.game.budget``; a simulated pilot participant is not limited) and their counts
stored as ``events_dropped``; connects past it are not logged, nor then their disconnects. What an accepted message
does to the participant's cook is the choices' job (``server.game.choices``).
"""

from __future__ import annotations

import asyncio
import time
from collections.abc import Callable

from server.game.budget import EventBudget
from server.game.connection import Connection
from server.game.records import EventLog
from server.protocol.client import AnyClientMessage, Heartbeat
from server.protocol.inbound import Inbound, ProtocolError
from server.protocol.server import Ack, Error, Hello, Pong, ServerMessage, State

MAX_LOGGED_ERRORS = 50
"""Rejected messages logged as ``error`` events per trial (the rest are answered but not logged)."""


class ParticipantLink:
    def __init__(self, max_message_bytes: int, log: EventLog, *, limited: bool = True,
                 budget: EventBudget | None = None, wall_ms: Callable[[], float] = lambda: time.time() * 1000) -> None:
        """``limited``: messages are held to the event budget (not a simulated pilot participant's); ``wall_ms``:
        the server time a ``pong`` carries."""
        self.max_message_bytes, self.log, self.limited, self.wall_ms = max_message_bytes, log, limited, wall_ms
        self.connection: Connection | None = None
        self.inbound = Inbound(max_message_bytes)
        """Checks each client frame (size, shape, sequence) and knows the last accepted ``seq``."""
        self.budget = budget or EventBudget()
        """How many messages of each kind may be applied now (``server.game.budget``)."""
        self.connected = asyncio.Event()
        self.wake = asyncio.Event()
        """Set when the loop waiting for the participant should look again (a message, a connection change)."""
        self.answered = asyncio.Event()
        """Set by every accepted client message: a ``fast`` pilot trial steps once its participant answered."""
        self.errors_logged = 0
        self._connect_logged = False

    def open(self, conn: Connection, hello: Hello, state: State, tick: int) -> Connection | None:
        """Make ``conn`` the connection and greet it (``hello``, then ``state``); the one it replaces (if any) is
        told so, closed and returned."""
        replaced = self.connection
        if replaced is not None:
            replaced.send(Error(code="replaced", message="this trial was opened in another window"))
            replaced.begin_close(4000)
        self.connection = conn
        self.inbound = Inbound(self.max_message_bytes)
        conn.open()
        conn.send(hello)
        conn.send(state)
        # A reconnection flood is counted like a message flood; a disconnect is logged when its connect was.
        self._connect_logged = self.budget.take("connect")
        if self._connect_logged:
            self.log("connect", {"replaced": replaced is not None, "resumed_at": tick})
        self.connected.set()
        self.wake.set()
        return replaced

    def drop(self, conn: Connection) -> bool:
        """Forget ``conn`` if it is the current connection (logged, with the refused messages' counts); whether
        it was."""
        if conn is not self.connection:
            return False
        self.connection = None
        self.connected.clear()
        if self._connect_logged:
            self.log("disconnect", {})
        self.store_drops(force=True)
        self.wake.set()
        return True

    def receive(self, conn: Connection, text: str | None, data: bytes | None, *, playing: bool,
                apply: Callable[[AnyClientMessage], Ack]) -> None:
        """Check one frame of ``conn``'s and answer it: a heartbeat by ``pong``, any other message by ``apply``'s
        ``ack``; a rejected one (``apply`` may reject too, raising :class:`ProtocolError`) by a typed ``error``,
        nothing changed. Frames of a replaced or closing connection are ignored; once the trial is over
        (``playing`` false), every message is refused as ``not_playing``."""
        if conn is not self.connection or not conn.is_open:
            return
        try:
            message = self.inbound.check(text, data)
            if not playing:
                raise ProtocolError("not_playing", "the trial is over", message.seq)
            if self.limited and not isinstance(message, Heartbeat) and not self.budget.take(message.type):
                self.store_drops()
                raise ProtocolError("rate_limited", "too many messages at once; this one was not applied",
                                    message.seq)
            if isinstance(message, Heartbeat):
                self.inbound.accept(message.seq)
                conn.send(Pong(ack=message.seq, client_time=message.client_time, server_time=self.wall_ms()))
                self.answered.set()
                return
            ack = apply(message)
        except ProtocolError as exc:
            conn.send(Error(code=exc.code, message=exc.message, ref=exc.ref))  # type: ignore[arg-type]
            if exc.code != "rate_limited" and self.may_log_error():
                self.log("error", {"code": exc.code, "ref": exc.ref})
            return
        self.inbound.accept(message.seq)
        conn.send(ack)
        self.answered.set()
        self.wake.set()

    def send(self, message: ServerMessage) -> None:
        """Send ``message`` if the participant is connected."""
        if self.connection is not None:
            self.connection.send(message)

    def close(self, code: int, last: ServerMessage | None = None) -> None:
        """Close the participant's connection, if any, with ``code`` (after sending ``last``)."""
        if self.connection is not None:
            if last is not None:
                self.connection.send(last)
            self.connection.begin_close(code)

    def store_drops(self, force: bool = False) -> None:
        """Store the refused messages' counts as one ``events_dropped`` row (:mod:`server.game.budget`)."""
        summary = self.budget.summary(force)
        if summary is not None:
            self.log("events_dropped", summary)

    def may_log_error(self) -> bool:
        """Whether another rejected message may be logged (at most ``MAX_LOGGED_ERRORS``); counts it."""
        if self.errors_logged >= MAX_LOGGED_ERRORS:
            return False
        self.errors_logged += 1
        return True
