"""The robot's decision for each tick of one live trial (docs/architecture.md, "the robot's decision deadline").

The decision for a state is requested as soon as the state exists, with a budget of ``decision_deadline_fraction``
of the tick period (a ``fast`` pilot trial: ``PILOT_DECISION_S``); the deadline is set, and the answer judged, on
the one clock of ``server.robots.deadline``. A missed deadline makes the robot stay that tick. The first decision
of a trial (or of a resumed trial) has ``FIRST_DECISION_S`` and the clock starts once it is in (see
``server.game.live``).
"""

from __future__ import annotations

import asyncio

from server.game.engine import TrialEngine
from server.game.meta import TrialMeta
from server.robots import RobotChoice, RobotPool
from server.robots import deadline as decision_deadline

PILOT_DECISION_S = 10.0
"""A ``fast`` pilot trial's robot decision deadline (seconds after the request)."""
FIRST_DECISION_S = 2.0
"""How long a trial's clock waits for the robot's first decision (see ``server.game.live``)."""


class RobotDecisions:
    """The pending decision of one trial's robot, the last one taken, and how many missed their deadline."""

    def __init__(self, pool: RobotPool, meta: TrialMeta, budget_s: float, first_s: float) -> None:
        self.pool, self.meta = pool, meta
        self.budget_s = budget_s
        """Seconds the robot has for a decision."""
        self.first_s = first_s
        """Seconds it has for the first decision of the trial (or of its resumption)."""
        self.pending: asyncio.Task[RobotChoice] | None = None
        self._tick = -1
        self.last: RobotChoice | None = None
        self.misses = 0

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
        """The decision for the engine's world (requested now if the pending one is for another tick)."""
        if self.pending is None or self._tick != engine.tick:
            self.request(engine)
        assert self.pending is not None
        choice = await self.pending
        self.pending = None
        self.last = choice
        if choice.missed:
            self.misses += 1
        return choice
