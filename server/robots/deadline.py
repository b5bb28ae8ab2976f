"""A robot decision's deadline, on one clock: where it is set, how long is left, and whether an answer met it.

The clock is ``time.monotonic()`` (one clock for every process of a machine): the game loop sets a deadline with
:func:`after`, a worker stamps its answer with :func:`now` as it sends it, and :func:`met` judges the answer on
that stamp (``server.robots.reply``), never on when the loop got round to reading it. The planner counts its own
time on ``time.perf_counter()`` (``planner.decision.Robot``); :func:`for_planner` hands it the same deadline on
that clock. A decision that misses its deadline makes the robot stay that tick (``server.robots.choice``) and counts
toward the trial's robot health (``server.game.health``).
"""

from __future__ import annotations

import time


def now() -> float:
    """The deadline clock now."""
    return time.monotonic()


def after(budget_s: float) -> float:
    """The deadline ``budget_s`` seconds from now."""
    return now() + budget_s


def left(deadline: float) -> float:
    """Seconds until ``deadline`` (0 once it has passed)."""
    return max(deadline - now(), 0.0)


def met(sent: float, deadline: float) -> bool:
    """Whether an answer sent at ``sent`` (:func:`now` when it was sent) met ``deadline``."""
    return sent <= deadline


def for_planner(deadline: float) -> float:
    """``deadline`` on the planner's clock (``time.perf_counter()``)."""
    return time.perf_counter() + left(deadline)
