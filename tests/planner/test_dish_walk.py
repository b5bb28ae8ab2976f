"""Behaviour 2's dish walk on predicted views (:func:`planner.dish_walk.dish_walk`) in the wait kitchen
(``steakhouse_wait_kitchen.py``): a robot with a dish at (1, 2) walks east along the top row to the serving counter
(7, 1) while the person stands at (4, 5) below the row, facing south (away from it) or north (the whole row in
view). The person's poses are given tick by tick, as the robot's rollouts predict them."""

from __future__ import annotations

import pytest
from steakhouse_wait_kitchen import WAIT_KITCHEN

from planner.dish_walk import dish_walk, seen_chances, walk_seen
from planner.geometry import Action, Direction
from planner.paths import distance, next_pose

LAYOUT = WAIT_KITCHEN
START = ((1, 2), Direction.NORTH)
SERVE = (7, 1)
SHORTEST = distance(LAYOUT, START, SERVE)
PERSON = (4, 5)


def person(turn_at: int | None, ticks: int = 20) -> list[tuple[tuple[int, int], Direction]]:
    """The person at (4, 5) facing south, and north from tick ``turn_at`` on (never: None)."""
    return [(PERSON, Direction.NORTH if turn_at is not None and t >= turn_at else Direction.SOUTH)
            for t in range(1, ticks + 1)]


def replay(plan, poses, garnish=False):
    """The robot's cells after each tick of ``plan`` before it delivers, and how many of the dish's ticks the person
    sees (:func:`planner.dish_walk.walk_seen`)."""
    pose, cells = START, []
    for action in plan[:-1]:  # the last is the interact that delivers
        if action.direction is not None:
            pose = next_pose(LAYOUT, pose, action.direction)
        cells.append(pose[0])
    seen, _ = walk_seen(LAYOUT, 120, START, plan, poses, garnish)
    return pose, cells, seen


def test_the_walk_ends_facing_the_counter_and_delivers():
    plan = dish_walk(LAYOUT, 120, START, [(1.0, person(None))], 4, 0.02, garnish=False)
    pose, _, _ = replay(plan, person(None))
    assert plan[-1] is Action.INTERACT and distance(LAYOUT, pose, SERVE) == 0


def test_a_person_who_never_turns_gets_the_shortest_walk():
    """Nothing of any walk is seen, so no extra tick is worth its price."""
    plan = dish_walk(LAYOUT, 120, START, [(1.0, person(None))], 4, 0.02, garnish=False)
    assert len(plan) == SHORTEST + 1 and Action.STAY not in plan


def test_the_robot_waits_for_a_person_predicted_to_turn_its_way():
    """Turning north at tick 4, the person sees the whole row from then on: the robot stays first, so more of its
    walk falls after the turn, and the person sees a larger share of the trip than going at once."""
    poses = person(4)
    plan = dish_walk(LAYOUT, 120, START, [(1.0, poses)], 4, 0.02, garnish=False)
    assert plan[0] is Action.STAY
    _, cells, seen = replay(plan, poses)
    going = dish_walk(LAYOUT, 120, START, [(1.0, poses)], 0, 0.02, garnish=False)
    _, going_cells, going_seen = replay(going, poses)
    assert seen / len(cells) > going_seen / len(going_cells)
    assert len(plan) <= SHORTEST + 1 + 4


def test_a_person_who_already_faces_the_row_needs_no_wait():
    plan = dish_walk(LAYOUT, 120, START, [(1.0, person(1))], 4, 0.02, garnish=False)
    assert len(plan) == SHORTEST + 1 and plan[0] is not Action.STAY


def test_no_budget_or_a_high_price_means_the_shortest_walk():
    for budget, price in ((0, 0.02), (4, 1.0)):
        plan = dish_walk(LAYOUT, 120, START, [(1.0, person(4))], budget, price, garnish=False)
        assert len(plan) == SHORTEST + 1 and Action.STAY not in plan


def test_at_a_ready_garnish_the_robot_waits_before_taking_it():
    """With a plated steak facing the garnish the plan is: stays, the interact that makes the dish, the walk."""
    poses = person(3)
    plan = dish_walk(LAYOUT, 120, START, [(1.0, poses)], 4, 0.02, garnish=True)
    first = plan.index(Action.INTERACT)
    assert first > 0 and set(plan[:first]) == {Action.STAY}
    assert plan[-1] is Action.INTERACT and plan.count(Action.INTERACT) == 2
    now = dish_walk(LAYOUT, 120, START, [(1.0, person(None))], 4, 0.02, garnish=True)
    assert now[0] is Action.INTERACT


def test_the_walk_never_steps_where_the_person_is_predicted_to_be():
    """The person stands on the row at (3, 2) facing west: the walk goes around them."""
    poses = [((3, 2), Direction.WEST)] * 20
    plan = dish_walk(LAYOUT, 120, START, [(1.0, poses)], 4, 0.02, garnish=False)
    _, cells, _ = replay(plan, poses)
    assert plan and (3, 2) not in cells


def test_hypotheses_are_weighed_by_their_probability():
    chances = seen_chances(LAYOUT, 120, [(0.25, person(1)), (0.75, person(None))], 3)
    assert chances[0][(4, 2)] == pytest.approx(0.25)
    assert chances[0][(4, 5)] == pytest.approx(1.0)  # the person's own cell, in every hypothesis


def test_no_serving_counter_or_no_prediction_no_plan():
    assert dish_walk(LAYOUT, 120, START, [], 4, 0.02, garnish=False) == ()


def test_a_walk_is_scored_on_the_poses_it_meets():
    """Going east at once along the top row: the person turned north at tick 4 sees the robot from (5, 2) on, the
    person facing south never; at a garnish the first tick (the interact) holds the dish too."""
    plan = (Action.EAST,) * 6 + (Action.INTERACT,)
    assert walk_seen(LAYOUT, 120, START, plan, person(None), garnish=False) == (0, 6)
    seen, ticks = walk_seen(LAYOUT, 120, START, plan, person(4), garnish=False)
    assert ticks == 6 and 0 < seen <= 3
    assert walk_seen(LAYOUT, 120, START, (Action.INTERACT,) + plan, person(1), garnish=True) == (7, 7)
