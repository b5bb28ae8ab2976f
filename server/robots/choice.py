"""What the game loop gets from a robot planner each tick, and the call that every pool shares.

A decision has a deadline (an absolute ``time.monotonic()``; by default 80 % of the tick period after the
world state was produced). A decision that arrives later is discarded: the robot stays that tick and the
loop logs a ``deadline_miss`` event. A planner error or a lost worker also makes the robot stay (logged as
an ``error`` event); the game goes on.
"""

from __future__ import annotations

import importlib
import time
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any, cast

import numpy as np

from planner.decision import Decision, Robot, RobotFactory
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


def load_factory(path: str) -> RobotFactory:
    """``"module:function"`` → the function (a :class:`planner.decision.RobotFactory`,
    ``factory(name, layout, rules, config)``)."""
    module, _, attr = path.partition(":")
    factory = getattr(importlib.import_module(module), attr)
    if not callable(factory):
        raise TypeError(f"{path} is not a robot factory (not callable)")
    return cast(RobotFactory, factory)


def robot_rng(seed: int, tick: int) -> np.random.Generator:
    """The robot's random stream for the decision at ``tick`` of the trial with ``seed``: a pure function of
    both, so a trial resumed at tick t (in any process) draws what it would have drawn."""
    return np.random.default_rng([seed, tick, 1])


def run_decision(policy: Robot, world: WorldState, events: Sequence[Event], seed: int, tick: int,
                 deadline: float) -> tuple[str, dict[str, Any]]:
    """Ask ``policy`` for its action; ``deadline`` is absolute ``time.monotonic()``. Returns the action's
    value and the decision record."""
    start = time.perf_counter()
    budget = max(deadline - time.monotonic(), 0.0)
    decision: Decision = policy.decide(world, events, robot_rng(seed, tick), start + budget)
    return decision.action.value, decision.to_dict()
