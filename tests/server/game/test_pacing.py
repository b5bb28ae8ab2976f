"""The round's clock (``server.game.pacing``): a step every period under ``fixed_rate`` with no burst after a late
one, the world paused while nobody is connected, the paper's clock waiting for the participant (a ``wait`` event)
and refusing a task that would do nothing, the round's wall-clock limit, and a fast pilot trial stepping once its
participant answered. Both clocks are moved by hand."""

from __future__ import annotations

import asyncio
from typing import Any, Literal

from steakhouse_live_parts import Events, HandClock, engine, waits_on, world_with

from planner.geometry import Action, Direction
from planner.objects import STEAK_PLATE
from planner.subtasks import Subtask
from server.game.blocked import Blocked
from server.game.engine import TrialEngine
from server.game.link import ParticipantLink
from server.game.pacing import Pacing
from server.protocol.interrupts import Interrupt
from study_config.study.sections import Timing

PERIOD = 0.25


class Setup:
    def __init__(self, mode: Literal["fixed_rate", "wait_for_participant"] = "fixed_rate", fast: bool = False,
                 connected: bool = True, **timing: Any) -> None:
        self.events, self.clock, self.ticker = Events(), HandClock(), HandClock()
        self.link = ParticipantLink(10_000, self.events)
        self.pacing = Pacing(Timing(mode=mode, tick_rate_hz=1 / PERIOD, **timing), 400, self.clock, fast=fast,
                             link=self.link, log=self.events, ticker=self.ticker)
        self.refused: list[Blocked] = []
        self.nudges = 0
        if connected:
            self.link.connected.set()
            self.pacing.connected(idle=True)

    def nudge(self) -> None:
        self.nudges += 1

    def due(self, on: TrialEngine) -> asyncio.Task[float | None]:
        return asyncio.ensure_future(self.pacing.due(on, self.refused.append, self.nudge))


async def step(s: Setup, on: TrialEngine, wait_for: float) -> tuple[float, float | None, bool]:
    """Ask for the next step and, if it waits on the steps' clock, move that clock by ``wait_for``: when the step
    started, its lateness, and whether it waited."""
    due = s.due(on)
    asked = asyncio.ensure_future(s.ticker.waiting.wait())
    await asyncio.wait({due, asked}, return_when=asyncio.FIRST_COMPLETED)
    asked.cancel()
    waited = not due.done()
    if waited:
        s.ticker.advance(wait_for)
    lateness = await due
    s.pacing.stepped(idle=False)
    return s.ticker.t, lateness, waited


def test_fixed_rate_steps_a_period_apart_and_a_late_step_is_not_followed_by_a_burst() -> None:
    async def scenario() -> tuple[list[tuple[float, float | None, bool]], list[float]]:
        s, world = Setup(), engine()
        steps = [await step(s, world, PERIOD)]
        s.ticker.advance(0.75)  # the step due at 0.5 starts at 1.0
        steps += [await step(s, world, PERIOD) for _ in range(3)]
        return steps, list(s.pacing.lateness)

    steps, kept = asyncio.run(scenario())
    # the late step's successor was planned for 0.75, passed: it comes at once; then a period apart again, not the
    # two more it would take to catch up
    assert steps == [(0.25, 0.0, True), (1.0, 500.0, False), (1.0, 0.0, False), (1.25, 0.0, True)]
    assert kept == [0.0, 500.0, 0.0, 0.0], "the live view's lateness is each step's"


def test_the_world_is_paused_while_nobody_is_connected_and_steps_a_period_after_they_return() -> None:
    async def scenario() -> tuple[bool, float | None, tuple[float, float | None, bool]]:
        s, world = Setup(), engine()
        await step(s, world, PERIOD)
        s.link.connected.clear()
        due = s.due(world)
        await asyncio.sleep(0)
        paused = not due.done()
        s.ticker.advance(5.0)  # time passes while away: no step comes of it, nor a catch-up after
        s.link.connected.set()
        looked_again = await due
        return paused, looked_again, await step(s, world, PERIOD)

    paused, looked_again, (started, lateness, waited) = asyncio.run(scenario())
    assert paused and looked_again is None
    assert (started, lateness, waited) == (5.25 + PERIOD, 0.0, True), "one period after the return, not at once"


def test_the_papers_clock_waits_for_the_participant_and_logs_the_wait() -> None:
    async def scenario() -> tuple[float | None, float | None, float | None, list[Any], int]:
        s, world = Setup("wait_for_participant"), engine()
        due = s.due(world)
        await waits_on(s.clock, due)
        since = s.pacing.waiting_since
        s.clock.advance(3.0)
        world.controller.interrupt(Interrupt.UP)
        s.link.wake.set()
        looked_again = await due
        return since, looked_again, s.pacing.waiting_since, s.events.kept, s.nudges

    since, looked_again, after, events, nudges = asyncio.run(scenario())
    assert since == 0.0 and after is None, "the running wait is known while it lasts (the lease stores it)"
    assert looked_again is None and events == [("wait", {"seconds": 3.0})] and nudges == 1


def test_the_papers_clock_steps_for_a_key_and_not_again_until_the_next() -> None:
    async def scenario() -> tuple[float | None, bool]:
        s, world = Setup("wait_for_participant"), engine()
        world.controller.interrupt(Interrupt.STAY)
        lateness = await s.due(world)
        world.advance(Action.STAY)
        s.pacing.stepped(idle=not world.controller.has_action())
        again = s.due(world)
        await waits_on(s.clock, again)
        waiting = not again.done()
        again.cancel()
        return lateness, waiting

    lateness, waiting = asyncio.run(scenario())
    assert lateness == 0.0 and waiting


def test_a_task_that_would_do_nothing_is_refused_with_its_reason_and_the_world_does_not_step() -> None:
    async def scenario() -> tuple[float | None, list[Blocked], bool]:
        s = Setup("wait_for_participant")
        world = engine(world_with(pos=(5, 2), facing=Direction.NORTH, held=STEAK_PLATE, board=0))
        world.controller.select(Subtask.PICKUP_GARNISH, STEAK_PLATE)
        before = world.world
        return await s.due(world), s.refused, world.world == before

    due, refused, unchanged = asyncio.run(scenario())
    assert due is None and unchanged
    assert [b.reason.code for b in refused] == ["not_chopped"] and refused[0].ended


def test_the_round_ends_at_its_wall_clock_limit_counted_while_connected() -> None:
    async def scenario() -> tuple[float | None, bool, float | None, bool]:
        s, world = Setup("wait_for_participant", connected=False, max_round_seconds=30), engine()
        s.clock.advance(100.0)  # away: not counted
        s.link.connected.set()
        s.pacing.connected(idle=True)
        s.clock.advance(29.0)
        world.controller.interrupt(Interrupt.STAY)
        before = await s.due(world), s.pacing.timed_out
        s.clock.advance(1.0)
        return *before, await s.due(world), s.pacing.timed_out

    stepped, timed_out_before, after, timed_out = asyncio.run(scenario())
    assert stepped is not None and not timed_out_before
    assert after is None and timed_out


def test_a_fast_pilot_trial_steps_once_its_participant_answered_or_after_a_period() -> None:
    async def scenario() -> tuple[float | None, bool, float | None]:
        s, world = Setup(fast=True), engine()
        s.link.answered.set()
        at_once = await s.due(world)
        s.pacing.stepped(idle=False)
        waiting = s.due(world)
        await waits_on(s.ticker, waiting)
        held = not waiting.done()
        s.ticker.advance(PERIOD)
        return at_once, held, await waiting

    at_once, held, after_a_period = asyncio.run(scenario())
    assert at_once == 0.0 and held and after_a_period == 0.0
