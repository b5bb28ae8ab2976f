"""The participant's link to one live trial: their current connection, the checks on their messages, and the
signals the game loop waits on (connected, woken, answered)."""

from __future__ import annotations

import asyncio

from server.game.budget import EventBudget
from server.game.connection import Connection
from server.protocol.inbound import Inbound
from server.protocol.server import Error, ServerMessage

MAX_LOGGED_ERRORS = 50
"""Rejected messages logged as ``error`` events per trial (the rest are answered but not logged)."""


class ParticipantLink:
    def __init__(self, max_message_bytes: int) -> None:
        self.max_message_bytes = max_message_bytes
        self.connection: Connection | None = None
        self.inbound = Inbound(max_message_bytes)
        """Checks each client frame (size, shape, sequence) and knows the last accepted ``seq``."""
        self.budget = EventBudget()
        """How many messages of each kind may be applied now (``server.game.budget``)."""
        self.connected = asyncio.Event()
        self.wake = asyncio.Event()
        """Set when the loop waiting for the participant should look again (a message, a connection change)."""
        self.answered = asyncio.Event()
        """Set by every accepted client message: a ``fast`` pilot trial steps once its participant answered."""
        self.errors_logged = 0

    def replace(self, conn: Connection) -> Connection | None:
        """Make ``conn`` the connection; the one it replaces (if any) is told so and closed, and returned."""
        replaced = self.connection
        if replaced is not None:
            replaced.send(Error(code="replaced", message="this trial was opened in another window"))
            replaced.begin_close(4000)
        self.connection = conn
        self.inbound = Inbound(self.max_message_bytes)
        return replaced

    def drop(self, conn: Connection) -> bool:
        """Forget ``conn`` if it is the current connection; whether it was."""
        if conn is not self.connection:
            return False
        self.connection = None
        self.connected.clear()
        return True

    def send(self, message: ServerMessage) -> None:
        """Send ``message`` if the participant is connected."""
        if self.connection is not None:
            self.connection.send(message)

    def may_log_error(self) -> bool:
        """Whether another rejected message may be logged (at most ``MAX_LOGGED_ERRORS``); counts it."""
        if self.errors_logged >= MAX_LOGGED_ERRORS:
            return False
        self.errors_logged += 1
        return True
