"""The robot's decision for each tick of one live trial (docs/architecture.md, "the robot's decision deadline").

The decision for a state is requested as soon as the state exists, with a budget of ``decision_deadline_fraction``
of the tick period (a ``fast`` pilot trial: ``PILOT_DECISION_S``); the deadline is set, and the answer judged, on
the one clock of ``server.robots.deadline``. A missed deadline makes the robot stay that tick. The first decision
of a trial (or of a resumed trial) has ``FIRST_DECISION_S`` and the clock starts once it is in: that decision is
the costliest (the robot's belief is spread over every subtask the person might start, and a fresh robot worker's
caches are cold), and when many participants start at once those decisions would queue behind each other.

A ``fast`` pilot trial's robot decides without the real-time deadline (at most ``PILOT_DECISION_S``): the
planner's decisions are then those of an unloaded machine, not cut short because the pilot runs many trials at once
on a busy one. Real participants' trials keep the study's clock and deadline.

Every decision is counted toward the robot's health (``count``: ``server.game.health_keeper``); a missed one is
logged as a ``deadline_miss`` event, a failed one as an ``error`` (``code: robot``). A robot worker lost mid-trial is
replaced: the planner is opened again on the world as it is, and the robot stays until it is back.
"""

from __future__ import annotations

import asyncio
import logging
from collections.abc import Callable

from server.game.engine import TrialEngine
from server.game.meta import TrialMeta
from server.game.records import EventLog
from server.robots import RobotChoice, RobotPool
from server.robots import deadline as decision_deadline
from study_config.catalog import LoadedStudy

log = logging.getLogger("server.game.live")
"""The game's log: a planner that cannot be re-opened is reported where the rest of its story is."""

PILOT_DECISION_S = 10.0
"""A ``fast`` pilot trial's robot decision deadline (seconds after the request)."""
FIRST_DECISION_S = 2.0
"""How long a trial's clock waits for the robot's first decision (see the module)."""


class RobotDecisions:
    """The pending decision of one trial's robot, the last one taken, and how many missed their deadline."""

    def __init__(self, pool: RobotPool, meta: TrialMeta, loaded: LoadedStudy, *, budget_s: float, first_s: float,
                 log: EventLog, count: Callable[[bool, bool], None]) -> None:
        """``count(missed, failed)``: told of every decision taken (the robot's health)."""
        self.pool, self.meta, self.loaded, self.log, self.count = pool, meta, loaded, log, count
        self.budget_s = budget_s
        """Seconds the robot has for a decision."""
        self.first_s = first_s
        """Seconds it has for the first decision of the trial (or of its resumption)."""
        self.pending: asyncio.Task[RobotChoice] | None = None
        self._tick = -1
        self.last: RobotChoice | None = None
        self.misses = 0

    @classmethod
    def paced(cls, pool: RobotPool, meta: TrialMeta, loaded: LoadedStudy, *, fast: bool, period_s: float,
              deadline_fraction: float, log: EventLog, count: Callable[[bool, bool], None]) -> RobotDecisions:
        """The decisions of a round stepping every ``period_s`` (``fast``: a fast pilot trial's, see the module)."""
        return cls(pool, meta, loaded, budget_s=PILOT_DECISION_S if fast else deadline_fraction * period_s,
                   first_s=PILOT_DECISION_S if fast else FIRST_DECISION_S, log=log, count=count)

    def request(self, engine: TrialEngine, budget: float | None = None) -> None:
        """Ask for the decision on the engine's world now, by ``budget`` seconds (default :attr:`budget_s`)."""
        world = engine.world
        deadline = decision_deadline.after(self.budget_s if budget is None else budget)
        self.pending = asyncio.create_task(self.pool.decide(
            self.meta.trial_id, world, engine.last_events, self.meta.seed, world.tick, deadline))
        self._tick = world.tick

    async def first(self, engine: TrialEngine) -> None:
        """Request the first decision with :attr:`first_s` and wait until it is in; the first step takes it."""
        self.request(engine, self.first_s)
        assert self.pending is not None
        await asyncio.wait({self.pending})

    async def take(self, engine: TrialEngine) -> RobotChoice:
        """The decision for the engine's world (requested now if the pending one is for another tick), counted and,
        when missed or failed, logged."""
        if self.pending is None or self._tick != engine.tick:
            self.request(engine)
        assert self.pending is not None
        choice = await self.pending
        self.pending = None
        self.last = choice
        self.misses += choice.missed
        self.count(choice.missed, choice.failed)
        if choice.missed:
            self.log("deadline_miss", {"budget_ms": round(self.budget_s * 1000, 1),
                                       "waited_ms": round(choice.decision_ms or 0.0, 1)})
        elif choice.error is not None:
            self.log("error", {"code": "robot", "message": choice.error[:300]})
        return choice

    async def stepped(self, engine: TrialEngine) -> None:
        """After a step: the planner re-opened if its worker was lost, and the next decision requested."""
        if self.last is not None and self.last.error == "worker_lost":
            await self._reopen(engine)
        if not engine.done:
            self.request(engine)

    def cancel(self) -> None:
        """Stop waiting for the pending decision (the trial ends)."""
        if self.pending is not None:
            self.pending.cancel()

    async def _reopen(self, engine: TrialEngine) -> None:
        trial_id, robot = self.meta.trial_id, self.meta.robot
        try:
            await self.pool.open(trial_id, self.loaded.planner(robot), engine.layout, engine.rules,
                                 self.loaded.robot_setup(robot, engine.angle), engine.world, engine.kb)
        except Exception as exc:  # the robot stays until a worker is back
            log.error("cannot re-open the planner of trial %d: %s", trial_id, exc)
