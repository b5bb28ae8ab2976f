"""The registry of live trials in this server process, created at start-up (no module-level state).

- :meth:`GameRegistry.attach` connects a participant to the trial of their current step: the live one if
  this process has it, else one prepared from the store (new, resumed or abandoned; see
  :mod:`server.game.resume`), with its robot planner opened in the pool.
- :meth:`GameRegistry.detach` pauses the trial and starts the reconnect grace timer. When it fires with
  nobody back: ``abandon`` ends the trial as abandoned and moves the participant on; ``resume`` and
  ``restart`` unload the trial, which stays ``running`` in the store until the participant returns.
- :meth:`GameRegistry.claim` comes first: a trial that is not live here yet needs a slot; when none is
  free the participant waits in the :class:`~server.game.lobby.Lobby` (docs/operations.md, "Admission
  control"). A slot is freed when its trial leaves this process (ended, suspended or unloaded).
- One owner per round (docs/deploy.md): starting or resuming a round takes its lease in the store
  (:mod:`server.game.resume`); every store flush renews the leases held here and reports those another process
  took over, whose rounds stop here at once (:mod:`server.game.ownership`).
- A periodic sweep keeps connected trials' ``last_active_at`` fresh (other server processes judge
  staleness by it; flushed ticks refresh it too, but on the paper's clock a thinking participant makes no
  tick), at least twice per reconnect grace window (:meth:`GameRegistry.touch_interval`), and abandons trials
  left running by a crash (``abandon`` studies only) once they have been idle longer than both the grace window
  and three sweep intervals.
"""

from __future__ import annotations

import asyncio
import dataclasses
import logging
import math
from typing import Any

from server.flow.progress import Phase
from server.flow.service import progress_of
from server.game.admission import Admission, Ticket
from server.game.connection import Connection
from server.game.health import RobotHealth
from server.game.live import GameDeps, LiveGame
from server.game.lobby import Lobby
from server.game.ownership import Ownership
from server.game.restore import trial_engine, trial_meta
from server.game.resume import Prepared, StepPassed, abandon_stale, prepare_trial
from server.protocol.server import Error
from store import lease, trials
from store.tables import ParticipantRow
from store.types import utcnow
from study_config.catalog import Catalog, LoadedStudy

log = logging.getLogger(__name__)


class NoTrial(Exception):
    """The participant's current step is not a trial."""

    def __init__(self, phase: Phase) -> None:
        super().__init__(f"the participant is in state {phase.value}, not in a trial")
        self.phase = phase


class TrialAbandoned(Exception):
    """The trial was abandoned when the participant came back after the grace window."""

    def __init__(self, prepared: Prepared) -> None:
        super().__init__("the trial was abandoned after the reconnect grace window")
        self.prepared = prepared


UNLIMITED = 1_000_000
MIN_TOUCH_S = 1.0
"""The shortest interval at which the connected trials' stored activity is refreshed (``touch_interval``)."""


class GameRegistry:
    def __init__(self, catalog: Catalog, deps: GameDeps, sweep_interval: float, lobby: Lobby | None = None) -> None:
        self.catalog = catalog
        self.lobby = lobby or Lobby(catalog, deps.store, deps.writer, Admission(UNLIMITED))
        """Tests and tools that build a registry themselves get no cap (``UNLIMITED`` slots)."""
        self.deps = GameDeps(deps.store, deps.writer, deps.pool, deps.deadline_fraction, deps.max_message_bytes,
                             on_end=self._ended, clock=deps.clock)
        self.sweep_interval = sweep_interval
        self.games: dict[int, LiveGame] = {}
        self._by_participant: dict[int, LiveGame] = {}
        self._locks: dict[int, asyncio.Lock] = {}
        self._timers: dict[int, asyncio.TimerHandle] = {}
        self._background: set[asyncio.Task[Any]] = set()
        self._sweeper: asyncio.Task[None] | None = None
        self.ownership = Ownership(deps.store)

    # -- lifecycle ------------------------------------------------------------------------------------

    async def start(self) -> None:
        writer = self.deps.writer
        writer.beats = lambda: self.ownership.beats(self.games.values())
        writer.on_stale = self._stale
        studies = list(self.catalog.studies)
        await self.ownership.restart(studies, lambda: frozenset(self.games))
        self._spawn(self.ownership.restart(studies, lambda: frozenset(self.games), lease.LEASE_TTL_S))
        await self.sweep()
        self._sweeper = asyncio.create_task(self._sweep_forever(), name="trial-sweeper")

    async def shutdown(self) -> None:
        """Suspend every live trial (they stay ``running`` and resume from the store)."""
        if self._sweeper is not None:
            self._sweeper.cancel()
        for handle in self._timers.values():
            handle.cancel()
        games = list(self.games.values())
        beats = self.ownership.beats(games)
        for game in games:
            await game.suspend()
        if beats:
            await asyncio.to_thread(self.ownership.release, beats)
        self.games.clear()
        self._by_participant.clear()
        for task in list(self._background):
            task.cancel()
        if games:
            await asyncio.to_thread(self._touch, [g.meta.trial_id for g in games])

    def _touch(self, trial_ids: list[int]) -> None:
        with self.deps.store.transaction() as session:
            trials.touch_many(session, trial_ids, utcnow())

    # -- admission ------------------------------------------------------------------------------------

    async def claim(self, participant: ParticipantRow) -> Ticket | None:
        """``None`` when the participant may start now (their trial is live here, or the lobby let them in);
        else their place in line (:class:`~server.game.lobby.Lobby`)."""
        progress = progress_of(participant)
        if progress.phase not in (Phase.PRACTICE, Phase.TRIAL):
            return None
        step = progress.current
        game = self._by_participant.get(participant.id)
        if game is not None and not game.finished and (game.meta.kind, game.meta.index) == (
                step.trial_kind, step.index):
            return None
        return await self.lobby.claim(participant.id, step)

    def release(self, participant_id: int) -> None:
        """Free the participant's slot unless their trial is live here (a failed start, a refusal)."""
        if participant_id not in self._by_participant:
            self.lobby.admission.release(participant_id)

    # -- participants ---------------------------------------------------------------------------------

    async def attach(self, participant: ParticipantRow, conn: Connection) -> LiveGame:
        loaded = self.catalog.get(participant.study_id)
        progress = progress_of(participant)
        if loaded is None or progress.phase not in (Phase.PRACTICE, Phase.TRIAL):
            raise NoTrial(progress.phase)
        step = progress.current
        lock = self._locks.setdefault(participant.id, asyncio.Lock())
        async with lock:
            game = self._by_participant.get(participant.id)
            if game is not None and (game.meta.kind, game.meta.index) == (step.trial_kind, step.index):
                if not game.finished and await asyncio.to_thread(self.ownership.holds, game):
                    self._cancel_timer(game)
                    self.ownership.connected(game.meta.trial_id, participant.token_hash)
                    game.attach(conn)
                    return game
                if not game.finished:  # another process took the round over: this copy is stale
                    await self._let_go(game, keep_slot=True)
                else:
                    # The trial is ending here (its last ticks and its end are being stored): resuming it from the
                    # store now would replay those ticks. Once stored, the participant has moved on (NoTrial below).
                    await game.stored.wait()
            try:
                prepared = await asyncio.to_thread(prepare_trial, self.deps.store, loaded, participant.id, step,
                                                   self.ownership.name)
            except StepPassed as passed:  # the trial ended after the participant's row was read
                raise NoTrial(passed.progress.phase) from None
            if prepared.outcome == "abandoned":
                raise TrialAbandoned(prepared)
            game = self._build(loaded, participant, prepared)
            await self.deps.pool.open(game.meta.trial_id, loaded.planner(game.meta.robot), game.engine.layout,
                                      game.engine.rules, loaded.robot_setup(game.meta.robot, game.engine.angle),
                                      game.engine.world, game.engine.kb)
            self.games[game.meta.trial_id] = game
            self._by_participant[participant.id] = game
            game.event("trial_start" if prepared.outcome == "new" else "resume",
                       {"attempt": game.meta.attempt, "tick": game.engine.tick, "seed": game.meta.seed,
                        "process": self.ownership.name, "epoch": prepared.epoch,
                        "previous_process": prepared.previous_owner})
            game.start()
            self.ownership.connected(game.meta.trial_id, participant.token_hash)
            game.attach(conn)
            return game

    def _stale(self, stale: set[lease.Key]) -> None:
        """The store found these leases taken over by another process (at a flush): stop those rounds here."""
        for trial_id, epoch in stale:
            game = self.games.get(trial_id)
            if game is not None and game.meta.epoch == epoch and not game.finished:
                self._spawn(self._lost(game))

    async def _lost(self, game: LiveGame) -> None:
        async with self._locks.setdefault(game.meta.participant_id, asyncio.Lock()):
            if self.games.get(game.meta.trial_id) is not game or game.finished:
                return
            await self._let_go(game)

    async def _let_go(self, game: LiveGame, keep_slot: bool = False) -> None:
        """Stop a round another process took over (its lease is gone): no more steps or rows here, its socket told
        to go, its slot freed (unless ``keep_slot``: the participant's new connection takes it over here)."""
        await self.ownership.stop(game)
        self._cancel_timer(game)
        if self.games.get(game.meta.trial_id) is game:
            del self.games[game.meta.trial_id]
        if self._by_participant.get(game.meta.participant_id) is game:
            del self._by_participant[game.meta.participant_id]
            if not keep_slot:
                self.lobby.admission.release(game.meta.participant_id)

    def revoke(self, participant_id: int) -> bool:
        """The participant's token was replaced (their resume link was used on a new device): the old browser's
        game socket gets ``error: moved`` and is closed (4401) now, not at its next reconnect. Whether one was
        open in this process."""
        game = self._by_participant.get(participant_id)
        conn = game.connection if game is not None else None
        if conn is None:
            return False
        conn.send(Error(code="moved", message="this session continues on another device"))
        conn.begin_close(4401)
        return True

    def _build(self, loaded: LoadedStudy, participant: ParticipantRow, prepared: Prepared) -> LiveGame:
        row, study = prepared.trial, loaded.study
        health = RobotHealth(study.validity.max_missed_decisions_pct, loaded.rules.horizon, prepared.decisions,
                             prepared.missed, row.invalid_reason, failed=prepared.failed,
                             max_flickers=study.validity.max_robot_flickers)
        last = prepared.last_tick
        meta = dataclasses.replace(trial_meta(loaded, participant, row), epoch=prepared.epoch)
        return LiveGame(meta, loaded, trial_engine(loaded, row, last), self.deps,
                        resumed=prepared.outcome == "resume", health=health, round_seconds=prepared.round_seconds)

    def detach(self, game: LiveGame, conn: Connection) -> None:
        if not game.detach(conn) or game.finished:
            return
        grace = game.loaded.study.reconnect.grace_seconds
        self.ownership.away(game.meta.trial_id)
        self._cancel_timer(game)
        loop = asyncio.get_running_loop()
        self._timers[game.meta.trial_id] = loop.call_later(grace, lambda: self._spawn(self._expire(game)))
        self._spawn(asyncio.to_thread(self._touch, [game.meta.trial_id]))

    def _spawn(self, coroutine: Any) -> None:
        task = asyncio.ensure_future(coroutine)
        self._background.add(task)
        task.add_done_callback(self._done)

    def _done(self, task: asyncio.Task[Any]) -> None:
        self._background.discard(task)
        if not task.cancelled() and task.exception() is not None:
            log.error("background task failed", exc_info=task.exception())

    async def _expire(self, game: LiveGame) -> None:
        """The grace window passed: apply the study's policy unless the participant came back (serialised
        with :meth:`attach` by the participant's lock)."""
        self._timers.pop(game.meta.trial_id, None)
        async with self._locks.setdefault(game.meta.participant_id, asyncio.Lock()):
            if game.connection is not None or game.finished:
                return
            if game.loaded.study.reconnect.after_grace == "abandon":
                await game.end("abandoned", "grace_expired")
                return
            beats = self.ownership.beats([game])
            await game.suspend()
            await self.deps.writer.flush()
            await asyncio.to_thread(self.ownership.release, beats)
            self._ended(game)

    def _cancel_timer(self, game: LiveGame) -> None:
        handle = self._timers.pop(game.meta.trial_id, None)
        if handle is not None:
            handle.cancel()

    def _ended(self, game: LiveGame) -> None:
        self._cancel_timer(game)
        self.ownership.forget(game.meta.trial_id)
        if self.games.get(game.meta.trial_id) is game:
            del self.games[game.meta.trial_id]
        if self._by_participant.get(game.meta.participant_id) is game:
            del self._by_participant[game.meta.participant_id]
            self.lobby.admission.release(game.meta.participant_id)

    def live(self) -> list[LiveGame]:
        return sorted(self.games.values(), key=lambda g: g.meta.trial_id)

    def connected(self) -> frozenset[int]:
        """The trials a participant is connected to in this process now (call it on the event loop)."""
        return frozenset(tid for tid, g in self.games.items() if g.connection is not None)

    # -- sweeping -------------------------------------------------------------------------------------

    def touch_interval(self) -> float:
        """How often the stored last activity of the connected trials is refreshed: every sweep, and at least twice
        per the shortest reconnect grace window served (for that, never more often than :data:`MIN_TOUCH_S`).
        Another server process judges a round it does not run by that stored activity (a participant's page, loaded
        through it, says whether the round is in progress or ended while away): it must never look older than the
        grace window while the participant is connected."""
        half_grace = min((loaded.study.reconnect.grace_seconds / 2 for loaded in self.catalog), default=math.inf)
        return min(self.sweep_interval, max(half_grace, MIN_TOUCH_S))

    async def _sweep_forever(self) -> None:
        interval = self.touch_interval()  # the catalog does not change after start-up
        since_sweep = 0.0
        while True:
            await asyncio.sleep(interval)
            since_sweep += interval
            try:
                if since_sweep >= self.sweep_interval:
                    since_sweep = 0.0
                    await self.sweep()
                else:
                    await self._touch_connected()
            except Exception:
                log.exception("trial sweep failed")

    async def _touch_connected(self) -> None:
        connected = [g.meta.trial_id for g in self.games.values() if g.connection is not None]
        if connected:
            await asyncio.to_thread(self._touch, connected)

    async def sweep(self) -> None:
        await self._touch_connected()
        live = set(self.games)
        for loaded in self.catalog:
            idle = max(loaded.study.reconnect.grace_seconds, 3 * self.sweep_interval)
            count = await asyncio.to_thread(abandon_stale, self.deps.store, loaded, idle, live)
            if count:
                log.info("abandoned %d stale trial(s) of study %s", count, loaded.id)
