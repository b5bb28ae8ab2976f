"""Behaviour 2 in the showing robot's decisions (docs/domain.md §5, "The showing robot";
:meth:`planner.showing_walks.ShowingWalks.dish_walk`) in a small hand-made kitchen (``steakhouse_wait_kitchen.py``):
the robot holds a dish at (1, 2) and its way to the serving counter (7, 1) runs along the top row, while the person
stands at (4, 5) facing the counter below them, so no walk within the trip's detour passes their view. The person's
predicted poses are scripted (the rollouts' person replaced tick by tick): when the person is predicted to turn
north four ticks from now, the showing robot waits for the turn; when the person never turns, or already faces
north, it goes at once, and the default FOV-aware robot and the baseline always go."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest
from steakhouse_wait_kitchen import WAIT_KITCHEN

from planner.flicker import FlickerWatch
from planner.geometry import Action, Direction
from planner.moment import Moment
from planner.objects import DISH, STEAK_PLATE
from planner.planner_config import PlannerConfig
from planner.qmdp import QmdpRobot, make_qmdp_robot
from planner.rules import Rules
from planner.showing_walks import ShowingWalks
from planner.state import AgentState, initial_state
from planner.subtasks import Subtask

RULES = Rules(chop_time=12)
LAYOUT = WAIT_KITCHEN  # steakhouse_wait_kitchen.py
PERSON = AgentState((4, 5), Direction.SOUTH)
LIKELY = ((Subtask.PICKUP_MEAT, 1.0),)


def with_dish():
    return replace(initial_state(LAYOUT, RULES), human=PERSON, robot=AgentState((1, 2), Direction.NORTH, DISH),
                   boards=(0,))


def showing(world) -> tuple[QmdpRobot, ShowingWalks]:
    robot = make_qmdp_robot("fov_aware_showing", LAYOUT, RULES)
    robot.reset(world)
    assert robot.walks is not None
    return robot, robot.walks


def moment(robot: QmdpRobot, world) -> Moment:
    """The decision's situation as :meth:`planner.qmdp.QmdpRobot.choose` builds it, the person on ``LIKELY``."""
    assert robot.kb is not None
    return Moment(world, robot.kb, LIKELY, 0, 42, 0, False, True, None, FlickerWatch())


def scripted(walks: ShowingWalks, turn_at: int | None) -> None:
    """The rollouts' predicted person: at (4, 5) facing south, and north from tick ``turn_at`` on (never: None)."""
    original = walks.futures

    def futures(m, subtask, ticks):
        return [(p, [(PERSON.pos, Direction.NORTH if turn_at is not None and t >= turn_at else Direction.SOUTH)
                     for t, _ in enumerate(poses, 1)]) for p, poses in original(m, subtask, ticks)]
    walks.futures = futures  # type: ignore[method-assign]


@pytest.mark.parametrize(("turn_at", "first"), [(4, Action.STAY), (None, Action.EAST), (1, Action.EAST)])
def test_the_robot_waits_only_for_a_person_predicted_to_turn_its_way(turn_at, first):
    """Turning north at tick 4, the person sees the whole top row: going now, the robot is seen from (5, 2) on;
    after waiting, more of its walk. Never turning, or facing north from the next tick on, a wait adds nothing."""
    world = with_dish()
    robot, walks = showing(world)
    walks.begin_trip(world)  # as the decision does
    scripted(walks, turn_at)
    assert walks.dish_walk(moment(robot, world), Subtask.DELIVER_DISH, garnish=False)[0] is first


def test_no_wait_once_the_trips_detour_is_spent():
    world = with_dish()
    robot, walks = showing(world)
    scripted(walks, 4)
    walks.begin_trip(world)  # the trip starts at tick 0
    late = replace(world, tick=PlannerConfig().dish_detour)  # as many ticks waited as the detour allows
    assert walks.dish_walk(moment(robot, late), Subtask.DELIVER_DISH, garnish=False)[0] is Action.EAST


@pytest.mark.parametrize("seed", range(3))
def test_the_showing_robot_stays_for_the_turn_and_the_others_go(seed):
    world = with_dish()
    aware, walks = showing(world)
    scripted(walks, 4)
    assert aware.decide(world, (), np.random.default_rng(seed)).action is Action.STAY
    unturned, walks = showing(world)
    scripted(walks, None)
    assert unturned.decide(world, (), np.random.default_rng(seed)).action is Action.EAST
    for name in ("fov_aware", "baseline"):
        other = make_qmdp_robot(name, LAYOUT, RULES)
        other.reset(world)
        assert other.decide(world, (), np.random.default_rng(seed)).action is Action.EAST, name


def test_at_a_ready_garnish_the_wait_counts_against_the_dish_trip():
    """A plated steak before a chopped garnish (the board (3, 6), faced from (3, 5)) starts the dish trip: the
    ticks waited there come off the trip's detour."""
    world = replace(initial_state(LAYOUT, RULES), human=AgentState((6, 2), Direction.NORTH),
                    robot=AgentState((3, 5), Direction.SOUTH, STEAK_PLATE), boards=(RULES.chop_time,))
    _, walks = showing(world)
    assert walks.at_ready_garnish(world)
    assert not walks.at_ready_garnish(replace(world, boards=(RULES.chop_time - 1,)))
    detour = PlannerConfig().dish_detour
    walks.begin_trip(world, garnish=True)
    assert walks.walk_budget(world, garnish=True) == detour and walks.walk_budget(world) == 0
    assert walks.walk_budget(replace(world, tick=2), garnish=True) == detour - 1
    dish = replace(world, tick=3, robot=replace(world.robot, held=DISH))
    walks.observe(dish)
    assert walks.trip_detour_left(dish) == detour - 2
