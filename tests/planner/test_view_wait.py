"""Behaviour 2's wait scored on one predicted future (:func:`planner.view_wait.wait_gains`): a robot with the dish
walks east along the top row to the serving counter while the person stands below, facing away from the row and,
in one future, turning toward it four ticks from now."""

from __future__ import annotations

from dataclasses import replace

import pytest
from steakhouse_wait_kitchen import WAIT_KITCHEN

from planner.geometry import Direction
from planner.objects import DISH
from planner.rules import Rules
from planner.state import AgentState, WorldState, initial_state
from planner.view_wait import wait_gains

LAYOUT = WAIT_KITCHEN  # steakhouse_wait_kitchen.py
START = AgentState((1, 2), Direction.EAST, DISH)
PRICE = 0.2


def future(turn_at: int | None, *, carried: bool = True) -> list[WorldState]:
    """Ticks 1-6: the robot steps east from (1, 2) to (7, 2) with the dish (or empty-handed), at tick 7 it has
    served; the person stands at (4, 5) facing south, and north from ``turn_at`` on (never: None)."""
    start = initial_state(LAYOUT, Rules())
    worlds = []
    for t in range(1, 8):
        held = DISH if carried and t < 7 else None
        facing = Direction.NORTH if turn_at is not None and t >= turn_at else Direction.SOUTH
        worlds.append(replace(start, tick=t, robot=AgentState((min(1 + t, 7), 2), Direction.EAST, held),
                              human=AgentState((4, 5), facing)))
    return worlds


def test_a_person_who_never_turns_sees_no_part_of_the_walk_so_waiting_only_costs():
    assert wait_gains(LAYOUT, 120, START, future(None), 3, PRICE, garnish=False) == pytest.approx(
        [0.0, -PRICE, -2 * PRICE, -3 * PRICE])


def test_waiting_for_a_person_who_turns_brings_more_of_the_walk_into_view():
    gains = wait_gains(LAYOUT, 120, START, future(4), 3, PRICE, garnish=False)
    assert gains is not None
    seen = [g + PRICE * k for k, g in enumerate(gains)]
    assert seen[0] < seen[3] and seen == sorted(seen), seen
    assert max(range(4), key=lambda k: (gains[k], -k)) > 0


def test_no_dish_walk_no_gains():
    assert wait_gains(LAYOUT, 120, START, future(4, carried=False), 3, PRICE, garnish=False) is None
    assert wait_gains(LAYOUT, 120, START, [], 3, PRICE, garnish=False) is None


def test_at_a_ready_garnish_the_dish_must_be_made_at_once():
    late = [replace(w, robot=replace(w.robot, held=None)) if w.tick == 1 else w for w in future(4)]
    assert wait_gains(LAYOUT, 120, START, late, 3, PRICE, garnish=True) is None
    assert wait_gains(LAYOUT, 120, START, future(4), 3, PRICE, garnish=True) is not None
