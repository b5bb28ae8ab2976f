"""What the game loop gets from a robot planner each tick, and the call that every pool shares.

A decision has a deadline (on the one clock of ``server.robots.deadline``; by default 80 % of the tick period
after the world state was produced). A decision that arrives later is discarded: the robot stays that tick and the
loop logs a ``deadline_miss`` event. A fault of the robot (it raised, answered an illegal decision or hung:
``planner.robot_guard``) or a lost worker also makes the robot stay (logged as an ``error`` event) and counts
toward the trial's robot health like a missed deadline; the game goes on.
"""

from __future__ import annotations

import importlib
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any, cast

from planner.decision import Robot
from planner.events import Event
from planner.geometry import Action
from planner.robot_catalog import RobotFactory
from planner.robot_guard import checked
from planner.state import WorldState
from planner.streams import robot_rng
from server.robots.deadline import for_planner


@dataclass(frozen=True, slots=True)
class RobotChoice:
    action: Action
    decision_ms: float | None = None
    """Round trip from request to answer, as the game loop saw it."""
    info: dict[str, Any] | None = None
    """``Decision.to_dict()``: q-values, belief over the participant's subtask, explored KBs, planner time."""
    missed: bool = False
    """The answer came after the deadline."""
    error: str | None = None
    """Why there was no decision: the robot's fault (``planner.robot_guard.describe``) or ``worker_lost``."""

    @property
    def failed(self) -> bool:
        """The robot stood still because it failed (not because it was late)."""
        return self.error is not None and not self.missed


STAY_CHOICE = RobotChoice(Action.STAY)


def load_factory(path: str) -> RobotFactory:
    """``"module:function"`` → the function (a :class:`planner.robot_catalog.RobotFactory`,
    ``factory(name, layout, rules, setup)``; by default :func:`planner.robot_catalog.build`)."""
    module, _, attr = path.partition(":")
    factory = getattr(importlib.import_module(module), attr)
    if not callable(factory):
        raise TypeError(f"{path} is not a robot factory (not callable)")
    return cast(RobotFactory, factory)


def run_decision(policy: Robot, world: WorldState, events: Sequence[Event], seed: int, tick: int,
                 deadline: float) -> tuple[str, dict[str, Any]]:
    """Ask ``policy`` for its action by ``deadline`` (``server.robots.deadline``). Returns the action's value and
    the decision record; raises what the robot raised, or ``planner.robot_guard.IllegalDecision``."""
    decision = checked(policy.decide(world, events, robot_rng(seed, tick), for_planner(deadline)))
    return decision.action.value, decision.to_dict()
