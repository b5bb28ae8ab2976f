"""The lobby: where participants wait for a live-trial slot of this server process (docs/operations.md,
"Admission control"; the slots and the line are :class:`~server.game.admission.Admission`).

- :meth:`Lobby.claim`: a round that is not live yet takes a free slot, or gets a place in line (a trial
  being resumed from the store goes first). Practice with the ``stay`` robot needs no slot: that robot plans
  nothing, and the capacity is the planners' CPU.
- :meth:`Lobby.wait_turn`: while in line the participant's connection gets ``waiting`` messages (place in
  line, expected wait), whenever the line moves and every :data:`WAITING_EVERY_S`; past ``max_wait_s`` the
  participant is screened out (``server_full``). Every wait is an ``admission_wait`` event.
- A participant who reloads the page while waiting keeps their ticket (the new connection takes it over);
  one who leaves gives up their place.
"""

from __future__ import annotations

import asyncio
import logging
import math
import time
from typing import Literal

from server.flow import service
from server.flow.plan import Step
from server.flow.progress import IllegalTransition, Move
from server.game.admission import DEFAULT_MAX_WAIT_S, Admission, Ticket
from server.game.connection import Connection
from server.protocol.server import Waiting
from store import trials
from store.engine import Store
from store.tables import ParticipantRow
from store.types import utcnow
from store.writer import BatchWriter
from study_config.catalog import Catalog

log = logging.getLogger(__name__)

WAITING_EVERY_S = 2.0
"""A waiting participant hears from the server at least this often (the client treats 6 s of silence as a
dropped connection)."""
EXEMPT_ROBOT = "stay"
"""Practice with this robot needs no slot: it plans nothing."""
ETA_STEP_S = 5
Outcome = Literal["admitted", "timeout", "left"]


def exempt(step: Step) -> bool:
    return step.trial_kind == "practice" and step.robot == EXEMPT_ROBOT


class Lobby:
    def __init__(self, catalog: Catalog, store: Store, writer: BatchWriter, admission: Admission,
                 max_wait_s: float = DEFAULT_MAX_WAIT_S) -> None:
        self.catalog, self.store, self.writer = catalog, store, writer
        self.admission = admission
        self.max_wait_s = max_wait_s
        self._tickets: dict[int, Ticket] = {}
        self._waiters: dict[int, Connection] = {}

    async def claim(self, participant_id: int, step: Step) -> Ticket | None:
        """``None`` when the participant may start ``step`` now (exempt, or a slot was free); else their
        place in line (the same one if they already wait, e.g. from a reloaded tab)."""
        if exempt(step) or self.admission.try_enter(participant_id):
            return None
        ticket = self._tickets.get(participant_id)
        if ticket is None or (ticket.granted.is_set() and not self.admission.holds(participant_id)):
            resuming = await asyncio.to_thread(self._running_attempt, participant_id, step)
            ticket = self.admission.enqueue(participant_id, first=resuming)
            self._tickets[participant_id] = ticket
        return ticket

    def _running_attempt(self, participant_id: int, step: Step) -> bool:
        with self.store.transaction() as session:
            row = trials.latest_attempt(session, participant_id, str(step.trial_kind), int(step.index or 0))
            return row is not None and row.status == trials.RUNNING

    async def wait_turn(self, participant: ParticipantRow, ticket: Ticket, conn: Connection) -> bool:
        """Tell ``conn`` its place in line and expected wait until the ticket is granted (``True``), or the
        wait passes ``max_wait_s`` (``False``: the participant is screened out, reason ``server_full``).
        Cancelled when the participant leaves."""
        self._waiters[participant.id] = conn
        first_position = self.admission.position(ticket)
        outcome: Outcome = "left"
        try:
            while not ticket.granted.is_set():
                waited = time.monotonic() - ticket.since
                if waited >= self.max_wait_s:
                    outcome = "timeout"
                    return False
                position = self.admission.position(ticket)
                eta = ETA_STEP_S * math.ceil(self.admission.eta_s(position, self._trial_s(participant)) / ETA_STEP_S)
                conn.send(Waiting(position=position, eta_s=eta))
                ticket.changed.clear()
                await _first_of(ticket, min(WAITING_EVERY_S, self.max_wait_s - waited))
            outcome = "admitted"
            return True
        finally:
            self._settle(participant.id, ticket, conn, outcome)
            self.writer.add_event({
                "participant_id": participant.id, "trial_id": None, "tick": None, "kind": "admission_wait",
                "payload": {"outcome": outcome, "waited_s": round(time.monotonic() - ticket.since, 2),
                            "first_position": first_position, "capacity": self.admission.capacity},
                "created_at": utcnow()})
            if outcome == "timeout":
                await asyncio.to_thread(self._screen_out, participant.id)

    def _settle(self, participant_id: int, ticket: Ticket, conn: Connection, outcome: Outcome) -> None:
        """Forget the waiter; give up the place in line unless admitted or another connection of the same
        participant (a reloaded tab) still waits on the ticket."""
        taken_over = self._waiters.get(participant_id) not in (None, conn)
        if self._waiters.get(participant_id) is conn:
            del self._waiters[participant_id]
        if self._tickets.get(participant_id) is not ticket:
            return
        if outcome == "admitted" or outcome == "timeout" or not taken_over:
            del self._tickets[participant_id]
        if outcome == "timeout" or (outcome == "left" and not taken_over):
            self.admission.leave(ticket)

    def _trial_s(self, participant: ParticipantRow) -> float:
        """A trial's longest length in seconds (``Timing.round_seconds``): the expected slot time before any was
        measured."""
        loaded = self.catalog.get(participant.study_id)
        if loaded is None:
            return 60.0
        return loaded.study.timing.round_seconds(loaded.rules.horizon)

    def _screen_out(self, participant_id: int) -> None:
        try:
            service.move(self.store, participant_id, Move.SERVER_FULL)
        except IllegalTransition:
            log.info("participant %d moved on while waiting for a slot", participant_id)
            return
        log.warning("participant %d waited %.0f s for a free slot and was screened out (server_full)",
                    participant_id, self.max_wait_s)


async def _first_of(ticket: Ticket, timeout: float) -> None:
    """Return when the ticket is granted, the line moves, or ``timeout`` seconds pass."""
    changed = asyncio.ensure_future(ticket.changed.wait())
    granted = asyncio.ensure_future(ticket.granted.wait())
    try:
        await asyncio.wait({changed, granted}, timeout=timeout, return_when=asyncio.FIRST_COMPLETED)
    finally:
        changed.cancel()
        granted.cancel()
