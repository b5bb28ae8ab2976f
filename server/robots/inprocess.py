"""Robot planners in the server process, on one dedicated thread (``robot_workers = 0``; tests, debugging).

Same semantics as the worker processes: requests are served one at a time in order, a decision finished
after its deadline is discarded (the thread finishes it in the background, so the next request waits for it).
One exception: a thread cannot be stopped, so a robot that hangs holds this pool up for good (the worker
processes stop it, ``server.robots.worker``).
"""

from __future__ import annotations

import asyncio
import time
from collections.abc import Callable, Sequence
from concurrent.futures import ThreadPoolExecutor
from typing import Any

from planner.decision import Robot
from planner.events import Event
from planner.kb import KnowledgeBase
from planner.layout import Layout
from planner.robot_catalog import RobotFactory, RobotSetup
from planner.robot_guard import describe
from planner.rules import Rules
from planner.state import WorldState
from server.robots import deadline as clock
from server.robots.choice import RobotChoice, run_decision
from server.robots.reply import Reply, await_reply


class InProcessRobots:
    def __init__(self, factory: RobotFactory) -> None:
        self.factory = factory
        self._policies: dict[int, Robot] = {}
        self._executor: ThreadPoolExecutor | None = None

    async def start(self) -> None:
        self._executor = ThreadPoolExecutor(max_workers=1, thread_name_prefix="robot")

    async def shutdown(self) -> None:
        if self._executor is not None:
            self._executor.shutdown(wait=True, cancel_futures=True)
            self._executor = None
        self._policies.clear()

    def _run(self, fn: Callable[..., Any], *args: Any) -> asyncio.Future[Any]:
        if self._executor is None:
            raise RuntimeError("the robot pool is not started")
        return asyncio.get_running_loop().run_in_executor(self._executor, fn, *args)

    async def open(self, trial_id: int, robot: str, layout: Layout, rules: Rules, setup: RobotSetup,
                   world: WorldState, kb: KnowledgeBase) -> None:
        def build() -> None:
            policy = self.factory(robot, layout, rules, setup)
            policy.reset(world, kb)
            self._policies[trial_id] = policy

        await self._run(build)

    async def decide(self, trial_id: int, world: WorldState, events: Sequence[Event], seed: int, tick: int,
                     deadline: float) -> RobotChoice:
        def call() -> Reply:
            policy = self._policies.get(trial_id)
            if policy is None:
                return ("lost", f"trial {trial_id} has no planner", clock.now())
            try:
                return ("ok", run_decision(policy, world, tuple(events), seed, tick, deadline), clock.now())
            except Exception as exc:  # a planner failure makes the robot stay
                return ("error", describe(exc), clock.now())

        start = time.perf_counter()
        return await await_reply(self._run(call), deadline, start)

    async def close_trial(self, trial_id: int) -> None:
        self._policies.pop(trial_id, None)

    def describe(self) -> dict[str, Any]:
        return {"mode": "in_process", "workers": 0, "trials": sorted(self._policies)}
