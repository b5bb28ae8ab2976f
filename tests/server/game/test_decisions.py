"""The robot's decisions (``server.game.decisions``): each tick's decision is asked for on that tick's world, with the
trial's budget; every decision is counted toward the robot's health, a late one logged as ``deadline_miss`` and a
failed one as an ``error``; a lost worker's planner is opened again on the world as it is; a fast pilot trial's robot
decides without the real-time deadline."""

from __future__ import annotations

import asyncio
import logging
from collections.abc import Sequence
from typing import Any

import pytest
from steakhouse_live_parts import Events, engine, meta
from steakhouse_testing import write_study

from planner.events import Event
from planner.geometry import Action
from planner.kb import KnowledgeBase
from planner.layout import Layout
from planner.robot_catalog import RobotSetup
from planner.rules import Rules
from planner.state import WorldState
from server.game.decisions import FIRST_DECISION_S, PILOT_DECISION_S, RobotDecisions
from server.robots import RobotChoice
from server.robots import deadline as decision_deadline
from study_config.catalog import LoadedStudy, load_one


class Pool:
    """A robot pool whose answers the test gives: ``answers`` in order, then ``stay``."""

    def __init__(self, *answers: RobotChoice, open_fails: bool = False) -> None:
        self.answers = list(answers)
        self.asked: list[tuple[int, float]] = []
        """The tick of each request and the seconds it was given."""
        self.opened: list[tuple[str, int]] = []
        self.open_fails = open_fails

    async def start(self) -> None: ...
    async def shutdown(self) -> None: ...

    async def open(self, trial_id: int, robot: str, layout: Layout, rules: Rules, setup: RobotSetup,
                   world: WorldState, kb: KnowledgeBase) -> None:
        if self.open_fails:
            raise RuntimeError("no worker")
        self.opened.append((robot, world.tick))

    async def decide(self, trial_id: int, world: WorldState, events: Sequence[Event], seed: int, tick: int,
                     deadline: float) -> RobotChoice:
        self.asked.append((tick, round(deadline - decision_deadline.now(), 2)))
        return self.answers.pop(0) if self.answers else RobotChoice(Action.STAY, decision_ms=1.0)

    async def close_trial(self, trial_id: int) -> None: ...

    def describe(self) -> dict[str, Any]:
        return {}


@pytest.fixture(scope="module")
def loaded(tmp_path_factory: pytest.TempPathFactory) -> LoadedStudy:
    return load_one(write_study(tmp_path_factory.mktemp("study")))


def robot(pool: Pool, loaded: LoadedStudy, events: Events, counted: list[tuple[bool, bool]],
          fast: bool = False) -> RobotDecisions:
    return RobotDecisions.paced(pool, meta(), loaded, fast=fast, period_s=0.2, deadline_fraction=0.5, log=events,
                                count=lambda missed, failed: counted.append((missed, failed)))


def test_each_decision_is_counted_and_a_late_or_failed_one_logged(loaded: LoadedStudy) -> None:
    async def scenario() -> tuple[list[Action], int]:
        pool = Pool(RobotChoice(Action.NORTH, decision_ms=3.0),
                    RobotChoice(Action.STAY, decision_ms=150.0, missed=True),
                    RobotChoice(Action.STAY, error="ValueError: boom"))
        decisions = robot(pool, loaded, events, counted)
        cook = engine()
        taken = []
        for _ in range(3):
            taken.append((await decisions.take(cook)).action)
            await decisions.stepped(cook)  # the same world: the request is for this tick again
        return taken, decisions.misses

    events, counted = Events(), list[tuple[bool, bool]]()
    taken, misses = asyncio.run(scenario())
    assert taken == [Action.NORTH, Action.STAY, Action.STAY] and misses == 1
    assert counted == [(False, False), (True, False), (False, True)], "the health counts late and failed apart"
    assert events.kept == [("deadline_miss", {"budget_ms": 100.0, "waited_ms": 150.0}),
                           ("error", {"code": "robot", "message": "ValueError: boom"})]


def test_the_decision_is_asked_for_the_tick_the_world_is_at(loaded: LoadedStudy) -> None:
    async def scenario() -> list[int]:
        pool, cook = Pool(), engine()
        decisions = robot(pool, loaded, Events(), [])
        await decisions.first(cook)
        cook.advance((await decisions.take(cook)).action)
        await decisions.take(cook)  # nothing was asked for tick 1 yet: asked now
        return [tick for tick, _ in pool.asked]

    assert asyncio.run(scenario()) == [0, 1]


def test_the_first_decision_has_longer_and_a_fast_pilot_trial_has_no_real_time_deadline(
        loaded: LoadedStudy, monkeypatch: pytest.MonkeyPatch) -> None:
    # The deadline clock stands still, so the budget the pool reads is the one given (a busy machine once let 10 ms
    # pass between setting the deadline and reading it).
    monkeypatch.setattr(decision_deadline, "now", lambda: 1000.0)

    async def budgets(fast: bool) -> list[float]:
        pool, cook = Pool(), engine()
        decisions = robot(pool, loaded, Events(), [], fast=fast)
        await decisions.first(cook)
        await decisions.take(cook)
        cook.advance(Action.STAY)
        await decisions.stepped(cook)
        await decisions.take(cook)
        return [budget for _, budget in pool.asked]

    assert asyncio.run(budgets(fast=False)) == [FIRST_DECISION_S, 0.1]  # the tick's: half of 0.2 s
    assert asyncio.run(budgets(fast=True)) == [PILOT_DECISION_S, PILOT_DECISION_S]


def test_a_lost_worker_is_replaced_on_the_world_as_it_is_and_a_failure_to_do_so_is_reported(
        loaded: LoadedStudy, caplog: pytest.LogCaptureFixture) -> None:
    async def scenario(pool: Pool) -> list[int]:
        cook, decisions = engine(), robot(pool, loaded, Events(), [])
        cook.advance((await decisions.take(cook)).action)
        await decisions.stepped(cook)
        await decisions.take(cook)
        return [tick for tick, _ in pool.asked]

    lost = RobotChoice(Action.STAY, error="worker_lost")
    pool = Pool(lost)
    assert asyncio.run(scenario(pool)) == [0, 1]
    assert pool.opened == [(loaded.planner("stay"), 1)]
    with caplog.at_level(logging.ERROR, logger="server.game.live"):
        assert asyncio.run(scenario(Pool(lost, open_fails=True))) == [0, 1], "the game goes on, the robot stays"
    assert "cannot re-open the planner of trial 7" in caplog.text


def test_no_decision_is_asked_for_once_the_round_is_over(loaded: LoadedStudy) -> None:
    async def scenario() -> tuple[list[int], bool]:
        pool = Pool()
        cook = engine(rules=Rules(orders=1, horizon=1))
        decisions = robot(pool, loaded, Events(), [])
        cook.advance((await decisions.take(cook)).action)
        await decisions.stepped(cook)
        return [tick for tick, _ in pool.asked], decisions.pending is None

    assert asyncio.run(scenario()) == ([0], True)
