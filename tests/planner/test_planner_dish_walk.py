"""Behaviour 2 in the FOV-aware robot's decisions (docs/domain.md §5, "The person's knowing";
:meth:`planner.qmdp.QmdpRobot.dish_walk`) in a small hand-made kitchen (``steakhouse_wait_kitchen.py``): the robot
holds a dish at (1, 2) and its way to the serving counter (7, 1) runs along the top row, while the person stands at
(4, 5) facing the counter below them, so no walk within the trip's detour passes their view. The person's predicted
poses are scripted (the rollout's person replaced tick by tick): when the person is predicted to turn north four
ticks from now, the FOV-aware robot waits for the turn; when the person never turns, or already faces north, it goes
at once, and the baseline always goes."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest
from steakhouse_wait_kitchen import WAIT_KITCHEN

from planner.geometry import Action, Direction
from planner.objects import DISH, STEAK_PLATE
from planner.planner_config import PlannerConfig
from planner.qmdp import QmdpRobot, make_qmdp_robot
from planner.rules import Rules
from planner.state import AgentState, initial_state
from planner.subtasks import Subtask

RULES = Rules(chop_time=12)
LAYOUT = WAIT_KITCHEN  # steakhouse_wait_kitchen.py
PERSON = AgentState((4, 5), Direction.SOUTH)
LIKELY = ((Subtask.PICKUP_MEAT, 1.0),)


def with_dish():
    return replace(initial_state(LAYOUT, RULES), human=PERSON, robot=AgentState((1, 2), Direction.NORTH, DISH),
                   boards=(0,))


def scripted(robot: QmdpRobot, turn_at: int | None) -> None:
    """The rollout's predicted person: at (4, 5) facing south, and north from tick ``turn_at`` on (never: None)."""
    original = robot.predicted_worlds

    def predicted(*args, **kwargs):
        worlds = original(*args, **kwargs)
        return [replace(w, human=replace(PERSON, facing=Direction.NORTH if turn_at is not None and t >= turn_at
                                         else Direction.SOUTH))
                for t, w in enumerate(worlds, 1)]
    robot.predicted_worlds = predicted  # type: ignore[method-assign]


@pytest.mark.parametrize(("turn_at", "first"), [(4, Action.STAY), (None, Action.EAST), (1, Action.EAST)])
def test_the_robot_waits_only_for_a_person_predicted_to_turn_its_way(turn_at, first):
    """Turning north at tick 4, the person sees the whole top row: going now, the robot is seen from (5, 2) on;
    after waiting, more of its walk. Never turning, or facing north from the next tick on, a wait adds nothing."""
    robot = make_qmdp_robot("fov_aware", LAYOUT, RULES)
    world = with_dish()
    robot.reset(world)
    robot.showing.begin_trip(world)  # as the decision does (Showing.start)
    scripted(robot, turn_at)
    assert robot.dish_walk(world, Subtask.DELIVER_DISH, LIKELY, 0, garnish=False)[0] is first


def test_no_wait_once_the_trips_detour_is_spent():
    robot = make_qmdp_robot("fov_aware", LAYOUT, RULES)
    world = with_dish()
    robot.reset(world)
    scripted(robot, 4)
    robot.showing.begin_trip(world)  # the trip starts at tick 0
    late = replace(world, tick=PlannerConfig().dish_detour)  # as many ticks waited as the detour allows
    assert robot.dish_walk(late, Subtask.DELIVER_DISH, LIKELY, 0, garnish=False)[0] is Action.EAST


@pytest.mark.parametrize("seed", range(3))
def test_the_fov_aware_robot_stays_for_the_turn_and_the_baseline_goes(seed):
    aware = make_qmdp_robot("fov_aware", LAYOUT, RULES)
    world = with_dish()
    aware.reset(world)
    scripted(aware, 4)
    assert aware.decide(world, (), np.random.default_rng(seed)).action is Action.STAY
    unturned = make_qmdp_robot("fov_aware", LAYOUT, RULES)
    unturned.reset(world)
    scripted(unturned, None)
    assert unturned.decide(world, (), np.random.default_rng(seed)).action is Action.EAST
    baseline = make_qmdp_robot("baseline", LAYOUT, RULES)
    baseline.reset(world)
    assert baseline.decide(world, (), np.random.default_rng(seed)).action is Action.EAST


def test_at_a_ready_garnish_the_wait_counts_against_the_dish_trip():
    """A plated steak before a chopped garnish (the board (3, 6), faced from (3, 5)) starts the dish trip: the
    ticks waited there come off the trip's detour."""
    robot = make_qmdp_robot("fov_aware", LAYOUT, RULES)
    world = replace(initial_state(LAYOUT, RULES), human=AgentState((6, 2), Direction.NORTH),
                    robot=AgentState((3, 5), Direction.SOUTH, STEAK_PLATE), boards=(RULES.chop_time,))
    robot.reset(world)
    assert robot.at_ready_garnish(world)
    assert not robot.at_ready_garnish(replace(world, boards=(RULES.chop_time - 1,)))
    detour = PlannerConfig().dish_detour
    robot.showing.begin_trip(world, garnish=True)
    assert robot.showing.walk_budget(world, garnish=True) == detour and robot.showing.walk_budget(world) == 0
    assert robot.showing.walk_budget(replace(world, tick=2), garnish=True) == detour - 1
    dish = replace(world, tick=3, robot=replace(world.robot, held=DISH))
    robot.showing.observe(dish)
    assert robot.showing.trip_detour_left(dish) == detour - 2
