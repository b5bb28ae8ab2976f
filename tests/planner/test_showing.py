"""The FOV-aware robot's showing state (planner.showing) in the small pickup kitchen of
``test_planner_behaviour_pickup.py``: a show plan is followed only while the person stays as they were, and a
dish trip's detour budget runs down with every tick the dish takes beyond its shortest way, and the trip's ticks
in the person's view are counted as it goes."""

from __future__ import annotations

from dataclasses import replace

from planner.geometry import Action, Direction
from planner.kb import initial_kb
from planner.layout import parse_layout
from planner.objects import DISH, MEAT
from planner.planner_config import PlannerConfig
from planner.rules import Rules
from planner.showing import Showing
from planner.smoothing import ValueAverages
from planner.state import AgentState, initial_state
from planner.subtasks import Subtask

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


def test_a_kept_plan_is_followed_while_the_person_stays_and_the_kb_does_not_know():
    showing = Showing(LAYOUT, PlannerConfig())
    world = world_with(MEAT)
    kb = initial_kb(world_with(None))  # the person last saw the robot empty-handed
    showing.keep((Action.STAY, Action.STAY), world)
    assert showing.follow(world, kb) is Action.STAY
    turned = replace(world, human=replace(PERSON, facing=Direction.EAST))
    assert showing.follow(turned, kb) is None
    showing.keep((Action.STAY,), world)
    assert showing.follow(world, initial_kb(world)) is None  # the KB knows the meat: nothing left to show


def test_the_dish_trip_budget_runs_down_with_the_ticks_beyond_the_shortest_way():
    config = PlannerConfig()
    showing = Showing(LAYOUT, config)
    world = world_with(DISH)
    assert showing.trip_detour_left(world) == 0  # no trip yet: its first decision begins it
    showing.begin_trip(world)
    assert showing.trip_detour_left(world) == config.dish_detour
    later = replace(world, tick=world.tick + 3)  # three ticks later, no nearer the serving counter
    assert showing.trip_detour_left(later) == config.dish_detour - 3
    assert showing.walk_budget(replace(later, tick=later.tick + 5)) == 0  # spent: no detour, no wait
    showing.observe(world_with(None))
    assert showing.dish_trip is None and showing.trip_detour_left(world_with(None)) == 0


def test_value_averages_restart_when_the_robots_hands_or_the_orders_change():
    values = ValueAverages(0.5)
    values.restart_on((None, 2))
    assert values.fold(Subtask.PICKUP_MEAT, 10.0) == 10.0
    assert values.fold(Subtask.PICKUP_MEAT, 20.0) == 15.0
    values.restart_on((None, 2))
    assert values.fold(Subtask.PICKUP_MEAT, 5.0) == 10.0
    values.restart_on((MEAT, 2))
    assert values.fold(Subtask.PICKUP_MEAT, 5.0) == 5.0


def test_the_dish_trips_ticks_in_the_persons_view_are_counted_until_the_dish_is_gone():
    """The person at (3, 3) faces south: (2, 3) beside them is in view, (1, 2) is not."""
    showing = Showing(LAYOUT, PlannerConfig())
    showing.observe(world_with(DISH))
    showing.observe(world_with(DISH, robot_pos=(2, 3)))
    showing.observe(world_with(DISH, robot_pos=(2, 3)))
    assert showing.trip_seen == (2, 3)
    showing.observe(world_with(None, robot_pos=(2, 3)))
    assert showing.trip_seen == (0, 0)


def test_a_legs_detour_runs_down_with_its_extra_ticks_and_restarts_with_new_hands_or_cells():
    """The hands walk's leg (:meth:`planner.showing.Showing.leg_budget`): ``view_detour`` extra ticks in all, as a
    dish trip; a tick spent without coming closer uses one, a tick that comes closer none; other hands or another
    station start a new leg."""
    showing = Showing(LAYOUT, PlannerConfig())
    full = PlannerConfig().view_detour
    grill = ((6, 4),)
    world = world_with(MEAT)
    assert showing.leg_budget(world, grill, 7) == full
    assert showing.leg_budget(replace(world, tick=1), grill, 7) == full - 1  # stayed: no closer
    assert showing.leg_budget(replace(world, tick=2), grill, 6) == full - 1  # one tick closer
    assert showing.leg_budget(replace(world, tick=20), grill, 6) == 0  # never below nothing
    assert showing.leg_budget(replace(world_with(None), tick=20), grill, 6) == full  # empty hands: a new leg
    assert showing.leg_budget(replace(world_with(None), tick=21), ((3, 4),), 3) == full  # another station
