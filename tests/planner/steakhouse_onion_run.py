"""Shared by the behaviour tests where the robot carries an onion the human does not know about: play the
robot (the human standing still) until the onion is on the board, tracking the human's KB."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pytest

from planner.events import Event
from planner.geometry import Action, Pos
from planner.kb import initial_kb, update_kb
from planner.layout import Layout
from planner.objects import ONION
from planner.planner_config import PlannerConfig
from planner.robots import make_robot
from planner.rules import Rules
from planner.state import WorldState
from planner.step import step


@dataclass(frozen=True)
class OnionRun:
    cells: list[Pos]
    """The robot's cell after each tick."""
    actions: list[Action]
    acknowledged: int | None
    """The tick at which the human's KB (120°, delay 3) acknowledged the onion; None if never."""


def carry_onion_to_board(layout: Layout, rules: Rules, name: str, seed: int, before: WorldState,
                         now: WorldState, max_ticks: int, config: PlannerConfig | None = None) -> OnionRun:
    """Robot ``name`` (reset on ``before``; ``config``: the planner's, default :class:`PlannerConfig`) plays from
    ``now`` until a board is loaded; fails the test if it takes more than ``max_ticks``."""
    robot = make_robot(name, layout, rules, config or PlannerConfig())
    robot.reset(before)
    kb = initial_kb(before)
    rng = np.random.default_rng(seed)
    cells: list[Pos] = []
    actions: list[Action] = []
    acknowledged = None
    world = now
    events: tuple[Event, ...] = ()
    for tick in range(max_ticks):
        action = robot.decide(world, events, rng).action
        actions.append(action)
        world, events = step(layout, world, {"human": Action.STAY, "robot": action}, rules)
        cells.append(world.robot.pos)
        kb = update_kb(kb, layout, world, angle=120, kb_delay=3)
        if acknowledged is None and kb.robot is not None and kb.robot.held == ONION:
            acknowledged = tick
        if any(board is not None for board in world.boards):
            return OnionRun(cells, actions, acknowledged)
    pytest.fail(f"{name} did not put the onion on the board in {max_ticks} ticks: {actions}")
