"""No flicker (:mod:`planner.flicker`; docs/domain.md §5, "No flicker"): the robot never undoes its own last touch
of a counter while nothing else has changed, and a trial counts the times it does.

The hand-made cases check the rule (what an undo is, and which changes of the world make one pay); the property
runs every QMDP robot with every partner over generated kitchens (the kind of kitchen and person that made the
robot put a clean plate down and pick it up again tick after tick before the rule) and asserts none flickers.
"""

from __future__ import annotations

from dataclasses import replace

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from planner.events import Event, EventKind
from planner.flicker import STALL_TICKS, FlickerWatch, Touch, scene_of, undoes
from planner.geometry import Action, Direction
from planner.layout import parse_layout
from planner.layout_gen import generate_named
from planner.objects import CLEAN_PLATE, MEAT, ONION
from planner.partner import PARTNERS, partner_model
from planner.planner_config import PlannerConfig
from planner.play import run_trial
from planner.robots import make_robot
from planner.rules import Rules
from planner.state import AgentState, initial_state
from planner.step import step

RULES = Rules()
KITCHEN = parse_layout("XXXXXXX\nO  1 2M\nX     D\nXPBWSXX\n", name="flicker")
"""The robot at (3, 1) faces the counter (3, 0) north of it."""


def _world(robot_held=None, counter=None, grills=(None,)):
    world = initial_state(KITCHEN, RULES)
    objects = (((3, 0), counter),) if counter else ()
    return type(world)(human=world.human, robot=AgentState((3, 1), Direction.NORTH, robot_held), objects=objects,
                       grills=grills, boards=world.boards, sinks=world.sinks, orders_left=world.orders_left)


def _interact(world):
    return step(KITCHEN, world, {"robot": Action.INTERACT, "human": Action.STAY}, RULES)


def test_a_put_down_then_a_pick_up_of_the_same_plate_is_a_flicker():
    start = _world(robot_held=CLEAN_PLATE)
    down, events = _interact(start)
    watch = FlickerWatch().observe(start, events, RULES)
    assert watch.last == Touch((3, 0), CLEAN_PLATE, None, scene_of(start, RULES, (3, 0)), start.tick)
    assert undoes(watch, KITCHEN, down, RULES), "picking the plate up again undoes the put-down"
    _, events = _interact(down)
    assert watch.observe(down, events, RULES).flickers == 1


def test_the_reverse_a_pick_up_then_a_put_back_is_a_flicker_too():
    start = _world(counter=ONION)
    up, events = _interact(start)
    watch = FlickerWatch().observe(start, events, RULES)
    _, events = _interact(up)
    assert undoes(watch, KITCHEN, up, RULES) and watch.observe(up, events, RULES).flickers == 1


def test_a_change_of_phase_elsewhere_makes_the_undo_pay_a_count_within_a_phase_does_not():
    start = _world(robot_held=CLEAN_PLATE, grills=(3,))
    down, events = _interact(start)
    watch = FlickerWatch().observe(start, events, RULES)
    cooking_on = type(down)(**{**{f: getattr(down, f) for f in down.__slots__}, "grills": (4,)})
    assert undoes(watch, KITCHEN, cooking_on, RULES), "a steak cooking on is no reason to take the plate back"
    ready = type(down)(**{**{f: getattr(down, f) for f in down.__slots__}, "grills": (RULES.cook_time,)})
    assert not undoes(watch, KITCHEN, ready, RULES), "the steak became ready: taking the plate back pays"
    person_took_meat = down.with_agent("human", AgentState(down.human.pos, down.human.facing, MEAT))
    assert not undoes(watch, KITCHEN, person_took_meat, RULES)


def test_another_interaction_in_between_ends_the_watch_and_a_blocked_move_does_not():
    start = _world(robot_held=CLEAN_PLATE)
    down, events = _interact(start)
    watch = FlickerWatch().observe(start, events, RULES)
    blocked = (Event("robot", EventKind.BLOCKED, (4, 1)),)
    assert watch.observe(down, blocked, RULES) == watch
    other = (Event("robot", EventKind.DISPENSE, (0, 1), ONION),)
    assert watch.observe(down, other, RULES).last is None


ROBOTS = ("fov_aware", "fov_aware_showing", "baseline", "no_rollout")


@pytest.mark.parametrize("partner", PARTNERS)
@settings(max_examples=8, deadline=None, derandomize=True, suppress_health_check=[HealthCheck.too_slow])
@given(generator_seed=st.integers(0, 1099), seed=st.integers(0, 9), robot=st.sampled_from(ROBOTS))
def test_no_robot_undoes_its_last_touch_in_an_unchanged_scene(partner, generator_seed, seed, robot):
    layout = generate_named(generator_seed)
    result = run_trial(layout, seed, robot=make_robot(robot, layout, RULES, PlannerConfig()),
                       human=partner_model(partner, layout, RULES))
    assert result.flickers == 0, (f"kitchen {layout.name} (generator seed {generator_seed}) seed {seed}: {robot} "
                                  f"with the {partner} partner undid its last touch {result.flickers} times")


def test_after_a_stall_as_long_as_the_standoff_rules_taking_the_item_back_is_no_flicker():
    """A robot that put its plate down in front of a person who then waits for that very plate would otherwise stand
    with them for the rest of the trial (a simulated participant of the pilot did): after ``STALL_TICKS`` ticks with
    nothing changed the team is stalled, and taking the plate back breaks the stalemate."""
    start = _world(robot_held=CLEAN_PLATE)
    down, events = _interact(start)
    watch = FlickerWatch().observe(start, events, RULES)
    soon = replace(down, tick=down.tick + STALL_TICKS - 2)
    late = replace(down, tick=down.tick + STALL_TICKS)
    assert undoes(watch, KITCHEN, soon, RULES)
    assert not undoes(watch, KITCHEN, late, RULES)
    _, events = _interact(late)
    assert watch.observe(late, events, RULES).flickers == 0
