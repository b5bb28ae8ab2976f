"""This server process's side of "one owner per live round" (docs/deploy.md; the lease itself: ``store.lease``).

- **Renewing**: at every store flush the writer renews the lease of each round this process runs, with the
  round's crash-aware clock (:meth:`Ownership.beats`: connected or away since when, the connected seconds that
  ``timing.max_round_seconds`` limits, the wait for the participant running now).
- **Losing**: a flush that finds a lease taken over by another process reports it; the round stops here at once
  (its loop and robot are stopped, nothing more is stored) and its socket, if one is open, is told to go:
  ``error`` ``moved`` (close 4401) when the participant's token changed since (a resume link was used), else
  ``replaced`` (close 4000: a newer connection of the same browser session runs the round elsewhere). The
  registry applies it (:meth:`server.game.registry.GameRegistry.attach` also checks the lease of a round it
  finds live here before attaching a connection to it).
- **Restarting**: at start, the rounds nobody holds count the participant as away from now
  (``store.lease.restart_count``): the reconnect grace window starts again after an outage. Again one lease
  lifetime later, for the rounds whose holder died just before this start.
- **Shutting down**: the leases are released with their last clock (``store.lease.release``).
"""

from __future__ import annotations

import asyncio
import logging
import os
import socket
from collections.abc import Callable, Iterable
from datetime import datetime

from server.game.connection import Connection
from server.game.live import LiveGame
from server.protocol.server import Error
from store import lease
from store.engine import Store
from store.tables import ParticipantRow, TrialRow
from store.types import utcnow

log = logging.getLogger(__name__)


def process_name() -> str:
    """``host:pid`` of this server process, stored with each trial start and resume and as the lease's holder:
    which process ran a trial, and which one took it over (docs/operations.md §4)."""
    return f"{socket.gethostname()}:{os.getpid()}"


class Ownership:
    def __init__(self, store: Store) -> None:
        self.store = store
        self.name = process_name()
        self._away: dict[int, datetime] = {}
        """Trial id → when its participant's connection dropped (the round is paused here)."""
        self._tokens: dict[int, str] = {}
        """Trial id → the token hash of the participant whose connection is attached."""

    # -- the round's connection -------------------------------------------------------------------------

    def connected(self, trial_id: int, token_hash: str) -> None:
        self._away.pop(trial_id, None)
        self._tokens[trial_id] = token_hash

    def away(self, trial_id: int) -> None:
        self._away[trial_id] = utcnow()

    def forget(self, trial_id: int) -> None:
        self._away.pop(trial_id, None)
        self._tokens.pop(trial_id, None)

    # -- renewing ---------------------------------------------------------------------------------------

    def beats(self, games: Iterable[LiveGame]) -> list[lease.Beat]:
        """The lease renewal of each round run here, as it stands now (call on the event loop)."""
        out = []
        for game in games:
            if game.finished:
                continue
            waiting = game.pacing.waiting_since
            clock = game.pacing.clock
            away = None if game.connection is not None else self._away.setdefault(game.meta.trial_id, utcnow())
            out.append(lease.Beat(game.meta.trial_id, game.meta.epoch, away, game.pacing.times.elapsed(),
                                  None if waiting is None else max(clock.now() - waiting, 0.0)))
        return out

    def holds(self, game: LiveGame) -> bool:
        """Whether this process still holds the round's lease (blocking: call it in a thread)."""
        with self.store.transaction() as session:
            row = session.get(TrialRow, game.meta.trial_id)
            return row is not None and row.lease_epoch == game.meta.epoch

    # -- losing -----------------------------------------------------------------------------------------

    async def stop(self, game: LiveGame) -> None:
        """Stop a round whose lease another process took: its loop and robot stop, nothing more is stored, its
        socket is told to go (the registry forgets it)."""
        log.warning("trial %d (participant %s): another server process took the round over; it stops here "
                    "(lease epoch %d is no longer the round's)", game.meta.trial_id, game.meta.participant,
                    game.meta.epoch)
        await self.tell_to_go(game)
        await game.suspend()
        self.forget(game.meta.trial_id)

    async def tell_to_go(self, game: LiveGame) -> None:
        """Tell the round's socket (if one is open here) that the round runs elsewhere now, and close it."""
        conn: Connection | None = game.connection
        if conn is None:
            return
        token_hash = self._tokens.get(game.meta.trial_id)
        changed = await asyncio.to_thread(self._token_changed, game.meta.participant_id, token_hash)
        if changed:
            conn.send(Error(code="moved", message="this session continues on another device"))
            conn.begin_close(4401)
        else:
            conn.send(Error(code="replaced", message="this trial was opened in another window"))
            conn.begin_close(4000)

    def _token_changed(self, participant_id: int, token_hash: str | None) -> bool:
        with self.store.transaction() as session:
            row = session.get(ParticipantRow, participant_id)
            return row is None or token_hash is None or row.token_hash != token_hash

    # -- starting and stopping ----------------------------------------------------------------------------

    async def restart(self, study_ids: list[str], live: Callable[[], frozenset[int]], after_s: float = 0.0) -> None:
        """After ``after_s``: the rounds nobody holds start their participants' grace window again (``live``: the
        rounds this process runs then)."""
        await asyncio.sleep(after_s)
        count = await asyncio.to_thread(self.restart_count, study_ids, live())
        if count:
            log.info("%d round(s) left by a stopped server process: their participants' grace window starts again",
                     count)

    def restart_count(self, study_ids: list[str], live: frozenset[int] = frozenset()) -> int:
        """The rounds nobody holds count their participant as away from now (blocking). A lease held by a
        process of this machine that no longer runs (this process's previous run, killed) is ended first: its
        holder is known to be gone before the lease runs out. ``live``: the rounds this process runs."""
        now = utcnow()
        with self.store.transaction() as session:
            gone = [trial_id for owner, trial_ids in lease.holders(session, study_ids, now).items()
                    if self._gone(owner) for trial_id in trial_ids if trial_id not in live]
            lease.expire(session, gone, now)
            return lease.restart_count(session, study_ids, now)

    def _gone(self, owner: str) -> bool:
        """Whether the process named ``owner`` (``host:pid``) is known not to run: it is on this machine and
        either has this process's name (a previous run with the same pid, as in a restarted container) or no
        process has its pid. (A process of another machine is judged by its lease's expiry alone.)"""
        host, _, pid = owner.rpartition(":")
        if host != socket.gethostname() or not pid.isdigit():
            return False
        if owner == self.name:
            return True
        try:
            os.kill(int(pid), 0)
        except ProcessLookupError:
            return True
        except PermissionError:
            return False
        return False

    def release(self, beats: list[lease.Beat]) -> None:
        """Give up the leases of ``beats`` with their last clock (blocking; a shutdown)."""
        with self.store.transaction() as session:
            lease.release(session, beats)
