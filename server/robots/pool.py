"""Robot worker processes: each live trial is pinned to one worker, which holds its planner all trial long.

Planners are stateful (a belief over the participant's subtask, a modelled KB), so every decision of a
trial must reach the same process. ``open`` pins a trial to the worker with the fewest trials; ``decide``
sends the world to that worker and waits until the deadline; ``close_trial`` frees the planner. A worker
that dies (its planner crashed the interpreter, it was killed) fails its pending and later requests with
``error = "worker_lost"``; the next ``open`` of an affected trial starts a fresh process.

Processes are started with ``spawn`` (no fork of a running event loop). Replies are read by one thread per
worker and handed to the event loop, so nothing blocks the loop. (Not ``loop.add_reader``: uvloop makes a
watched file descriptor non-blocking, and the requests go out on the same one.)
Deadlines are judged on when the worker sent its answer (:mod:`server.robots.reply`).
"""

from __future__ import annotations

import asyncio
import contextlib
import itertools
import logging
import multiprocessing
import threading
import time
from collections.abc import Sequence
from typing import Any, Protocol

from planner.events import Event
from planner.geometry import Action
from planner.kb import KnowledgeBase
from planner.layout import Layout
from planner.robot_catalog import RobotFactory, RobotSetup
from planner.rules import Rules
from planner.state import WorldState
from server.robots.choice import RobotChoice
from server.robots.reply import Reply, await_reply, lost
from server.robots.worker import worker_main

log = logging.getLogger(__name__)
OPEN_TIMEOUT_S = 60.0


class RobotPool(Protocol):
    async def start(self) -> None: ...
    async def shutdown(self) -> None: ...
    async def open(self, trial_id: int, robot: str, layout: Layout, rules: Rules, setup: RobotSetup,
                   world: WorldState, kb: KnowledgeBase) -> None:
        """Build trial ``trial_id``'s planner with the factory, ``factory(robot, layout, rules, setup)``, and
        reset it on ``world`` and ``kb``, the participant's modelled KB there (the engine's: the initial KB at
        tick 0, the restored one when the trial resumes), so the robot's model of the person goes on from
        the one the server logs. ``setup`` is the person the study shows (its FOV angle and KB delay) and the robot's
        settings (``study_config.catalog.LoadedStudy.robot_setup``)."""
    async def decide(self, trial_id: int, world: WorldState, events: Sequence[Event], seed: int, tick: int,
                     deadline: float) -> RobotChoice: ...
    async def close_trial(self, trial_id: int) -> None: ...
    def describe(self) -> dict[str, Any]: ...


class _Worker:
    """One process, its pipe, its reply-reading thread and the futures waiting for replies."""

    def __init__(self, index: int, factory_path: str) -> None:
        self.index, self.factory_path = index, factory_path
        self.trials: set[int] = set()
        self.pending: dict[int, asyncio.Future[Reply]] = {}
        self.alive = False
        self.process: Any = None
        self.conn: Any = None
        self._send_lock = threading.Lock()
        self._ids = itertools.count(1)

    def start(self, loop: asyncio.AbstractEventLoop) -> None:
        context = multiprocessing.get_context("spawn")
        parent, child = context.Pipe()
        self.process = context.Process(target=worker_main, args=(child, self.factory_path),
                                       name=f"steakhouse-robot-{self.index}", daemon=True)
        self.process.start()
        child.close()
        self.conn, self.alive, self.trials = parent, True, set()
        threading.Thread(target=self._read, args=(loop, parent), name=f"robot-reader-{self.index}",
                         daemon=True).start()

    def _read(self, loop: asyncio.AbstractEventLoop, conn: Any) -> None:
        while True:
            try:
                req, status, payload, sent = conn.recv()
            except (EOFError, OSError):
                break
            try:
                loop.call_soon_threadsafe(self._resolve, req, status, payload, sent)
            except RuntimeError:
                return
        with contextlib.suppress(RuntimeError):
            loop.call_soon_threadsafe(self._lost, conn)

    def _resolve(self, req: int, status: str, payload: Any, sent: float) -> None:
        future = self.pending.pop(req, None)
        if future is not None and not future.done():
            future.set_result((status, payload, sent))

    def _lost(self, conn: Any) -> None:
        if conn is not self.conn:
            return
        if self.alive:
            log.error("robot worker %d stopped; its trials' robots stay until re-opened", self.index)
        self.alive = False
        for future in self.pending.values():
            if not future.done():
                future.set_result(lost())
        self.pending.clear()

    def request(self, op: str, *args: Any) -> asyncio.Future[Reply]:
        """Send ``(op, req, *args)``; the future gets ``(status, payload, sent)`` (``"lost"`` if the worker
        died), ``sent`` being when the worker sent its reply (``server.robots.deadline.now``)."""
        req = next(self._ids)
        message = (op, req, *args)
        future: asyncio.Future[Reply] = asyncio.get_running_loop().create_future()
        if not self.alive:
            future.set_result(lost())
            return future
        self.pending[req] = future
        try:
            with self._send_lock:
                self.conn.send(message)
        except (BrokenPipeError, OSError):
            self.pending.pop(req, None)
            future.set_result(lost())
        return future

    def stop(self) -> None:
        self.alive = False
        if self.conn is not None:
            try:
                with self._send_lock:
                    self.conn.send(("stop",))
            except (BrokenPipeError, OSError):
                pass
        if self.process is not None:
            self.process.join(timeout=5)
            if self.process.is_alive():
                self.process.kill()
                self.process.join(timeout=5)
            self.process.close()
            self.process = None
        if self.conn is not None:
            self.conn.close()
            self.conn = None


class ProcessRobots:
    def __init__(self, workers: int, factory_path: str) -> None:
        if workers < 1:
            raise ValueError("a process pool needs at least one worker")
        self._workers = [_Worker(i, factory_path) for i in range(workers)]
        self._pins: dict[int, _Worker] = {}

    async def start(self) -> None:
        loop = asyncio.get_running_loop()
        for worker in self._workers:
            await asyncio.to_thread(worker.start, loop)

    async def shutdown(self) -> None:
        for worker in self._workers:
            await asyncio.to_thread(worker.stop)
        self._pins.clear()

    async def open(self, trial_id: int, robot: str, layout: Layout, rules: Rules, setup: RobotSetup,
                   world: WorldState, kb: KnowledgeBase) -> None:
        """Pin ``trial_id`` to the least-loaded worker and build its planner there (restarting a dead one)."""
        await self.close_trial(trial_id)
        for dead in [w for w in self._workers if not w.alive]:
            await asyncio.to_thread(dead.stop)
            await asyncio.to_thread(dead.start, asyncio.get_running_loop())
        worker = min(self._workers, key=lambda w: (len(w.trials), w.index))
        worker.trials.add(trial_id)
        self._pins[trial_id] = worker
        status, payload, _ = await asyncio.wait_for(
            worker.request("open", trial_id, robot, layout, rules, setup, world, kb), OPEN_TIMEOUT_S)
        if status != "ok":
            worker.trials.discard(trial_id)
            self._pins.pop(trial_id, None)
            raise RuntimeError(f"cannot start robot {robot!r}: {payload}")

    async def decide(self, trial_id: int, world: WorldState, events: Sequence[Event], seed: int, tick: int,
                     deadline: float) -> RobotChoice:
        worker = self._pins.get(trial_id)
        if worker is None:
            return RobotChoice(Action.STAY, error="worker_lost")
        start = time.perf_counter()
        future = worker.request("decide", trial_id, world, tuple(events), seed, tick, deadline)
        return await await_reply(future, deadline, start)

    async def close_trial(self, trial_id: int) -> None:
        worker = self._pins.pop(trial_id, None)
        if worker is None:
            return
        worker.trials.discard(trial_id)
        if worker.alive:
            worker.request("close", trial_id)

    def describe(self) -> dict[str, Any]:
        return {"mode": "processes", "workers": [
            {"index": w.index, "alive": w.alive, "trials": sorted(w.trials),
             "pid": w.process.pid if w.process is not None else None} for w in self._workers]}


def make_pool(workers: int, factory_path: str, factory: RobotFactory | None = None) -> RobotPool:
    """Worker processes when ``workers`` > 0, else the in-process thread (with ``factory`` if given)."""
    if workers > 0:
        return ProcessRobots(workers, factory_path)
    from server.robots.choice import load_factory
    from server.robots.inprocess import InProcessRobots

    return InProcessRobots(factory or load_factory(factory_path))
