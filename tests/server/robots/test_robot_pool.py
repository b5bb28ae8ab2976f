"""Robot planners off the event loop: each trial pinned to one worker process that keeps its planner,
deadlines enforced (a late decision means the robot stays), planner failures and dead workers survived."""

from __future__ import annotations

import asyncio
import time

import pytest
from steakhouse_test_robots import counting, failing, slow

from planner.geometry import Action
from planner.kb import initial_kb
from planner.robot_catalog import RobotSetup
from planner.rules import Rules
from planner.state import initial_state
from server.robots import InProcessRobots, ProcessRobots
from study_config import load_layout

LAYOUT = load_layout("practice")
RULES = Rules()
CONFIG = RobotSetup()
WORLD = initial_state(LAYOUT, RULES)
KB = initial_kb(WORLD)


async def decide(pool, trial: int, budget: float = 2.0):
    return await pool.decide(trial, WORLD, (), 1, 0, time.monotonic() + budget)


def test_each_trial_keeps_its_planner_in_one_worker_process():
    async def run():
        pool = ProcessRobots(2, "steakhouse_test_robots:counting")
        await pool.start()
        try:
            await pool.open(1, "any", LAYOUT, RULES, CONFIG, WORLD, KB)
            await pool.open(2, "any", LAYOUT, RULES, CONFIG, WORLD, KB)
            choices = {t: [await decide(pool, t) for _ in range(3)] for t in (1, 2)}
            described = pool.describe()
        finally:
            await pool.shutdown()
        return choices, described

    choices, described = asyncio.run(run())
    for trial in (1, 2):
        assert [c.info["q_values"]["calls"] for c in choices[trial]] == [1, 2, 3]
        assert [c.action for c in choices[trial]] == [Action.NORTH, Action.SOUTH, Action.NORTH]
        assert len({c.info["q_values"]["pid"] for c in choices[trial]}) == 1
        assert all(c.decision_ms is not None and not c.missed for c in choices[trial])
    assert choices[1][0].info["q_values"]["pid"] != choices[2][0].info["q_values"]["pid"]
    assert sorted(len(w["trials"]) for w in described["workers"]) == [1, 1]


def test_a_late_decision_is_discarded_and_the_robot_stays():
    async def run():
        pool = ProcessRobots(1, "steakhouse_test_robots:slow")
        await pool.start()
        try:
            await pool.open(1, "any", LAYOUT, RULES, CONFIG, WORLD, KB)
            late = await decide(pool, 1, budget=0.05)
            await asyncio.sleep(0.4)
            on_time = await decide(pool, 1, budget=2.0)
        finally:
            await pool.shutdown()
        return late, on_time

    late, on_time = asyncio.run(run())
    assert late.missed and late.action is Action.STAY and late.decision_ms < 200
    assert not on_time.missed and on_time.info["q_values"]["calls"] == 2, "the late decision still ran"


def test_a_failing_planner_and_a_dead_worker_make_the_robot_stay_until_reopened():
    async def run():
        failing_pool = ProcessRobots(1, "steakhouse_test_robots:failing")
        crashing_pool = ProcessRobots(1, "steakhouse_test_robots:crashing")
        await failing_pool.start()
        await crashing_pool.start()
        try:
            await failing_pool.open(1, "any", LAYOUT, RULES, CONFIG, WORLD, KB)
            failed = await decide(failing_pool, 1)
            await crashing_pool.open(7, "any", LAYOUT, RULES, CONFIG, WORLD, KB)
            before = [await decide(crashing_pool, 7) for _ in range(2)]
            crashed = await decide(crashing_pool, 7)
            after_crash = await decide(crashing_pool, 7)
            await crashing_pool.open(7, "any", LAYOUT, RULES, CONFIG, WORLD, KB)
            reopened = await decide(crashing_pool, 7)
        finally:
            await failing_pool.shutdown()
            await crashing_pool.shutdown()
        return failed, before, crashed, after_crash, reopened

    failed, before, crashed, after_crash, reopened = asyncio.run(run())
    assert failed.action is Action.STAY and failed.error == "raised ValueError: planner bug"
    assert [c.action for c in before] == [Action.NORTH, Action.SOUTH]
    assert crashed.error == "worker_lost" and crashed.action is Action.STAY
    assert after_crash.error == "worker_lost"
    assert reopened.error is None and reopened.info["q_values"]["calls"] == 1
    assert reopened.info["q_values"]["pid"] != before[0].info["q_values"]["pid"]


@pytest.mark.parametrize("factory,expect", [(counting, "ok"), (slow, "missed"), (failing, "error")])
def test_the_in_process_pool_has_the_same_rules(factory, expect):
    async def run():
        pool = InProcessRobots(factory)
        await pool.start()
        try:
            await pool.open(1, "any", LAYOUT, RULES, CONFIG, WORLD, KB)
            return await decide(pool, 1, budget=0.1), await decide(pool, 99)
        finally:
            await pool.shutdown()

    choice, unknown = asyncio.run(run())
    assert unknown.error == "worker_lost" and unknown.action is Action.STAY
    if expect == "ok":
        assert choice.action is Action.NORTH and not choice.missed and choice.error is None
    elif expect == "missed":
        assert choice.missed and choice.action is Action.STAY
    else:
        assert choice.error == "raised ValueError: planner bug"


def test_a_worker_keeps_what_its_planners_built_out_of_full_collections():
    """A full garbage collection of a worker's grown planner caches held decisions up past their deadline:
    a worker freezes what exists once a trial opens (and every ``FREEZE_EVERY`` requests)."""
    async def run():
        pool = ProcessRobots(1, "steakhouse_test_robots:gc_probe")
        await pool.start()
        try:
            await pool.open(1, "any", LAYOUT, RULES, CONFIG, WORLD, KB)
            return (await decide(pool, 1)).info["q_values"]["frozen"]
        finally:
            await pool.shutdown()

    assert asyncio.run(run()) > 1000


def test_an_answer_sent_in_time_counts_when_the_server_was_held_past_the_deadline():
    """A full garbage collection of the server holds its interpreter (every thread of it) for tens of ms at
    60 trials. An answer the worker sent before the deadline is in the pipe when the server comes back, and
    the tick it is for has not been applied yet: it counts, rather than being judged on when the server got
    round to reading it."""
    import sys

    async def run():
        pool = ProcessRobots(1, "steakhouse_test_robots:counting")
        await pool.start()
        interval = sys.getswitchinterval()
        try:
            await pool.open(1, "any", LAYOUT, RULES, CONFIG, WORLD, KB)
            pending = asyncio.create_task(decide(pool, 1, budget=0.15))
            await asyncio.sleep(0)  # the request is on its way
            sys.setswitchinterval(10.0)  # like a collection: no other thread of the server runs meanwhile
            held_until = time.monotonic() + 0.6
            while time.monotonic() < held_until:
                pass
            sys.setswitchinterval(interval)
            return await pending
        finally:
            sys.setswitchinterval(interval)
            await pool.shutdown()

    choice = asyncio.run(run())
    assert not choice.missed and choice.action is Action.NORTH
    assert choice.decision_ms > 150, "the server was held past the deadline"
