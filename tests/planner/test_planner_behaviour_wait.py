"""Behaviour 2's wait (docs/domain.md §5, "The person's knowing"; :meth:`planner.qmdp.QmdpRobot.wait_for_view`) in a
small hand-made kitchen: the robot holds a dish at (1, 2) and its way to the serving counter (7, 1) runs along the
top row, while the person stands at (4, 5) facing the counter below them, so no walk within the trip's detour
passes their view. The person's predicted poses are scripted (the rollout's person replaced tick by tick): when
the person is predicted to turn north four ticks from now, waiting three ticks brings the whole walk into their
view, and the FOV-aware robot waits; when the person never turns, or already faces north, it goes at once, and the
baseline always goes. The wait is an option, off by default (``wait_price`` 0); these tests set its price."""

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
WAITING = PlannerConfig(wait_price=0.2)
"""The wait is an option (off by default): the price it was measured with."""


def with_dish():
    return replace(initial_state(LAYOUT, RULES), human=PERSON, robot=AgentState((1, 2), Direction.NORTH, DISH),
                   boards=(0,))


def scripted(robot: QmdpRobot, turn_at: int | None) -> None:
    """The rollout's predicted person: at (4, 5) facing south, and north from tick ``turn_at`` on (never: None)."""
    original = robot.predicted_worlds

    def predicted(*args, **kwargs):  # type: ignore[no-untyped-def]
        worlds = original(*args, **kwargs)
        return [replace(w, human=replace(PERSON, facing=Direction.NORTH if turn_at is not None and t >= turn_at
                                         else Direction.SOUTH))
                for t, w in enumerate(worlds, 1)]
    robot.predicted_worlds = predicted  # type: ignore[method-assign]


def test_the_way_to_the_counter_is_out_of_the_persons_view_so_there_is_no_route_through_it():
    robot = make_qmdp_robot("fov_aware", LAYOUT, RULES, WAITING)
    world = with_dish()
    robot.reset(world)
    assert robot.view_route(world, Subtask.DELIVER_DISH) == ()


@pytest.mark.parametrize(("turn_at", "waits"), [(4, True), (None, False), (1, False)])
def test_the_robot_waits_only_for_a_person_predicted_to_turn_its_way(turn_at, waits):
    """Turning north at tick 4, the person sees the whole top row: going now, the robot is seen from (5, 2) on (4
    of its 7 ticks); after three ticks of waiting, its whole walk (7). Never turning, or facing north from the
    next tick on, a wait adds nothing to what the walk shows."""
    robot = make_qmdp_robot("fov_aware", LAYOUT, RULES, WAITING)
    world = with_dish()
    robot.reset(world)
    scripted(robot, turn_at)
    assert robot.wait_for_view(world, Subtask.DELIVER_DISH, LIKELY, 0, garnish=False) is waits


def test_no_wait_once_the_trips_detour_is_spent_or_without_a_price():
    robot = make_qmdp_robot("fov_aware", LAYOUT, RULES, WAITING)
    world = with_dish()
    robot.reset(world)
    scripted(robot, 4)
    robot.showing.trip_detour_left(world)  # the trip starts at tick 0
    late = replace(world, tick=PlannerConfig().view_detour)  # as many ticks waited as the detour allows
    assert not robot.wait_for_view(late, Subtask.DELIVER_DISH, LIKELY, 0, garnish=False)
    free = make_qmdp_robot("fov_aware", LAYOUT, RULES)  # the default: no price, no wait
    free.reset(world)
    scripted(free, 4)
    assert not free.wait_for_view(world, Subtask.DELIVER_DISH, LIKELY, 0, garnish=False)


@pytest.mark.parametrize("seed", range(3))
def test_the_fov_aware_robot_stays_for_the_turn_and_the_baseline_goes(seed):
    aware = make_qmdp_robot("fov_aware", LAYOUT, RULES, WAITING)
    world = with_dish()
    aware.reset(world)
    scripted(aware, 4)
    assert aware.decide(world, (), np.random.default_rng(seed)).action is Action.STAY
    unturned = make_qmdp_robot("fov_aware", LAYOUT, RULES, WAITING)
    unturned.reset(world)
    scripted(unturned, None)
    assert unturned.decide(world, (), np.random.default_rng(seed)).action is Action.EAST
    baseline = make_qmdp_robot("baseline", LAYOUT, RULES)
    baseline.reset(world)
    assert baseline.decide(world, (), np.random.default_rng(seed)).action is Action.EAST


def test_at_a_ready_garnish_the_wait_counts_against_the_dish_trip():
    """A plated steak before a chopped garnish (the board (3, 6), faced from (3, 5)) starts the dish trip: the
    ticks waited there come off the trip's detour."""
    robot = make_qmdp_robot("fov_aware", LAYOUT, RULES, WAITING)
    world = replace(initial_state(LAYOUT, RULES), human=AgentState((6, 2), Direction.NORTH),
                    robot=AgentState((3, 5), Direction.SOUTH, STEAK_PLATE), boards=(RULES.chop_time,))
    robot.reset(world)
    assert robot.at_ready_garnish(world)
    assert not robot.at_ready_garnish(replace(world, boards=(RULES.chop_time - 1,)))
    detour = PlannerConfig().view_detour
    assert robot.showing.waits(world, garnish=True) == detour and robot.showing.waits(world) == 0
    assert robot.showing.waits(replace(world, tick=2), garnish=True) == detour - 1
    dish = replace(world, tick=3, robot=replace(world.robot, held=DISH))
    robot.showing.observe(dish)
    assert robot.showing.trip_detour_left(dish) == detour - 2
