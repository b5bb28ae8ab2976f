"""One live trial: its parts, wired together, and the game loop task that drives them.

Each part owns one job end to end: the round's clock (:mod:`server.game.pacing`), the participant's link and what
their messages do (:mod:`server.game.link`, :mod:`server.game.choices`), the robot's decisions
(:mod:`server.game.decisions`), the robot's health kept in the store (:mod:`server.game.health_keeper`), what the
participant is told beside the state (:mod:`server.game.hints`), and what the trial stores
(:mod:`server.game.records`). Each tick: the clock says a step is due, the robot's decision is taken, the world
steps, the step is stored, judged and hinted on, the next decision is requested and the participant sees the state.
"""

from __future__ import annotations

import asyncio
import contextlib
import logging
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from server.game import snapshot
from server.game.blocked import Blocked
from server.game.choices import apply_choice
from server.game.clock import Clock, MonotonicClock
from server.game.connection import Connection
from server.game.decisions import RobotDecisions
from server.game.engine import TrialEngine
from server.game.health import RobotHealth
from server.game.health_keeper import HealthKeeper
from server.game.hints import Hints
from server.game.link import ParticipantLink
from server.game.meta import TrialMeta
from server.game.pacing import Pacing
from server.game.records import TrialRecords
from server.game.taking_part import TakingPart
from server.protocol.server import Error, State
from server.robots import RobotPool
from store.engine import Store
from store.writer import BatchWriter
from study_config.catalog import LoadedStudy

log = logging.getLogger(__name__)


@dataclass(frozen=True)
class GameDeps:
    store: Store
    writer: BatchWriter
    pool: RobotPool
    deadline_fraction: float
    max_message_bytes: int
    on_end: Callable[[LiveGame], None]
    clock: Clock = field(default_factory=MonotonicClock)
    """The wall clock of the round limit and the idle nudge (tests inject one they move by hand)."""


class LiveGame:
    def __init__(self, meta: TrialMeta, loaded: LoadedStudy, engine: TrialEngine, deps: GameDeps,
                 resumed: bool, health: RobotHealth | None = None, round_seconds: float = 0.0) -> None:
        """``round_seconds``: what the round had already run while connected (a round resumed from the store)."""
        self.meta, self.loaded, self.engine, self.deps, self.resumed = meta, loaded, engine, deps, resumed
        study, timing = loaded.study, loaded.study.timing
        self.part = TakingPart(study.validity, timing.tick_rate_hz, judged=meta.kind == "main")
        """The round's taking part so far: a warning while the participant can act (``server.game.taking_part``)."""
        self.records = TrialRecords(deps.writer, meta, engine, self.part)
        self.event = self.records.event
        self.link = ParticipantLink(deps.max_message_bytes, self.event, limited=not meta.pilot_pace)
        self.pacing = Pacing(timing, engine.rules.horizon, deps.clock, fast=meta.pilot_pace == "fast",
                             link=self.link, log=self.event, spent_s=round_seconds)
        self.keeper = HealthKeeper.fresh(study.validity, engine.rules.horizon, deps.store, meta, self.event, health)
        self.robot = RobotDecisions.paced(deps.pool, meta, loaded, fast=self.pacing.fast, period_s=self.pacing.period,
                                          deadline_fraction=deps.deadline_fraction, log=self.event,
                                          count=self.keeper.record)
        self.hints = Hints(timing.stall_hint_ticks(), self.link, self.event, self.pacing.times, self.part)
        self.finished = False
        self.stored = asyncio.Event()
        """Set once an ending trial's last ticks and its end are stored (:meth:`end`), so that a reconnection
        arriving meanwhile decides on what the store then says, not on a store still missing its last ticks."""
        self.task: asyncio.Task[None] | None = None

    @property
    def connection(self) -> Connection | None:
        return self.link.connection

    @property
    def health(self) -> RobotHealth:
        return self.keeper.health

    def state_message(self) -> State:
        return snapshot.state(self.engine, mode=self.pacing.mode, rate=self.pacing.rate,
                              ack=self.link.inbound.last_seq, round_left=self.pacing.times.left())

    def attach(self, conn: Connection) -> None:
        """Make ``conn`` the participant's connection (replacing an older one) and send hello + state."""
        self.pacing.connected(idle=not self.engine.controller.has_action())
        hello = snapshot.hello(self.meta, self.engine, mode=self.pacing.mode, rate=self.pacing.rate,
                               resumed=self.resumed or self.engine.tick > 0, limit=self.deps.max_message_bytes)
        self.link.open(conn, hello, self.state_message(), self.engine.tick)

    def detach(self, conn: Connection) -> bool:
        """Forget ``conn`` if it is the current connection (the world pauses); whether it was."""
        if not self.link.drop(conn):
            return False
        self.pacing.times.disconnected()
        return True

    def handle(self, conn: Connection, text: str | None, data: bytes | None = None) -> None:
        """Apply one client frame, answering ``ack`` / ``pong`` or a typed ``error`` (nothing changed)."""
        self.link.receive(conn, text, data, playing=not self.finished, apply=lambda message: apply_choice(
            message, self.engine, log=self.event, blocked=self.hints.blocked, acted=self.pacing.times.acted))

    def _refused(self, blocked: Blocked) -> None:
        self.hints.blocked(blocked)
        self.link.send(self.state_message())

    def start(self) -> None:
        self.task = asyncio.create_task(self.run(), name=f"trial-{self.meta.trial_id}")

    async def run(self) -> None:
        try:
            await self._play()
        except asyncio.CancelledError:
            raise
        except Exception:
            log.exception("game loop of trial %d failed", self.meta.trial_id)
            self.event("error", {"code": "internal", "where": "game_loop"})
            self.link.close(1011, Error(code="internal", message="the game stopped; reload to resume"))
            self.deps.on_end(self)

    async def _play(self) -> None:
        engine, pacing, robot = self.engine, self.pacing, self.robot
        await robot.first(engine)
        while not engine.done and not pacing.timed_out:
            lateness_ms = await pacing.due(engine, self._refused, self.hints.nudge)
            if lateness_ms is None:
                continue
            choice = await robot.take(engine)
            before = engine.world
            outcome = engine.advance(choice.action)
            self.keeper.stepped(before, outcome.events, engine.rules)
            self.records.tick(outcome, choice, lateness_ms, pacing.times.elapsed())
            self.hints.stepped(engine, outcome)
            await robot.stepped(engine)
            self.link.send(self.state_message())
            pacing.stepped(idle=not engine.controller.has_action())
            self.hints.nudge()
        if pacing.timed_out:
            log.info("trial %d (participant %s) reached its wall-clock limit of %.0f s", self.meta.trial_id,
                     self.meta.participant, pacing.times.limit_s or 0.0)
        reason = "time_limit" if pacing.timed_out else "delivered" if engine.world.orders_left == 0 else "horizon"
        await self.end("finished", reason)

    async def end(self, status: str, reason: str) -> None:
        """End the trial (``finished`` or ``abandoned``): store everything, move the participant on, tell
        the client, free the planner. Called by the loop itself or, for abandonment, by the registry."""
        if self.finished:
            return
        self.finished = True
        try:
            if self.task is not None and self.task is not asyncio.current_task():
                self.task.cancel()
            self.robot.cancel()
            self.keeper.finish()
            self.link.store_drops(force=True)
            await self.deps.writer.flush()
            await self.keeper.settle()
            self.link.close(*await self.records.store_end(self.deps.store, self.loaded.study, status, reason))
            await self.deps.pool.close_trial(self.meta.trial_id)
            self.deps.on_end(self)
        finally:
            self.stored.set()

    async def suspend(self) -> None:
        """Stop the loop without ending the trial (server shutdown, eviction): it can be resumed from the store."""
        for task in (self.task, self.robot.pending):
            if task is not None and not task.done():
                task.cancel()
                with contextlib.suppress(asyncio.CancelledError, Exception):
                    await task
        self.link.close(1012)
        await self.keeper.keep()
        await self.deps.pool.close_trial(self.meta.trial_id)

    def spectator(self) -> dict[str, Any]:
        last = self.robot.last
        return snapshot.spectator(self.meta, self.engine, {
            **self.status(), "mode": self.pacing.mode, "tick_rate_hz": self.pacing.rate,
            "decision": last.info if last else None, "decision_ms": last.decision_ms if last else None})

    def status(self) -> dict[str, Any]:
        """What the admin's list of live trials shows of this round: its link, the robot's misses and health, the
        stall hints, and the percentiles of the recent steps' lateness (milliseconds)."""
        return {"connected": self.link.connection is not None, "deadline_misses": self.robot.misses,
                "stall_hints": self.hints.stall_hints, "health": self.keeper.health.to_dict(),
                "lateness_ms": snapshot.percentiles(list(self.pacing.lateness))}
