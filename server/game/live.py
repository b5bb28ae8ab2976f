"""One live trial: the participant's connection, their messages, and the game loop task.

The clock:

- ``fixed_rate``: a step every ``1 / tick_rate_hz`` seconds; ``wait_for_participant``: a step only when
  the avatar has something to do (a queued interrupt or a subtask), never faster than the tick rate.
- **The world is paused while no participant is connected** (the researcher's choice: a dropped
  connection must not cost the participant ticks); the next step comes one period after they return.
- Tick lateness = actual start of a step − its scheduled start (logged per tick). A late step does not
  cause a burst of catch-up steps.
- A pilot participant's trial at pace ``fast`` (``steakhouse pilot``; the pace is the store's pilot mark, so no
  real participant can get it) steps as soon as the simulated participant has answered the last ``state``
  with any message (it sends a heartbeat when it has nothing to do) and the robot has decided; it waits at most
  one period for that answer, and its robot decides without the real-time deadline (at most
  ``PILOT_DECISION_S``): the planner's decisions are then those of an unloaded machine, not cut short because
  the pilot runs many trials at once on a busy one. Real participants' trials keep the study's clock and deadline.
- The robot's decision for a state is requested as soon as the state exists, with a deadline of
  ``decision_deadline_fraction`` of the period; a missed deadline makes the robot stay that tick and is
  logged as a ``deadline_miss`` event. The exception is the first decision of a trial (or of a resumed
  trial): the clock starts once it is in, at most ``FIRST_DECISION_S`` later. That decision is the costliest
  (the robot's belief is spread over every subtask the person might start, and a fresh robot worker's caches
  are cold), and when many participants start at once those decisions would queue behind each other.
- ``wait_for_participant`` rounds have a wall-clock limit (``timing.max_round_seconds``, counted while the
  participant is connected): past it the round ends with reason ``time_limit``. Each stretch the world waits
  for the participant is logged as a ``wait`` event (its seconds count toward the trial's ``idle_pct``).
  In both clocks, a cook with nothing to do for ``timing.idle_nudge_seconds`` gets one ``nudge`` per stretch
  (``server.game.round_time``; the wall clock is injected, ``server.game.clock``).
- Robot health (``server.game.health``): every decision counts toward the trial's share of missed
  deadlines; past the study's ``validity.max_missed_decisions_pct`` the trial is marked invalid as it
  happens (a warning in the server log, a ``trial_invalid`` event, the trial row's ``invalid_reason``).

Client messages are applied between ticks (the loop and the handlers share one event loop thread), so an
interrupt acts at the next tick. Every accepted message is answered by ``ack`` (``pong`` for heartbeats),
every rejected one by a typed ``error``.
"""

from __future__ import annotations

import asyncio
import contextlib
import logging
import time
from collections import deque
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from server.flow import service
from server.game import snapshot
from server.game.blocked import Blocked
from server.game.budget import EventBudget
from server.game.clock import Clock, MonotonicClock
from server.game.connection import Connection
from server.game.engine import TickOutcome, TrialEngine
from server.game.health import RobotHealth
from server.game.meta import TrialMeta
from server.game.records import tick_row
from server.game.round_time import RoundTime
from server.game.stall_hint import Hint, StallWatch
from server.game.stall_hint import advance as watch_stall
from server.protocol.client import Blur, Focus, Heartbeat, Idle, InterruptMessage, SelectSubtask
from server.protocol.inbound import Inbound, ProtocolError
from server.protocol.server import Ack, Error, Nudge, Pong, State, TrialEnd
from server.protocol.server import StallHint as StallHintMessage
from server.robots import RobotChoice, RobotPool
from server.robots import deadline as decision_deadline
from store import trials
from store.engine import Store
from store.types import utcnow
from store.writer import BatchWriter
from study_config.catalog import LoadedStudy

log = logging.getLogger(__name__)
MAX_LOGGED_ERRORS = 50
PILOT_DECISION_S = 10.0
"""A ``fast`` pilot trial's robot decision deadline (seconds after the request)."""
FIRST_DECISION_S = 2.0
"""How long a trial's clock waits for the robot's first decision (see the module docstring)."""


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
                 resumed: bool, health: RobotHealth | None = None) -> None:
        self.meta, self.loaded, self.engine, self.deps, self.resumed = meta, loaded, engine, deps, resumed
        self.health = health or RobotHealth(loaded.study.validity.max_missed_decisions_pct, engine.rules.horizon)
        self._health_writes: set[asyncio.Task[None]] = set()
        timing = loaded.study.timing
        self.mode, self.rate, self.period = timing.mode, timing.tick_rate_hz, 1.0 / timing.tick_rate_hz
        self.times = RoundTime(deps.clock, timing.round_limit_seconds(engine.rules.horizon), timing.idle_nudge_seconds)
        self.connection: Connection | None = None
        self.inbound = Inbound(deps.max_message_bytes)
        self.connected = asyncio.Event()
        self.wake = asyncio.Event()
        self.fast = meta.pilot_pace == "fast"
        self.answered = asyncio.Event()
        """Set by every accepted client message: a ``fast`` pilot trial steps once its participant answered."""
        self.finished = False
        self.task: asyncio.Task[None] | None = None
        self._decision: asyncio.Task[RobotChoice] | None = None
        self._decision_tick = -1
        self.last_choice: RobotChoice | None = None
        self.lateness: deque[float] = deque(maxlen=5000)
        self.misses = 0
        self._errors_logged = 0
        self.budget = EventBudget()
        self.stall_watch, self.stall_hints = StallWatch(), 0
        self.hint_ticks = timing.stall_hint_ticks()

    # -- connection ---------------------------------------------------------------------------------

    def start(self) -> None:
        self.task = asyncio.create_task(self.run(), name=f"trial-{self.meta.trial_id}")

    def attach(self, conn: Connection) -> None:
        """Make ``conn`` the participant's connection (replacing an older one) and send hello + state."""
        replaced = self.connection
        if replaced is not None:
            replaced.send(Error(code="replaced", message="this trial was opened in another window"))
            replaced.begin_close(4000)
        self.connection = conn
        self.inbound = Inbound(self.deps.max_message_bytes)
        self.times.connected()
        if not self.engine.controller.has_action():
            self.times.idle()
        conn.open()
        conn.send(snapshot.hello(self.meta, self.engine, mode=self.mode, rate=self.rate,
                                 resumed=self.resumed or self.engine.tick > 0, limit=self.deps.max_message_bytes))
        conn.send(self.state_message())
        self.event("connect", {"replaced": replaced is not None, "resumed_at": self.engine.tick})
        self.connected.set()
        self.wake.set()

    def detach(self, conn: Connection) -> bool:
        """Forget ``conn`` if it is the current connection (the world pauses); whether it was."""
        if conn is not self.connection:
            return False
        self.connection = None
        self.times.disconnected()
        self.connected.clear()
        self._store_drops(force=True)
        self.event("disconnect", {})
        self.wake.set()
        return True

    def state_message(self) -> State:
        return snapshot.state(self.engine, mode=self.mode, rate=self.rate, ack=self.inbound.last_seq)

    # -- client messages ------------------------------------------------------------------------------

    def handle(self, conn: Connection, text: str | None, data: bytes | None = None) -> None:
        """Apply one client frame, answering ``ack`` / ``pong`` or a typed ``error`` (nothing changed)."""
        if conn is not self.connection or not conn.is_open:
            return
        try:
            message = self.inbound.check(text, data)
            if self.finished:
                raise ProtocolError("not_playing", "the trial is over", message.seq)
            if not (isinstance(message, Heartbeat) or self.meta.pilot_pace) and not self.budget.take(message.type):
                self._store_drops()
                raise ProtocolError("rate_limited", "too many messages at once; this one was not applied",
                                    message.seq)
            controller = self.engine.controller
            if isinstance(message, SelectSubtask):
                hint = controller.available(self.engine.world, self.engine.kb)
                refused = controller.select(message.subtask, self.engine.world.human.held)
                self.event("select_subtask", {"seq": message.seq, "subtask": message.subtask.value,
                                              "available": message.subtask in hint})
                if refused is not None:
                    self._blocked(refused)
            elif isinstance(message, InterruptMessage):
                before = controller.subtask
                if not controller.interrupt(message.action):
                    raise ProtocolError("queue_full", "three interrupts are already waiting", message.seq)
                self.event("interrupt", {"seq": message.seq, "action": message.action.value,
                                         "subtask": before.value if before else None})
            elif isinstance(message, Heartbeat):
                self.inbound.accept(message.seq)
                conn.send(Pong(ack=message.seq, client_time=message.client_time, server_time=time.time() * 1000))
                self.answered.set()
                return
            elif isinstance(message, Focus | Blur):
                self.event(message.type, {"seq": message.seq})
            elif isinstance(message, Idle):
                self.event("idle", {"seq": message.seq, "idle_ms": message.idle_ms})
        except ProtocolError as exc:
            conn.send(Error(code=exc.code, message=exc.message, ref=exc.ref))  # type: ignore[arg-type]
            if exc.code != "rate_limited" and self._errors_logged < MAX_LOGGED_ERRORS:
                self._errors_logged += 1
                self.event("error", {"code": exc.code, "ref": exc.ref})
            return
        self.inbound.accept(message.seq)
        if isinstance(message, SelectSubtask | InterruptMessage) and controller.has_action():
            self.times.acted()
        conn.send(Ack(ack=message.seq, subtask=controller.subtask.value if controller.subtask else None,
                      queued=len(controller.queue)))
        self.answered.set()
        self.wake.set()

    # -- the loop -------------------------------------------------------------------------------------

    async def run(self) -> None:
        try:
            await self._play()
        except asyncio.CancelledError:
            raise
        except Exception:
            log.exception("game loop of trial %d failed", self.meta.trial_id)
            self.event("error", {"code": "internal", "where": "game_loop"})
            if self.connection is not None:
                self.connection.send(Error(code="internal", message="the game stopped; reload to resume"))
                self.connection.begin_close(1011)
            self.deps.on_end(self)

    async def _play(self) -> None:
        period = self.period
        next_at: float | None = None
        last_start: float | None = None
        await self._robot_ready()
        timed_out = False
        while not self.engine.done:
            if not self.connected.is_set():
                await self.connected.wait()
                next_at = None
                continue
            if self.times.over_limit():
                timed_out = True
                break
            now = time.monotonic()
            if self.fast:
                await self._await_answer(period)
                scheduled = now = time.monotonic()
            elif self.mode == "wait_for_participant":
                if not self.engine.controller.has_action():
                    await self._wait_for_participant()
                    continue
                scheduled = now if last_start is None else max(last_start + period, now)
            else:
                scheduled = next_at if next_at is not None else now + period
            if scheduled > now:
                await asyncio.sleep(scheduled - now)
            if not self.connected.is_set():
                continue
            started = time.monotonic()
            choice = await self._take_decision()
            outcome = self.engine.advance(choice.action)
            self._record(outcome, choice, max(started - scheduled, 0.0) * 1000)
            if outcome.blocked is not None:
                self._blocked(outcome.blocked)
            self._watch_stall(outcome)
            if choice.error == "worker_lost":
                await self._reopen_planner()
            if not self.engine.done:
                self._request_decision()
            if self.connection is not None:
                self.connection.send(self.state_message())
            if not self.engine.controller.has_action():
                self.times.idle()
                self._nudge()
            last_start = started
            next_at = max(scheduled + period, time.monotonic())
        world = self.engine.world
        reason = "time_limit" if timed_out else "delivered" if world.orders_left == 0 else "horizon"
        if timed_out:
            log.info("trial %d (participant %s) reached its wall-clock limit of %.0f s", self.meta.trial_id,
                     self.meta.participant, self.times.limit_s or 0.0)
        await self.end("finished", reason)

    async def _wait_for_participant(self) -> None:
        """``wait_for_participant``: the cook has nothing to do, so the world waits for the participant's next
        choice or key (or a disconnection), at most until the nudge or the round's limit is due. The stretch is
        logged as a ``wait`` event with its seconds."""
        self.times.idle()
        self.wake.clear()
        clock = self.deps.clock
        began = clock.now()
        await clock.wait(self.wake, self.times.until_next())
        waited = clock.now() - began
        if waited > 0:
            self.event("wait", {"seconds": round(waited, 3)})
        self._nudge()

    def _nudge(self) -> None:
        """Send the idle stretch's nudge once it is due (it names nothing of the condition)."""
        if self.times.take_nudge() and self.connection is not None:
            self.connection.send(Nudge())
            self.event("nudge", {})

    def decision_budget(self) -> float:
        """Seconds the robot has for a decision: a share of the tick period, or ``PILOT_DECISION_S`` for a
        ``fast`` pilot trial."""
        return PILOT_DECISION_S if self.fast else self.deps.deadline_fraction * self.period

    async def _await_answer(self, period: float) -> None:
        """A ``fast`` pilot trial: wait (at most ``period``) for the participant's answer to the last state."""
        if not self.answered.is_set():
            with contextlib.suppress(TimeoutError):
                await asyncio.wait_for(self.answered.wait(), period)
        self.answered.clear()

    async def _robot_ready(self) -> None:
        """Request the first decision with ``FIRST_DECISION_S`` (a ``fast`` pilot: its usual budget) and wait
        until it is in; it is the one the first step takes."""
        self._request_decision(FIRST_DECISION_S if not self.fast else PILOT_DECISION_S)
        assert self._decision is not None
        await asyncio.wait({self._decision})

    def _request_decision(self, budget: float | None = None) -> None:
        world = self.engine.world
        deadline = decision_deadline.after(self.decision_budget() if budget is None else budget)
        self._decision = asyncio.create_task(self.deps.pool.decide(
            self.meta.trial_id, world, self.engine.last_events, self.meta.seed, world.tick, deadline))
        self._decision_tick = world.tick

    async def _take_decision(self) -> RobotChoice:
        if self._decision is None or self._decision_tick != self.engine.tick:
            self._request_decision()
        assert self._decision is not None
        choice = await self._decision
        self._decision = None
        self.last_choice = choice
        self._judge(choice.missed)
        if choice.missed:
            self.misses += 1
            self.event("deadline_miss", {"budget_ms": round(self.decision_budget() * 1000, 1),
                                         "waited_ms": round(choice.decision_ms or 0.0, 1)})
        elif choice.error is not None:
            self.event("error", {"code": "robot", "message": choice.error[:300]})
        return choice

    def _judge(self, missed: bool) -> None:
        """Count the decision; the moment the trial becomes invalid, say so in the log, the events and the
        trial row (docs/operations.md, "Robot health")."""
        if self._update_health(self.health.record(missed), "is invalid"):
            task = asyncio.create_task(asyncio.to_thread(self._store_health, self.health))
            self._health_writes.add(task)
            task.add_done_callback(self._health_writes.discard)

    def _update_health(self, health: RobotHealth, verb: str) -> bool:
        """Take ``health``; when it makes the trial invalid, log a warning and a ``trial_invalid`` event and
        answer ``True``."""
        became_invalid = health.invalid and not self.health.invalid
        self.health = health
        if became_invalid:
            log.warning("trial %d (participant %s) %s: %s", self.meta.trial_id, self.meta.participant, verb,
                        health.invalid_reason)
            self.event("trial_invalid", health.to_dict())
        return became_invalid

    def _store_health(self, health: RobotHealth) -> None:
        with self.deps.store.transaction() as session:
            trials.record_health(session, self.meta.trial_id, decisions=health.decisions, missed=health.missed,
                                 invalid_reason=health.invalid_reason)

    async def _reopen_planner(self) -> None:
        try:
            await self.deps.pool.open(self.meta.trial_id, self.meta.robot, self.engine.layout, self.engine.rules,
                                      self.loaded.planner_config(self.engine.angle), self.engine.world,
                                      self.engine.kb)
        except Exception as exc:  # the robot stays until a worker is back
            log.error("cannot re-open the planner of trial %d: %s", self.meta.trial_id, exc)

    def _record(self, outcome: TickOutcome, choice: RobotChoice, lateness_ms: float) -> None:
        self.lateness.append(lateness_ms)
        self.deps.writer.add_tick(tick_row(self.meta.trial_id, outcome, choice, lateness_ms,
                                           self.engine.controller.to_dict()))

    def _blocked(self, blocked: Blocked) -> None:
        """Tell the participant why their subtask is not getting anywhere; log it when the subtask ended."""
        if blocked.ended:
            self.event("subtask_blocked", {"subtask": blocked.subtask.value if blocked.subtask else None,
                                           "reason": blocked.reason.code,
                                           "item": blocked.reason.item})
        if self.connection is not None:
            self.connection.send(snapshot.blocked_message(blocked))

    def _watch_stall(self, outcome: TickOutcome) -> None:
        """``server.game.stall_hint``: after ``stall_hint_seconds`` without team progress, hint and log it."""
        engine = self.engine
        self.stall_watch, hint = watch_stall(self.stall_watch, engine.layout, engine.rules, outcome.world,
                                             outcome.kb, outcome.events, self.hint_ticks)
        if hint is not None:
            self._hint(hint)

    def _hint(self, hint: Hint) -> None:
        self.stall_hints += 1
        self.event("stall_hint", {"code": hint.code, "text": hint.text})
        if self.connection is not None:
            self.connection.send(StallHintMessage(code=hint.code, text=hint.text))

    def event(self, kind: str, payload: dict[str, Any]) -> None:
        self.deps.writer.add_event({"participant_id": self.meta.participant_id, "trial_id": self.meta.trial_id,
                                    "tick": self.engine.tick, "kind": kind, "payload": payload,
                                    "created_at": utcnow()})

    def _store_drops(self, force: bool = False) -> None:
        """Store the refused messages' counts as one ``events_dropped`` row (:mod:`server.game.budget`)."""
        summary = self.budget.summary(force)
        if summary is not None:
            self.event("events_dropped", summary)

    # -- ending ---------------------------------------------------------------------------------------

    async def end(self, status: str, reason: str) -> None:
        """End the trial (``finished`` or ``abandoned``): store everything, move the participant on, tell
        the client, free the planner. Called by the loop itself or, for abandonment, by the registry."""
        if self.finished:
            return
        self.finished = True
        if self.task is not None and self.task is not asyncio.current_task():
            self.task.cancel()
        if self._decision is not None:
            self._decision.cancel()
        world = self.engine.world
        self._update_health(self.health.final(), "ended invalid")
        self._store_drops(force=True)
        self.event("trial_end", {"status": status, "reason": reason, "ticks": world.tick})
        await self.deps.writer.flush()
        delivered = self.engine.rules.orders - world.orders_left
        if self._health_writes:
            await asyncio.gather(*self._health_writes, return_exceptions=True)
        await asyncio.to_thread(self._store_health, self.health)
        progress = await asyncio.to_thread(
            service.end_trial, self.deps.store, self.meta.participant_id, self.meta.trial_id, self.meta.kind,
            self.meta.index, status=status, reason=reason, ticks=world.tick, delivered=delivered, score=world.score,
            study=self.loaded.study)
        if self.connection is not None:
            self.connection.send(TrialEnd(status=status, reason=reason, ticks=world.tick,  # type: ignore[arg-type]
                                          delivered=delivered, score=world.score,
                                          next=progress.phase.value if progress else "unknown"))
            self.connection.begin_close(1000)
        await self.deps.pool.close_trial(self.meta.trial_id)
        self.deps.on_end(self)

    async def suspend(self) -> None:
        """Stop the loop without ending the trial (server shutdown, eviction): it can be resumed from the store."""
        for task in (self.task, self._decision):
            if task is not None and not task.done():
                task.cancel()
                with contextlib.suppress(asyncio.CancelledError, Exception):
                    await task
        if self.connection is not None:
            self.connection.begin_close(1012)
        with contextlib.suppress(Exception):  # the counts are recomputed from the ticks on resume anyway
            await asyncio.to_thread(self._store_health, self.health)
        await self.deps.pool.close_trial(self.meta.trial_id)

    def spectator(self) -> dict[str, Any]:
        return snapshot.spectator(self.meta, self.engine, {
            "connected": self.connection is not None, "mode": self.mode, "tick_rate_hz": self.rate,
            "decision": self.last_choice.info if self.last_choice else None,
            "decision_ms": self.last_choice.decision_ms if self.last_choice else None,
            "deadline_misses": self.misses, "stall_hints": self.stall_hints, "health": self.health.to_dict(),
            "lateness_ms": snapshot.percentiles(list(self.lateness)),
        })
