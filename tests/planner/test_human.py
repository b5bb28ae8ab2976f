"""The simulated human (docs/domain.md §4): KB-judged subtasks, commitment, seeded uniform choice, paths, unstuck."""

from __future__ import annotations

from collections import Counter
from dataclasses import replace

import numpy as np

from planner.geometry import MOVES, Action, Direction
from planner.human import HumanMemory, HumanModel
from planner.kb import initial_kb
from planner.objects import CLEAN_PLATE, DISH, MEAT, ONION, STEAK_PLATE
from planner.paths import distance
from planner.rules import Rules
from planner.state import AgentState, initial_state
from planner.subtasks import Believed, Subtask, available

RULES = Rules()


def believed(kb, held=None, partner_held=None, orders_left=2):
    return Believed(kb=kb, held=held, partner_held=partner_held, orders_left=orders_left)


def test_empty_handed_options_in_an_empty_kitchen(kitchen):
    kb = initial_kb(initial_state(kitchen, RULES))
    assert set(available(believed(kb), RULES)) == {Subtask.PICKUP_MEAT, Subtask.PICKUP_ONION,
                                                   Subtask.PICKUP_PLATE}


def test_availability_is_judged_on_the_kb_not_the_world(kitchen):
    world = replace(initial_state(kitchen, RULES), boards=(0,), grills=(3,))
    stale_kb = initial_kb(initial_state(kitchen, RULES))
    assert Subtask.PICKUP_ONION in available(believed(stale_kb), RULES)
    assert Subtask.PICKUP_ONION not in available(believed(initial_kb(world)), RULES)
    assert Subtask.PICKUP_MEAT not in available(believed(initial_kb(world)), RULES)


def test_partner_holding_the_item_removes_the_option(kitchen):
    kb = initial_kb(initial_state(kitchen, RULES))
    assert Subtask.PICKUP_MEAT not in available(believed(kb, partner_held=MEAT), RULES)
    assert Subtask.PICKUP_ONION not in available(believed(kb, partner_held=ONION), RULES)


def test_clean_plate_pickup_needs_clean_plate_steak_and_garnish(kitchen):
    base = initial_state(kitchen, RULES)
    ready = initial_kb(replace(base, sinks=(RULES.wash_time,), grills=(4,), boards=(1,)))
    assert Subtask.PICKUP_CLEAN_PLATE in available(believed(ready), RULES)
    no_garnish = replace(ready, boards=(None,))
    assert Subtask.PICKUP_CLEAN_PLATE not in available(believed(no_garnish), RULES)
    assert Subtask.PICKUP_CLEAN_PLATE in available(believed(no_garnish, partner_held=ONION), RULES)


def test_holding_forces_the_continuation(kitchen):
    kb = initial_kb(replace(initial_state(kitchen, RULES), grills=(3,)))
    assert available(believed(kb, held=ONION), RULES) == (Subtask.DROP_ONION,)
    assert available(believed(kb, held=MEAT), RULES) == (Subtask.DROP_ON_COUNTER,)
    assert available(believed(kb, held=CLEAN_PLATE), RULES) == (Subtask.PICKUP_STEAK,)
    assert available(believed(kb, held=DISH), RULES) == (Subtask.DELIVER_DISH,)
    assert available(believed(kb, held=STEAK_PLATE, partner_held=ONION), RULES) == (Subtask.PICKUP_GARNISH,)


def test_keeps_chopping_while_the_onion_is_unfinished(kitchen):
    kb = initial_kb(replace(initial_state(kitchen, RULES), boards=(1,)))
    assert available(believed(kb), RULES, Subtask.CHOP_ONION) == (Subtask.CHOP_ONION,)
    assert available(believed(kb), RULES, Subtask.DROP_ONION) == (Subtask.CHOP_ONION,)


def test_nothing_to_do_means_pickup_plate(kitchen):
    kb = initial_kb(replace(initial_state(kitchen, RULES), grills=(3,), boards=(1,), sinks=(1,)))
    assert available(believed(kb), RULES) == (Subtask.PICKUP_PLATE,)


def test_choice_is_seeded_and_uniform(kitchen):
    model = HumanModel(kitchen, RULES)
    world = initial_state(kitchen, RULES)
    kb = initial_kb(world)
    picks = [model.commit(world, kb, HumanMemory(), np.random.default_rng(seed)) for seed in range(3000)]
    again = [model.commit(world, kb, HumanMemory(), np.random.default_rng(seed)) for seed in range(3000)]
    assert picks == again
    counts = Counter(picks)
    assert set(counts) == {Subtask.PICKUP_MEAT, Subtask.PICKUP_ONION, Subtask.PICKUP_PLATE}
    assert all(900 < n < 1100 for n in counts.values()), counts


def test_commits_until_done_or_unavailable(kitchen):
    model = HumanModel(kitchen, RULES)
    world = initial_state(kitchen, RULES)
    memory = HumanMemory(subtask=Subtask.PICKUP_MEAT)
    rng = np.random.default_rng(0)
    assert all(model.commit(world, initial_kb(world), memory, rng) is Subtask.PICKUP_MEAT for _ in range(50))
    grill_taken = initial_kb(replace(world, grills=(2,)))
    assert model.commit(world, grill_taken, memory, rng) is not Subtask.PICKUP_MEAT
    holding = replace(world, human=replace(world.human, held=MEAT))
    assert model.commit(holding, initial_kb(world), memory, rng) is Subtask.DROP_MEAT


def test_shortest_path_counts_moves_and_turns(kitchen):
    # From (1, 3) facing south to face the grill at (4, 1): three steps east/north to (4, 2)... plus the
    # turn north (a move into the grill only turns): 5 actions, checked by hand.
    assert distance(kitchen, ((1, 3), Direction.SOUTH), (4, 1)) == 5
    assert distance(kitchen, ((4, 2), Direction.NORTH), (4, 1)) == 0
    assert distance(kitchen, ((4, 2), Direction.EAST), (4, 1)) == 1


def test_walks_to_the_target_and_interacts(kitchen):
    model = HumanModel(kitchen, RULES)
    world = replace(initial_state(kitchen, RULES), human=AgentState((4, 2), Direction.NORTH, MEAT))
    action, memory = model.act(world, initial_kb(world), HumanMemory(), np.random.default_rng(0))
    assert action is Action.INTERACT and memory.subtask is Subtask.DROP_MEAT


def test_takes_a_random_free_move_after_two_stuck_ticks(kitchen):
    model = HumanModel(kitchen, RULES)
    world = replace(initial_state(kitchen, RULES), human=AgentState((6, 2), Direction.SOUTH, MEAT))
    pose = (world.human.pos, world.human.facing)
    stuck = HumanMemory(subtask=Subtask.DROP_MEAT, held=MEAT, last_pose=pose, wants_move=True, still=1)
    planned, _ = model.act(world, initial_kb(world), HumanMemory(), np.random.default_rng(0))
    assert planned is Action.WEST
    seen = set()
    for seed in range(40):
        action, memory = model.act(world, initial_kb(world), stuck, np.random.default_rng(seed))
        assert action in MOVES and memory.still == 0
        seen.add(action)
    assert len(seen) >= 2
