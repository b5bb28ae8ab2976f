"""What the game loop gets from a robot planner each tick, and the call that every pool shares.

A decision has a deadline (an absolute ``time.monotonic()``; by default 80 % of the tick period after the
world state was produced). A decision that arrives later is discarded: the robot stays that tick and the
loop logs a ``deadline_miss`` event. A planner error or a lost worker also makes the robot stay (logged as
an ``error`` event); the game goes on.
"""

from __future__ import annotations

import importlib
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from planner.decision import Decision
from planner.events import Event
from planner.geometry import Action
from planner.state import WorldState


@dataclass(frozen=True, slots=True)
class RobotChoice:
    action: Action
    decision_ms: float | None = None
    """Round trip from request to answer, as the game loop saw it."""
    info: dict[str, Any] | None = None
    """``Decision.to_dict()``: q-values, belief over the participant's subtask, explored KBs, planner time."""
    missed: bool = False
    error: str | None = None


STAY_CHOICE = RobotChoice(Action.STAY)


def load_factory(path: str) -> Callable[..., Any]:
    """``"module:function"`` → the function (a robot factory taking ``(name, layout, rules)``)."""
    module, _, attr = path.partition(":")
    return getattr(importlib.import_module(module), attr)  # type: ignore[no-any-return]


def run_decision(policy: Any, world: WorldState, events: Sequence[Event], seed: int, tick: int,
                 deadline: float) -> tuple[str, dict[str, Any]]:
    """Ask ``policy`` for its action; ``deadline`` is absolute ``time.monotonic()``. Returns the action's
    value and the decision record. Policies with only ``act`` (simulated partners) are accepted too."""
    rng = np.random.default_rng([seed, tick, 1])
    start = time.perf_counter()
    if hasattr(policy, "decide"):
        budget = max(deadline - time.monotonic(), 0.0)
        decision: Decision = policy.decide(world, events, rng, start + budget)
    else:
        action = policy.act(world, events, rng)
        decision = Decision(action, elapsed_ms=(time.perf_counter() - start) * 1000)
    return decision.action.value, decision.to_dict()
