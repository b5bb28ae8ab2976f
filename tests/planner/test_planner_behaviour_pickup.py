"""Behaviour 1 of the paper (§VI-C; docs/domain.md §6, "Behaviours") in a small hand-made kitchen: the robot
takes meat from the crate behind the person, who chops a slow onion at the board facing the wall, so the robot
can be seen only on the cells left and right of them. The showing robot (``fov_aware_showing``: the hands walk,
docs/domain.md §5) steps beside the person on its way to the grill and stays there until the person can
acknowledge the meat (``kb_delay`` consecutive ticks). Its model of the person expects them to walk off for meat
or a plate; that they keep standing at the board is what the hands walk's hypothesis of a person who keeps their
pose brings in (without it the robot waits in the wrong place, then goes unseen); the
baseline, whose person sees everything, walks the shortest way along the top row, unseen. Checked for several
planner seeds and with the measure the benchmark uses (:func:`planner.behaviours.measure`)."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from planner.behaviours import frame_of, measure
from planner.events import Event
from planner.fov import visible_cells
from planner.geometry import Action, Direction
from planner.layout import parse_layout
from planner.objects import DISH, MEAT, ONION
from planner.paths import distance
from planner.perception import FOV_ANGLE, KB_DELAY
from planner.planner_config import PlannerConfig
from planner.qmdp import QmdpRobot
from planner.robots import make_robot
from planner.rules import Rules
from planner.state import AgentState, initial_state
from planner.step import step

RULES = Rules(chop_time=12)
LAYOUT = parse_layout("\n".join([
    "XXXXXXXXX",
    "XMXDXWXXX",
    "X1      X",
    "X 2     X",
    "XOXBXXPSX",
    "XXXXXXXXX",
]), name="pickup_test")
PERSON = AgentState((3, 3), Direction.SOUTH)
SEEDS = range(4)


def trial(robot_name: str, seed: int):
    """The frames from the pickup until the meat is on the grill (at most 20 ticks), the person chopping."""
    start = replace(initial_state(LAYOUT, RULES), human=PERSON, robot=AgentState((1, 2), Direction.NORTH),
                    boards=(0,))
    robot = make_robot(robot_name, LAYOUT, RULES)
    robot.reset(start)
    rng = np.random.default_rng(seed)
    world, events = step(LAYOUT, start, {"human": Action.INTERACT, "robot": Action.INTERACT}, RULES)
    assert world.robot.held == MEAT
    frames = [frame_of(LAYOUT, world, events, FOV_ANGLE)]
    for _ in range(20):
        action = robot.decide(world, events, rng).action
        world, events = step(LAYOUT, world, {"human": Action.INTERACT, "robot": action}, RULES)
        frames.append(frame_of(LAYOUT, world, events, FOV_ANGLE))
        if world.robot.held is None:
            break
    return world, frames


def test_the_pickup_and_the_shortest_way_are_out_of_view():
    seen = visible_cells(LAYOUT, PERSON.pos, PERSON.facing, FOV_ANGLE)
    assert seen & LAYOUT.floor == {(2, 3), (3, 3), (4, 3)}


@pytest.mark.parametrize("seed", SEEDS)
def test_the_showing_robot_shows_what_it_picked_up_then_cooks_it(seed):
    world, frames = trial("fov_aware_showing", seed)
    assert world.grills == (0,) or (world.grills[0] is not None and world.robot.held is None)
    assert measure(frames, KB_DELAY).shown == 1


@pytest.mark.parametrize("seed", SEEDS)
def test_the_default_robot_takes_the_shortest_way_when_being_seen_does_not_pay(seed):
    """The default FOV-aware robot values being seen only by what it does for the team (docs/domain.md §5): here its
    rollouts of the person, who goes on chopping a long onion, find nothing the person would do otherwise for
    knowing the meat is coming, so it walks the shortest way to the grill, as the baseline does."""
    world, frames = trial("fov_aware", seed)
    assert world.grills[0] is not None and world.robot.held is None
    assert len(frames) == distance(LAYOUT, ((1, 2), Direction.NORTH), (6, 4)) + 2


@pytest.mark.parametrize("seed", SEEDS)
def test_the_baseline_carries_it_to_the_grill_unseen(seed):
    world, frames = trial("baseline", seed)
    assert world.grills[0] is not None and world.robot.held is None
    b = measure(frames, KB_DELAY)
    assert (b.holdings, b.shown) == (1, 0)


def delivery(robot_name: str, seed: int):
    """The frames of a dish trip from the robot's start (the dish in hand) until it delivers (at most 25 ticks). The
    robot first watches the person put an onion on the board and chop it three times (so that the person's modelled
    KB, which takes in their own loaded board after ``kb_delay`` ticks as the reference's rule does, and the belief
    know what they do), then the person goes on chopping."""
    world = replace(initial_state(LAYOUT, RULES), human=replace(PERSON, held=ONION),
                    robot=AgentState((1, 2), Direction.NORTH, DISH))
    robot = make_robot(robot_name, LAYOUT, RULES)
    assert isinstance(robot, QmdpRobot)
    robot.reset(world)
    events: tuple[Event, ...] = ()
    robot.observe(world, events)
    for _ in range(4):
        world, events = step(LAYOUT, world, {"human": Action.INTERACT, "robot": Action.STAY}, RULES)
        robot.observe(world, events)
    rng = np.random.default_rng(seed)
    frames = []
    for _ in range(25):
        action = robot.decide(world, events, rng).action
        world, events = step(LAYOUT, world, {"human": Action.INTERACT, "robot": action}, RULES)
        frames.append(frame_of(LAYOUT, world, events, FOV_ANGLE))
        if world.robot.held is None:
            break
    return world, frames


@pytest.mark.xfail(strict=True, reason=(
    "since the reference's KB rule (planner/kb.py, 2026-12-07) the person's own loading of the board enters their "
    "modelled KB only kb_delay ticks later, so the robot's belief (planner/belief.py: chopping follows dropping the "
    "onion) never has the person chopping and its dish walk aims where it expects them to walk; passes again once "
    "the person's own loading enters at once, as planner/kb.py's docstring says"))
def test_the_showing_robot_mostly_carries_the_dish_through_the_persons_view():
    """Behaviour 2 in a trial: over planner seeds 0-7 the showing robot delivers every dish, and on most trips
    (one rollout per hypothesis is noisy) passes the person's view, within the trip's detour; the baseline's trip,
    along the top row, is never in view."""
    shares = []
    for seed in range(8):
        world, frames = delivery("fov_aware_showing", seed)
        b = measure(frames, KB_DELAY)
        assert world.robot.held is None and b.trips == 1
        assert len(frames) <= distance(LAYOUT, ((1, 2), Direction.NORTH), (7, 4)) + 1 + PlannerConfig().dish_detour
        shares.append(b.trip_share_sum)
        world, frames = delivery("baseline", seed)
        b = measure(frames, KB_DELAY)
        assert world.robot.held is None and (b.trips, b.trip_share_sum) == (1, 0.0)
    assert sum(share > 0 for share in shares) >= 6


@pytest.mark.parametrize("seed", range(4))
def test_the_default_robot_carries_the_dish_the_shortest_way(seed):
    """The default FOV-aware robot has no dish walk (docs/domain.md §5): being seen with a dish changes nothing the
    person does in its model, so it delivers by the shortest way, unseen here."""
    world, frames = delivery("fov_aware", seed)
    assert world.robot.held is None
    assert len(frames) == distance(LAYOUT, ((1, 2), Direction.NORTH), (7, 4)) + 1

