"""The showing robot's dish trip and hands-walk leg (:mod:`planner.showing_walks`) in the small pickup kitchen of
``test_planner_behaviour_pickup.py``: a dish trip's detour budget runs down with every tick the dish takes beyond its
shortest way, its ticks in the person's view are counted as it goes, and a leg's budget likewise."""

from __future__ import annotations

from dataclasses import replace

from planner.geometry import Direction
from planner.layout import parse_layout
from planner.objects import DISH, MEAT
from planner.planner_config import PlannerConfig
from planner.rollout import Rollout
from planner.rules import Rules
from planner.showing_walks import ShowingWalks
from planner.state import AgentState, initial_state

RULES = Rules()
LAYOUT = parse_layout("\n".join([
    "XXXXXXXXX",
    "XMXDXWXXX",
    "X1      X",
    "X 2     X",
    "XOXBXXPSX",
    "XXXXXXXXX",
]), name="showing_test")
PERSON = AgentState((3, 3), Direction.SOUTH)


def world_with(held: str | None, robot_pos=(1, 2)):
    return replace(initial_state(LAYOUT, RULES), human=PERSON, robot=AgentState(robot_pos, Direction.NORTH, held))


def walks(config: PlannerConfig = PlannerConfig()) -> ShowingWalks:
    return ShowingWalks(LAYOUT, RULES, config, Rollout(LAYOUT, RULES, config))


def test_the_dish_trip_budget_runs_down_with_the_ticks_beyond_the_shortest_way():
    config = PlannerConfig()
    showing = walks(config)
    world = world_with(DISH)
    assert showing.trip_detour_left(world) == 0  # no trip yet: its first decision begins it
    showing.begin_trip(world)
    assert showing.trip_detour_left(world) == config.dish_detour
    later = replace(world, tick=world.tick + 3)  # three ticks later, no nearer the serving counter
    assert showing.trip_detour_left(later) == config.dish_detour - 3
    assert showing.walk_budget(replace(later, tick=later.tick + 5)) == 0  # spent: no detour, no wait
    showing.observe(world_with(None))
    assert showing.dish_trip is None and showing.trip_detour_left(world_with(None)) == 0


def test_the_dish_trips_ticks_in_the_persons_view_are_counted_until_the_dish_is_gone():
    """The person at (3, 3) faces south: (2, 3) beside them is in view, (1, 2) is not."""
    showing = walks()
    showing.observe(world_with(DISH))
    showing.observe(world_with(DISH, robot_pos=(2, 3)))
    showing.observe(world_with(DISH, robot_pos=(2, 3)))
    assert showing.trip_seen == (2, 3)
    showing.observe(world_with(None, robot_pos=(2, 3)))
    assert showing.trip_seen == (0, 0)


def test_a_legs_detour_runs_down_with_its_extra_ticks_and_restarts_with_new_hands_or_cells():
    """The hands walk's leg (:meth:`planner.showing_walks.ShowingWalks.leg_budget`): ``view_detour`` extra ticks in
    all, as a dish trip; a tick spent without coming closer uses one, a tick that comes closer none; other hands or
    another station start a new leg."""
    showing = walks()
    full = PlannerConfig().view_detour
    grill = ((6, 4),)
    world = world_with(MEAT)
    assert showing.leg_budget(world, grill, 7) == full
    assert showing.leg_budget(replace(world, tick=1), grill, 7) == full - 1  # stayed: no closer
    assert showing.leg_budget(replace(world, tick=2), grill, 6) == full - 1  # one tick closer
    assert showing.leg_budget(replace(world, tick=20), grill, 6) == 0  # never below nothing
    assert showing.leg_budget(replace(world_with(None), tick=20), grill, 6) == full  # empty hands: a new leg
    assert showing.leg_budget(replace(world_with(None), tick=21), ((3, 4),), 3) == full  # another station
