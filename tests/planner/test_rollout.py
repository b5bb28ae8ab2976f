"""The robot's lookahead (planner/rollout.py; docs/domain.md §5): the shaping potential Φ, what a rollout is worth
in a kitchen whose future is known, its determinism for a seed, and the robot's own subtask choice inside it.

The rules kitchen of tests/conftest.py: serving counter at (7, 1), grill (4, 1), board (5, 1), sink (6, 1);
the person starts at (7, 3) and the robot at (1, 3).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from planner.geometry import Action, Direction
from planner.human import HumanMemory
from planner.kb import initial_kb
from planner.objects import CLEAN_PLATE, DISH, MEAT, ONION, STEAK_PLATE
from planner.planner_config import BASELINE, PlannerConfig
from planner.rollout import RobotTasker, Rollout, potential
from planner.rules import Rules
from planner.state import AgentState, initial_state
from planner.subtasks import Subtask

RULES = Rules()
CFG = PlannerConfig()
# Delivering the last order: Φ goes from −40 (one order left) + 30 (a dish held) to +100 (none left).
DELIVERY_GAIN = 100.0 - (-40.0 + 30.0)


def one_order_left(kitchen, robot):
    """The last order open, the robot as given and the person out of its way at (1, 4)."""
    return replace(initial_state(kitchen, RULES), robot=robot, human=AgentState((1, 4), Direction.WEST),
                   orders_left=1)


def test_the_potential_counts_orders_stations_and_what_is_held_or_put_down(kitchen):
    start = initial_state(kitchen, RULES)
    assert potential(start, CFG) == -80.0
    assert potential(replace(start, orders_left=0), CFG) == 100.0
    busy = replace(start, grills=(4,), boards=(1,), sinks=(2,))
    assert potential(busy, CFG) - potential(start, CFG) == 5.0 + (3.0 + 1) + (3.0 + 2)
    carrying = replace(start, human=replace(start.human, held=CLEAN_PLATE), robot=replace(start.robot, held=DISH),
                       objects=(((4, 3), STEAK_PLATE),))
    assert potential(carrying, CFG) - potential(start, CFG) == 12.0 + 30.0 + 20.0
    # Raw ingredients in the hands are no progress yet.
    assert potential(replace(start, human=replace(start.human, held=MEAT)), CFG) == potential(start, CFG)


def test_serving_the_last_dish_at_once_is_worth_the_whole_gain(kitchen):
    world = one_order_left(kitchen, AgentState((7, 2), Direction.NORTH, DISH))
    rollout = Rollout(kitchen, RULES, CFG)
    value = rollout.value(world, initial_kb(world), Subtask.PICKUP_MEAT, Subtask.DELIVER_DISH, horizon=42, seed=0)
    assert value == pytest.approx(DELIVERY_GAIN)


def test_progress_two_ticks_later_is_worth_less(kitchen):
    """From (6, 2) facing west the robot needs two moves (east, then north to face the counter) before it
    serves; the rollout discounts the gain by 0.97 per tick."""
    world = one_order_left(kitchen, AgentState((6, 2), Direction.WEST, DISH))
    rollout = Rollout(kitchen, RULES, CFG)
    value = rollout.value(world, initial_kb(world), Subtask.PICKUP_MEAT, Subtask.DELIVER_DISH, horizon=42, seed=0)
    assert value == pytest.approx(CFG.tick_discount ** 2 * DELIVERY_GAIN)


def test_the_robot_plays_its_prefix_before_its_subtask(kitchen):
    world = one_order_left(kitchen, AgentState((7, 2), Direction.NORTH, DISH))
    rollout = Rollout(kitchen, RULES, CFG)
    waited = rollout.value(world, initial_kb(world), Subtask.PICKUP_MEAT, Subtask.DELIVER_DISH, horizon=42, seed=0,
                           prefix=(Action.STAY, Action.STAY, Action.STAY))
    assert waited == pytest.approx(CFG.tick_discount ** 3 * DELIVERY_GAIN)
    too_short = rollout.value(world, initial_kb(world), Subtask.PICKUP_MEAT, Subtask.DELIVER_DISH, horizon=3,
                              seed=0, prefix=(Action.STAY, Action.STAY, Action.STAY))
    assert too_short == 0.0


@pytest.mark.parametrize("cfg", [CFG, BASELINE], ids=["fov_aware", "baseline"])
def test_a_rollout_is_determined_by_its_seed(kitchen, cfg):
    world = initial_state(kitchen, RULES)
    kb = initial_kb(world)

    def value(seed: int) -> float:
        return Rollout(kitchen, RULES, cfg).value(world, kb, Subtask.PICKUP_ONION, Subtask.PICKUP_MEAT,
                                                  horizon=42, seed=seed)

    values = [value(seed) for seed in range(8)]
    assert values == [value(seed) for seed in range(8)]
    # The simulated person chooses at random when a subtask is done, so the seeds see different futures.
    assert len(set(values)) > 1


def test_only_a_person_with_a_limited_view_learns_from_the_robot_carrying_a_dish_past_them(kitchen):
    """The robot carries a dish from (3, 2) to the serving counter across the view of a person at (7, 3) facing
    west. For the FOV-aware robot's model of the person that is worth something (and the same progress); a person
    who sees everything (the baseline's model) learns nothing from it; without ``knowing`` nothing is added."""
    world = replace(initial_state(kitchen, RULES), robot=AgentState((3, 2), Direction.EAST, DISH),
                    human=AgentState((7, 3), Direction.WEST))
    kb = initial_kb(initial_state(kitchen, RULES))

    def parts(cfg: PlannerConfig, knowing: bool = True) -> tuple[float, float]:
        return Rollout(kitchen, RULES, cfg).parts(world, kb, HumanMemory(subtask=Subtask.PICKUP_MEAT),
                                                  np.random.default_rng(0), Subtask.DELIVER_DISH, 12, knowing=knowing)

    progress, known = parts(CFG)
    assert known > 0
    assert parts(BASELINE) == (progress, 0.0)
    assert parts(CFG, knowing=False) == (progress, 0.0)


def test_the_shown_value_is_earned_once_when_the_persons_kb_takes_in_the_load(kitchen):
    rollout = Rollout(kitchen, RULES, CFG)
    world = replace(initial_state(kitchen, RULES), robot=AgentState((5, 3), Direction.EAST, ONION))
    unaware = initial_kb(initial_state(kitchen, RULES))
    aware = replace(unaware, robot=world.robot)
    before = rollout.start(world, unaware, HumanMemory(), Subtask.DROP_ONION)
    assert rollout.knowing(before, world, aware, showing=ONION) == CFG.shown_value
    already = rollout.start(world, aware, HumanMemory(), Subtask.DROP_ONION)
    assert rollout.knowing(already, world, aware, showing=ONION) == 0.0
    # Only what the robot held when it decided counts, and empty hands earn nothing.
    assert rollout.knowing(before, world, aware, showing=None) == 0.0
    empty = replace(world, robot=replace(world.robot, held=None))
    assert rollout.knowing(before, empty, replace(unaware, robot=empty.robot), showing=None) == 0.0


def test_the_robot_offers_to_put_a_plated_steak_down_while_no_garnish_is_coming(kitchen):
    tasker = RobotTasker(kitchen, RULES)
    start = initial_state(kitchen, RULES)
    holding = replace(start, robot=replace(start.robot, held=STEAK_PLATE))
    assert Subtask.DROP_ON_COUNTER in tasker.options(holding, None)
    chopped = replace(holding, boards=(RULES.chop_time,))
    assert Subtask.DROP_ON_COUNTER not in tasker.options(chopped, None)


def test_the_robot_takes_the_nearest_subtask_the_person_is_not_doing(kitchen):
    """From its start (1, 3) the onion dispenser (1, 1) is the nearest fetch; when the person is already
    fetching an onion the robot goes for the next nearest."""
    tasker = RobotTasker(kitchen, RULES)
    world = initial_state(kitchen, RULES)
    options = tasker.options(world, None)
    assert set(options) >= {Subtask.PICKUP_MEAT, Subtask.PICKUP_ONION, Subtask.PICKUP_PLATE}
    assert tasker.nearest(world, options, avoid=None) is Subtask.PICKUP_ONION
    assert tasker.nearest(world, options, avoid=Subtask.PICKUP_ONION) is Subtask.PICKUP_MEAT

