"""The show plan the FOV-aware robots follow (:mod:`planner.show_plan`) in the small pickup kitchen of
``test_planner_behaviour_pickup.py``: a kept plan is followed only while the person stays as they were and the KB
does not know what the robot holds."""

from __future__ import annotations

from dataclasses import replace

from planner.geometry import Action, Direction
from planner.kb import initial_kb
from planner.layout import parse_layout
from planner.objects import MEAT
from planner.rules import Rules
from planner.show_plan import ShowPlan
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


def test_a_kept_plan_is_followed_while_the_person_stays_and_the_kb_does_not_know():
    show = ShowPlan(LAYOUT, 120, 3, 6)
    world = world_with(MEAT)
    kb = initial_kb(world_with(None))  # the person last saw the robot empty-handed
    show.keep((Action.STAY, Action.STAY), world)
    assert show.follow(world, kb) is Action.STAY
    turned = replace(world, human=replace(PERSON, facing=Direction.EAST))
    assert show.follow(turned, kb) is None
    show.keep((Action.STAY,), world)
    assert show.follow(world, initial_kb(world)) is None  # the KB knows the meat: nothing left to show


def test_the_plan_walks_into_the_view_and_stays_for_the_delay_within_its_detour():
    """The person at (3, 3) faces south: (2, 3) beside them is in view, the robot's (1, 2) is not. With meat the
    person has not seen, the way to the grill (6, 4) through (2, 3) and a wait there is within 6 extra ticks; with no
    detour at all there is none, and a KB that knows the meat needs none."""
    world = world_with(MEAT)
    kb = initial_kb(world_with(None))
    plan = ShowPlan(LAYOUT, 120, 3, 6).plan(world, kb, ((6, 4),))
    assert plan and plan[:3] == (Action.SOUTH, Action.EAST, Action.STAY)
    assert ShowPlan(LAYOUT, 120, 3, 0).plan(world, kb, ((6, 4),)) == ()
    assert ShowPlan(LAYOUT, 120, 3, 6).plan(world, initial_kb(world), ((6, 4),)) == ()
