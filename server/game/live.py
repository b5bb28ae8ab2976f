"""One live trial: the participant's connection, their messages, and the game loop task.

The game is made of parts with one job each, driven by its loop: the round's clock (``server.game.pacing``), the
participant's link (``server.game.link``), the robot's decisions (``server.game.decisions``), the robot health
kept in the store (``server.game.health_keeper``) and the stall hints (``server.game.stall_hint``).

The clock:

- ``fixed_rate``: a step every ``1 / tick_rate_hz`` seconds; ``wait_for_participant`` (the paper's clock): a
  step only for an action of the participant's (a key's one action, or a step of their task that moves, turns
  or works: a task whose next step would do nothing ends with its reason instead, ``server.game.steps``),
  never faster than the tick rate.
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
  participant is connected, and stored with each tick so a round resumed from the store goes on counting):
  past it the round ends with reason ``time_limit``. Each stretch the world waits
  for the participant is logged as a ``wait`` event (its seconds count toward the trial's ``idle_pct``); the last
  minute of the limit is counted down on the page (``countdown``).
  In both clocks, a cook with nothing to do gets a ``nudge`` every ``timing.idle_nudge_seconds``, and from the
  second on a ``warning`` when the round so far would not count (``server.game.round_time``,
  ``server.game.taking_part``; the wall clock is injected, ``server.game.clock``).
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
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from server.flow import service
from server.game import snapshot
from server.game.blocked import Blocked
from server.game.clock import Clock, MonotonicClock
from server.game.connection import Connection
from server.game.decisions import FIRST_DECISION_S, PILOT_DECISION_S, RobotDecisions
from server.game.engine import TickOutcome, TrialEngine
from server.game.health import RobotHealth
from server.game.health_keeper import HealthKeeper
from server.game.link import ParticipantLink
from server.game.meta import TrialMeta
from server.game.pacing import Pacing
from server.game.records import tick_row
from server.game.stall_hint import Hint, StallHints
from server.game.taking_part import TakingPart
from server.protocol.client import Blur, Focus, Heartbeat, Idle, InterruptMessage, SelectSubtask
from server.protocol.inbound import ProtocolError
from server.protocol.server import Ack, Countdown, EngagementWarning, Error, Nudge, Pong, State, TrialEnd
from server.protocol.server import StallHint as StallHintMessage
from server.robots import RobotChoice, RobotPool
from store.engine import Store
from store.types import utcnow
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
    """One live trial, in parts with one job each: :attr:`pacing` (the round's clock), :attr:`link` (the
    participant's connection and messages), :attr:`robot` (the robot's decision each tick), :attr:`keeper` (the
    robot health, kept in the store) and :attr:`stalls` (the stall hints); the game drives them from its loop."""

    def __init__(self, meta: TrialMeta, loaded: LoadedStudy, engine: TrialEngine, deps: GameDeps,
                 resumed: bool, health: RobotHealth | None = None, round_seconds: float = 0.0) -> None:
        """``round_seconds``: what the round had already run while connected (a round resumed from the store)."""
        self.meta, self.loaded, self.engine, self.deps, self.resumed = meta, loaded, engine, deps, resumed
        timing = loaded.study.timing
        self.pacing = Pacing(timing, engine.rules.horizon, deps.clock, fast=meta.pilot_pace == "fast",
                             spent_s=round_seconds)
        self.link = ParticipantLink(deps.max_message_bytes)
        fast = self.pacing.fast
        self.robot = RobotDecisions(deps.pool, meta,
                                    PILOT_DECISION_S if fast else deps.deadline_fraction * self.pacing.period,
                                    PILOT_DECISION_S if fast else FIRST_DECISION_S)
        self.keeper = HealthKeeper(
            health or RobotHealth(loaded.study.validity.max_missed_decisions_pct, engine.rules.horizon,
                                  max_flickers=loaded.study.validity.max_robot_flickers),
            deps.store, meta, self.event)
        self.stalls = StallHints(timing.stall_hint_ticks())
        self.part = TakingPart(loaded.study.validity, timing.tick_rate_hz, judged=meta.kind == "main")
        """The round's taking part so far: a warning while the participant can act (``server.game.taking_part``)."""
        self.finished = False
        self.stored = asyncio.Event()
        """Set once an ending trial's last ticks and its end are stored (:meth:`end`), so that a reconnection
        arriving meanwhile decides on what the store then says, not on a store still missing its last ticks."""
        self._connect_logged = False
        self.waiting_since: float | None = None
        """When the current wait for the participant began (``pacing.clock``), while the world waits: the round's
        lease renewals store it, so a crash does not lose it from the idle share (``store.lease``)."""
        self.task: asyncio.Task[None] | None = None

    # -- what the registry, the admin and the tests read ------------------------------------------------

    @property
    def connection(self) -> Connection | None:
        return self.link.connection

    @property
    def health(self) -> RobotHealth:
        return self.keeper.health

    @health.setter
    def health(self, health: RobotHealth) -> None:
        self.keeper.health = health

    @property
    def misses(self) -> int:
        return self.robot.misses

    @property
    def stall_hints(self) -> int:
        return self.stalls.given

    # -- connection ---------------------------------------------------------------------------------

    def start(self) -> None:
        self.task = asyncio.create_task(self.run(), name=f"trial-{self.meta.trial_id}")

    def attach(self, conn: Connection) -> None:
        """Make ``conn`` the participant's connection (replacing an older one) and send hello + state."""
        replaced = self.link.replace(conn)
        times = self.pacing.times
        times.connected()
        if not self.engine.controller.has_action():
            times.idle()
        conn.open()
        conn.send(snapshot.hello(self.meta, self.engine, mode=self.pacing.mode, rate=self.pacing.rate,
                                 resumed=self.resumed or self.engine.tick > 0, limit=self.deps.max_message_bytes))
        conn.send(self.state_message())
        # A reconnection flood is counted like a message flood; a disconnect is logged when its connect was.
        self._connect_logged = self.link.budget.take("connect")
        if self._connect_logged:
            self.event("connect", {"replaced": replaced is not None, "resumed_at": self.engine.tick})
        self.link.connected.set()
        self.link.wake.set()

    def detach(self, conn: Connection) -> bool:
        """Forget ``conn`` if it is the current connection (the world pauses); whether it was."""
        if not self.link.drop(conn):
            return False
        self.pacing.times.disconnected()
        if self._connect_logged:
            self.event("disconnect", {})
        self._store_drops(force=True)
        self.link.wake.set()
        return True

    def state_message(self) -> State:
        return snapshot.state(self.engine, mode=self.pacing.mode, rate=self.pacing.rate,
                              ack=self.link.inbound.last_seq, round_left=self.pacing.times.left())

    # -- client messages ------------------------------------------------------------------------------

    def handle(self, conn: Connection, text: str | None, data: bytes | None = None) -> None:
        """Apply one client frame, answering ``ack`` / ``pong`` or a typed ``error`` (nothing changed)."""
        link = self.link
        if conn is not link.connection or not conn.is_open:
            return
        try:
            message = link.inbound.check(text, data)
            if self.finished:
                raise ProtocolError("not_playing", "the trial is over", message.seq)
            if not (isinstance(message, Heartbeat) or self.meta.pilot_pace) and not link.budget.take(message.type):
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
                link.inbound.accept(message.seq)
                conn.send(Pong(ack=message.seq, client_time=message.client_time, server_time=time.time() * 1000))
                link.answered.set()
                return
            elif isinstance(message, Focus | Blur):
                self.event(message.type, {"seq": message.seq})
            elif isinstance(message, Idle):
                self.event("idle", {"seq": message.seq, "idle_ms": message.idle_ms})
        except ProtocolError as exc:
            conn.send(Error(code=exc.code, message=exc.message, ref=exc.ref))  # type: ignore[arg-type]
            if exc.code != "rate_limited" and link.may_log_error():
                self.event("error", {"code": exc.code, "ref": exc.ref})
            return
        link.inbound.accept(message.seq)
        if isinstance(message, SelectSubtask | InterruptMessage) and controller.has_action():
            self.pacing.times.acted()
        conn.send(Ack(ack=message.seq, subtask=controller.subtask.value if controller.subtask else None,
                      queued=len(controller.queue)))
        link.answered.set()
        link.wake.set()

    # -- the loop -------------------------------------------------------------------------------------

    async def run(self) -> None:
        try:
            await self._play()
        except asyncio.CancelledError:
            raise
        except Exception:
            log.exception("game loop of trial %d failed", self.meta.trial_id)
            self.event("error", {"code": "internal", "where": "game_loop"})
            if self.link.connection is not None:
                self.link.connection.send(Error(code="internal", message="the game stopped; reload to resume"))
                self.link.connection.begin_close(1011)
            self.deps.on_end(self)

    async def _play(self) -> None:
        pacing, link = self.pacing, self.link
        period = pacing.period
        next_at: float | None = None
        last_start: float | None = None
        await self.robot.first(self.engine)
        timed_out = False
        while not self.engine.done:
            if not link.connected.is_set():
                await link.connected.wait()
                next_at = None
                continue
            if pacing.times.over_limit():
                timed_out = True
                break
            now = time.monotonic()
            if pacing.fast:
                await self._await_answer(period)
                scheduled = now = time.monotonic()
            elif pacing.mode == "wait_for_participant" and not self.engine.controller.has_action():
                await self._wait_for_participant()
                continue
            else:
                scheduled = pacing.scheduled(now, last_start, next_at)
            if scheduled > now:
                await asyncio.sleep(scheduled - now)
            if not link.connected.is_set() or not self._may_step():
                continue
            started = time.monotonic()
            choice = await self._take_decision()
            before = self.engine.world
            outcome = self.engine.advance(choice.action)
            self.keeper.stepped(before, outcome.events, self.engine.rules)
            self._record(outcome, choice, max(started - scheduled, 0.0) * 1000)
            if outcome.blocked is not None:
                self._blocked(outcome.blocked)
            self._watch_stall(outcome)
            if choice.error == "worker_lost":
                await self._reopen_planner()
            if not self.engine.done:
                self.robot.request(self.engine)
            if link.connection is not None:
                link.connection.send(self.state_message())
            if not self.engine.controller.has_action():
                pacing.times.idle()
            self._nudge()
            last_start = started
            next_at = max(scheduled + period, time.monotonic())
        world = self.engine.world
        reason = "time_limit" if timed_out else "delivered" if world.orders_left == 0 else "horizon"
        if timed_out:
            log.info("trial %d (participant %s) reached its wall-clock limit of %.0f s", self.meta.trial_id,
                     self.meta.participant, pacing.times.limit_s or 0.0)
        await self.end("finished", reason)

    def _may_step(self) -> bool:
        """The paper's clock steps only for the participant's actions (``server.game.steps``): a subtask whose next
        step would do nothing they chose ends, they are told why (and sent the unchanged state, their task gone),
        and the world does not step; nor does it for a cook left with nothing to do meanwhile (a ``stop``). Asked
        right before each step, after any message that came meanwhile."""
        if self.pacing.mode != "wait_for_participant":
            return True
        refused = self.engine.refused_step()
        if refused is not None:
            self._blocked(refused)
            self.link.send(self.state_message())
            return False
        return self.pacing.fast or self.engine.controller.has_action()

    async def _wait_for_participant(self) -> None:
        """``wait_for_participant``: the cook has nothing to do, so the world waits for the participant's next
        choice or key (or a disconnection), at most until the nudge or the round's limit is due. The stretch is
        logged as a ``wait`` event with its seconds."""
        times, clock = self.pacing.times, self.pacing.clock
        times.idle()
        self.link.wake.clear()
        began = self.waiting_since = clock.now()
        await clock.wait(self.link.wake, times.until_next())
        self.waiting_since = None
        waited = clock.now() - began
        if waited > 0:
            self.event("wait", {"seconds": round(waited, 3)})
        self._nudge()

    def _nudge(self) -> None:
        """Send the idle stretch's nudges as they fall due (they name nothing of the condition) and the countdown
        of the round's last minute; from the second nudge on, and with the countdown (once the round has run a nudge
        interval), warn when the round so far would not count (``server.game.taking_part``)."""
        times = self.pacing.times
        if self.link.connection is None:
            return
        repeat = times.take_nudge()
        if repeat:
            self.link.send(Nudge(repeat=repeat))
            self.event("nudge", {"repeat": repeat})
        left = times.take_countdown()
        if left is not None:
            self.link.send(Countdown(seconds_left=round(left, 1)))
            self.event("countdown", {"seconds_left": round(left, 1)})
        due = (repeat >= 2 or left is not None) and times.elapsed() >= times.nudge_s  # never before they could act
        problem = self.part.problem() if due else None
        if problem is not None:
            self.link.send(EngagementWarning(rule=problem.rule, seconds_left=times.left()))
            self.event("engagement_warning", {"rule": problem.rule, "value": round(problem.value, 2)})

    async def _await_answer(self, period: float) -> None:
        """A ``fast`` pilot trial: wait (at most ``period``) for the participant's answer to the last state."""
        answered = self.link.answered
        if not answered.is_set():
            with contextlib.suppress(TimeoutError):
                await asyncio.wait_for(answered.wait(), period)
        answered.clear()

    async def _take_decision(self) -> RobotChoice:
        choice = await self.robot.take(self.engine)
        self.keeper.record(choice.missed, choice.failed)
        if choice.missed:
            self.event("deadline_miss", {"budget_ms": round(self.robot.budget_s * 1000, 1),
                                         "waited_ms": round(choice.decision_ms or 0.0, 1)})
        elif choice.error is not None:
            self.event("error", {"code": "robot", "message": choice.error[:300]})
        return choice

    async def _reopen_planner(self) -> None:
        try:
            await self.deps.pool.open(self.meta.trial_id, self.loaded.planner(self.meta.robot), self.engine.layout,
                                      self.engine.rules, self.loaded.robot_setup(self.meta.robot, self.engine.angle),
                                      self.engine.world, self.engine.kb)
        except Exception as exc:  # the robot stays until a worker is back
            log.error("cannot re-open the planner of trial %d: %s", self.meta.trial_id, exc)

    def _record(self, outcome: TickOutcome, choice: RobotChoice, lateness_ms: float) -> None:
        self.pacing.lateness.append(lateness_ms)
        self.part.stepped(outcome)
        self.deps.writer.add_tick(tick_row(self.meta.trial_id, outcome, choice, lateness_ms,
                                           self.engine.controller.to_dict(), self.pacing.times.elapsed(),
                                           self.meta.epoch))

    def _blocked(self, blocked: Blocked) -> None:
        """Tell the participant why their subtask is not getting anywhere; log it when the subtask ended."""
        if blocked.ended:
            place = {"place": blocked.reason.place} if blocked.reason.place else {}
            self.event("subtask_blocked", {"subtask": blocked.subtask.value if blocked.subtask else None,
                                           "reason": blocked.reason.code, "item": blocked.reason.item, **place})
        self.link.send(snapshot.blocked_message(blocked))

    def _watch_stall(self, outcome: TickOutcome) -> None:
        """``server.game.stall_hint``: after ``stall_hint_seconds`` without team progress, hint and log it."""
        engine = self.engine
        hint = self.stalls.step(engine.layout, engine.rules, outcome.world, outcome.kb, outcome.events)
        if hint is not None:
            self._hint(hint)

    def _hint(self, hint: Hint) -> None:
        self.event("stall_hint", {"code": hint.code, "text": hint.text})
        self.link.send(StallHintMessage(code=hint.code, text=hint.text))

    def event(self, kind: str, payload: dict[str, Any]) -> None:
        self.part.note(kind, payload)
        self.deps.writer.add_event({"participant_id": self.meta.participant_id, "trial_id": self.meta.trial_id,
                                    "tick": self.engine.tick, "kind": kind, "payload": payload,
                                    "created_at": utcnow(), "epoch": self.meta.epoch})

    def _store_drops(self, force: bool = False) -> None:
        """Store the refused messages' counts as one ``events_dropped`` row (:mod:`server.game.budget`)."""
        summary = self.link.budget.summary(force)
        if summary is not None:
            self.event("events_dropped", summary)

    # -- ending ---------------------------------------------------------------------------------------

    async def end(self, status: str, reason: str) -> None:
        """End the trial (``finished`` or ``abandoned``): store everything, move the participant on, tell
        the client, free the planner. Called by the loop itself or, for abandonment, by the registry."""
        if self.finished:
            return
        self.finished = True
        try:
            if self.task is not None and self.task is not asyncio.current_task():
                self.task.cancel()
            if self.robot.pending is not None:
                self.robot.pending.cancel()
            world = self.engine.world
            self.keeper.update(self.keeper.health.final(), "ended invalid")
            self._store_drops(force=True)
            await self.deps.writer.flush()
            delivered = self.engine.rules.orders - world.orders_left
            await self.keeper.settle()
            # The end and its event are stored together under this process's lease, or not at all (the round was
            # taken over by another process meanwhile: it ends there, once).
            progress = await asyncio.to_thread(
                service.end_trial, self.deps.store, self.meta.participant_id, self.meta.trial_id, self.meta.kind,
                self.meta.index, status=status, reason=reason, ticks=world.tick, delivered=delivered, score=world.score,
                study=self.loaded.study, epoch=self.meta.epoch,
                end_event={"status": status, "reason": reason, "ticks": world.tick})
            if self.link.connection is not None and progress is None:
                self.link.connection.send(Error(code="replaced", message="this round continues in another window"))
                self.link.connection.begin_close(4000)
            elif self.link.connection is not None and progress is not None:
                self.link.connection.send(TrialEnd(status=status, reason=reason,  # type: ignore[arg-type]
                                                   ticks=world.tick, delivered=delivered, score=world.score,
                                                   next=progress.phase.value))
                self.link.connection.begin_close(1000)
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
        if self.link.connection is not None:
            self.link.connection.begin_close(1012)
        with contextlib.suppress(Exception):  # the counts are recomputed from the ticks on resume anyway
            await asyncio.to_thread(self.keeper.store_now, self.keeper.health)
        await self.deps.pool.close_trial(self.meta.trial_id)

    def spectator(self) -> dict[str, Any]:
        last = self.robot.last
        return snapshot.spectator(self.meta, self.engine, {
            "connected": self.link.connection is not None, "mode": self.pacing.mode,
            "tick_rate_hz": self.pacing.rate,
            "decision": last.info if last else None,
            "decision_ms": last.decision_ms if last else None,
            "deadline_misses": self.robot.misses, "stall_hints": self.stalls.given,
            "health": self.keeper.health.to_dict(),
            "lateness_ms": snapshot.percentiles(list(self.pacing.lateness)),
        })
