"""A worker's reply to a decision request, as the game loop's :class:`~server.robots.choice.RobotChoice`.

A decision is judged on when its answer was **sent** (``server.robots.deadline``, one clock for every process of
a machine), not on when the game loop got round to reading it: a full garbage collection of the server holds
all its threads for tens of ms at 60 trials, and an answer sent in time waits in the pipe meanwhile while the
tick it is for has not been applied yet. So when the deadline passes unanswered, the loop waits at most
``READ_GRACE_S`` for a reply already on its way, and takes it if it was sent by the deadline.
"""

from __future__ import annotations

import asyncio
import contextlib
import time
from typing import Any

from planner.geometry import Action
from server.robots import deadline as clock
from server.robots.choice import RobotChoice

READ_GRACE_S = 0.02
"""How long past an unanswered deadline the loop waits for a reply that may have been sent in time."""
Reply = tuple[str, Any, float]
"""``(status, payload, sent)``: ``sent`` is when the answer was sent (``server.robots.deadline.now``)."""


def lost() -> Reply:
    """The reply of a worker that is gone (dead, or never reached), as of now."""
    return ("lost", "worker_lost", clock.now())


async def await_reply(future: asyncio.Future[Reply], deadline: float, start: float) -> RobotChoice:
    """The choice ``future`` brings by ``deadline`` (``server.robots.deadline``); ``start`` is the
    ``time.perf_counter()`` of the request, for the round trip the loop saw."""
    with contextlib.suppress(TimeoutError):
        await asyncio.wait_for(asyncio.shield(future), clock.left(deadline))
    if not future.done():
        with contextlib.suppress(TimeoutError):
            await asyncio.wait_for(asyncio.shield(future), READ_GRACE_S)
    elapsed_ms = (time.perf_counter() - start) * 1000
    if not future.done() or not clock.met(future.result()[2], deadline):
        return RobotChoice(Action.STAY, decision_ms=elapsed_ms, missed=True)
    status, payload, _ = future.result()
    return choice_from_reply(status, payload, elapsed_ms)


def choice_from_reply(status: str, payload: Any, elapsed_ms: float) -> RobotChoice:
    """``("ok", (action, info))`` → the action; ``"lost"`` (no planner, dead worker) or ``"error"`` (the
    planner raised; ``payload`` is the message) → the robot stays, with the reason."""
    if status == "ok":
        action, info = payload
        return RobotChoice(Action(action), decision_ms=elapsed_ms, info=info)
    return RobotChoice(Action.STAY, decision_ms=elapsed_ms, error="worker_lost" if status == "lost" else payload)
