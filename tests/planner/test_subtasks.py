"""Never more than the orders need (planner.subtasks.beyond_orders): the robot starts no step
of a dish the orders left do not need, counting what anyone has in progress."""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from planner.events import Event, EventKind
from planner.geometry import Action, Direction, Pos
from planner.layout import parse_layout
from planner.objects import DISH, STEAK_PLATE
from planner.planner_config import PlannerConfig
from planner.robots import make_robot
from planner.rollout import RobotTasker
from planner.rules import Rules
from planner.state import AgentState, WorldState, initial_state
from planner.step import step
from planner.subtasks import Subtask, beyond_orders, within_orders

RULES = Rules()
# The board (1,2) is used only from (2,2).
WALKTHROUGH = parse_layout("""XXXXXXXXXX
XXXOMXXDXX
XB2     1X
XXXPXWXSXX
XXXXXXXXXX
""", name="walkthrough")


def steaks_in_play(world: WorldState) -> int:
    things = (world.human.held, world.robot.held, *(obj for _, obj in world.objects))
    return sum(g is not None for g in world.grills) + sum(t in (STEAK_PLATE, DISH) for t in things)


def test_the_walkthrough_robot_grills_no_more_steaks_than_the_orders_left():
    # The participant put an onion on the board and stands in the board's only access cell for good. The
    # robot used to grill and plate a steak after another (seven for two orders in 400 ticks, four in the
    # first 250): each plated steak waiting for a garnish went down on a counter, and a free grill with orders
    # left asked for meat.
    world = replace(initial_state(WALKTHROUGH, RULES), human=AgentState((2, 2), Direction.WEST), boards=(0,))
    for name in ("baseline", "fov_aware"):
        robot = make_robot(name, WALKTHROUGH, RULES, PlannerConfig())
        robot.reset(world)
        rng, now, started = np.random.default_rng(0), world, 0
        events: tuple[Event, ...] = ()
        for _ in range(250):
            action = robot.decide(now, events, rng).action
            before = steaks_in_play(now)
            now, events = step(WALKTHROUGH, now, {"human": Action.STAY, "robot": action}, RULES)
            if any(e.kind is EventKind.START_COOKING for e in events):
                assert before < now.orders_left, f"{name}: a steak beyond the orders at tick {now.tick}"
                started += 1
        assert started == RULES.orders, f"{name} should have grilled one steak per order, grilled {started}"
        assert steaks_in_play(now) == RULES.orders


def test_what_is_in_progress_anywhere_counts():
    none: tuple[tuple[Pos, str], ...] = ()
    assert beyond_orders(None, None, 2, none, (None,), (None,), (None,)) == frozenset()
    # One steak on the grill, one plated on a counter: no more meat; the grill's steak still needs a plate.
    full = beyond_orders(None, None, 2, (((3, 1), STEAK_PLATE),), (4,), (None,), (None,))
    assert Subtask.PICKUP_MEAT in full
    assert Subtask.PICKUP_PLATE not in full and Subtask.PICKUP_ONION not in full
    # With a plate in the sink as well, no more plates.
    assert Subtask.PICKUP_PLATE in beyond_orders(None, None, 2, (((3, 1), STEAK_PLATE),), (4,), (None,), (0,))
    # The partner's meat counts as a steak in progress.
    assert Subtask.PICKUP_MEAT in beyond_orders(None, "meat", 1, none, (None,), (None,), (None,))
    # A raw onion lying on a counter does not: taking it starts nothing new.
    assert Subtask.PICKUP_ONION not in beyond_orders(None, None, 1, (((3, 1), "onion"),), (None,), (None,), (None,))
    # A dish made is a garnish, a plate and a steak.
    assert {Subtask.PICKUP_ONION, Subtask.PICKUP_MEAT, Subtask.PICKUP_PLATE, Subtask.PICKUP_GARNISH} <= \
        beyond_orders(DISH, None, 1, none, (None,), (None,), (None,))


def test_with_nothing_needed_the_robot_puts_its_load_down():
    assert within_orders((Subtask.PICKUP_STEAK,), frozenset({Subtask.PICKUP_STEAK})) == (Subtask.DROP_ON_COUNTER,)
    assert within_orders((Subtask.PICKUP_MEAT, Subtask.CHOP_ONION), frozenset({Subtask.PICKUP_MEAT})) == (
        Subtask.CHOP_ONION,)


def test_a_plated_steak_put_down_is_taken_up_again_once_the_garnish_is_ready():
    # Counting the plated steaks on counters as dishes in progress asks that someone take them up again: with
    # empty hands the robot's pickup_steak goes to such a counter when a chopped garnish is waiting.
    tasker = RobotTasker(WALKTHROUGH, RULES)
    plated = replace(initial_state(WALKTHROUGH, RULES), objects=(((5, 1), STEAK_PLATE),), boards=(RULES.chop_time,),
                     orders_left=1)
    assert Subtask.PICKUP_STEAK in tasker.options(plated, None)
    assert tasker.targets(Subtask.PICKUP_STEAK, plated) == ((5, 1),)
    assert Subtask.PICKUP_MEAT not in tasker.options(plated, None), "the plated steak is the order's steak"
    unchopped = replace(plated, boards=(0,))
    assert Subtask.PICKUP_STEAK not in tasker.options(unchopped, None), "holding it, nobody could chop the onion"
