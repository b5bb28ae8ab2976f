"""The robot's belief over the person's subtask (planner/belief.py; docs/domain.md §5): what it believes after
watching the person for a tick, on the rules kitchen of tests/conftest.py (onion (1, 1), meat (2, 1), plate
dispenser (3, 1) along the top wall; the person starts at (7, 3)).

With an empty-handed person in an empty kitchen the feasible subtasks are fetching meat, an onion or a plate.
"""

from __future__ import annotations

from dataclasses import replace

import pytest

from planner.belief import Belief, update_belief
from planner.geometry import Action, Direction
from planner.kb import initial_kb
from planner.objects import DISH, MEAT, ONION
from planner.paths import distance
from planner.rules import Rules
from planner.state import AgentState, initial_state
from planner.subtasks import Subtask

RULES = Rules()
FETCHING = {Subtask.PICKUP_MEAT, Subtask.PICKUP_ONION, Subtask.PICKUP_PLATE}
# A step west from (2, 2) to (1, 2) brings the person closer to the onion dispenser (1, 1) only.
BEFORE = AgentState((2, 2), Direction.EAST)
TOWARD_ONION = AgentState((1, 2), Direction.WEST)


def observe(layout, belief, before, now, action, kb=None, partner_held=None, orders_left=2):
    kb = kb if kb is not None else initial_kb(initial_state(layout, RULES))
    return update_belief(belief, layout, RULES, kb, before, now, action, partner_held, orders_left)


def test_the_step_is_toward_the_onion_only(kitchen):
    """The premise of the tests below, from the kitchen's shortest paths."""
    onion, meat, plate = (1, 1), (2, 1), (3, 1)
    before, after = (BEFORE.pos, BEFORE.facing), (TOWARD_ONION.pos, TOWARD_ONION.facing)
    assert distance(kitchen, after, onion) < distance(kitchen, before, onion)
    assert distance(kitchen, after, meat) > distance(kitchen, before, meat)
    assert distance(kitchen, after, plate) > distance(kitchen, before, plate)


def test_before_anything_is_seen_every_feasible_subtask_is_equally_likely(kitchen):
    belief = observe(kitchen, None, None, initial_state(kitchen, RULES).human, None)
    assert set(belief.as_dict()) == FETCHING
    assert belief.as_dict() == pytest.approx({s.value: 1 / 3 for s in FETCHING})


def test_a_step_toward_one_dispenser_makes_its_subtask_the_likely_one(kitchen):
    prior = observe(kitchen, None, None, BEFORE, None)
    belief = observe(kitchen, prior, BEFORE, TOWARD_ONION, Action.WEST)
    # (1 − 0.7) · 1/3 + 0.7 · 1 for the onion, (1 − 0.7) · 1/3 for the others: no renormalisation needed.
    assert belief.as_dict() == pytest.approx({"pickup_onion": 0.8, "pickup_meat": 0.1, "pickup_plate": 0.1})
    assert sum(belief.as_dict().values()) == pytest.approx(1.0)


def test_steady_progress_sharpens_the_belief_and_standing_still_blurs_it(kitchen):
    prior = observe(kitchen, None, None, BEFORE, None)
    once = observe(kitchen, prior, BEFORE, TOWARD_ONION, Action.WEST)
    facing_onion = AgentState((1, 2), Direction.NORTH)
    twice = observe(kitchen, once, TOWARD_ONION, facing_onion, Action.NORTH)
    assert twice.as_dict()["pickup_onion"] == pytest.approx(0.3 * 0.8 + 0.7)
    still = observe(kitchen, twice, facing_onion, facing_onion, Action.STAY)
    # No progress toward anything reads as no evidence: the belief moves toward uniform but keeps its order.
    assert still.as_dict()["pickup_onion"] == pytest.approx(0.3 * twice.as_dict()["pickup_onion"] + 0.7 / 3)
    assert max(still.probs, key=lambda sp: sp[1])[0] is Subtask.PICKUP_ONION


def test_a_person_holding_something_has_one_certain_subtask(kitchen):
    prior = observe(kitchen, None, None, BEFORE, None)
    holding = AgentState((1, 2), Direction.NORTH, ONION)
    belief = observe(kitchen, prior, AgentState((1, 2), Direction.NORTH), holding, Action.INTERACT)
    assert belief.probs == ((Subtask.DROP_ONION, 1.0),)
    assert belief.held == ONION


def test_what_the_person_believes_decides_what_is_feasible(kitchen):
    """The person believes the robot carries meat: fetching meat is not among the subtasks (docs/domain.md §4)."""
    world = initial_state(kitchen, RULES)
    kb = initial_kb(replace(world, robot=replace(world.robot, held=MEAT)))
    belief = observe(kitchen, None, None, world.human, None, kb=kb, partner_held=MEAT)
    assert set(belief.as_dict()) == {"pickup_onion", "pickup_plate"}
    # The grill is free in the same KB: it is the belief about the partner's hands that rules meat out.
    assert "pickup_meat" in observe(kitchen, None, None, world.human, None, kb=kb, partner_held=None).as_dict()


def test_a_change_in_what_the_person_knows_starts_the_belief_afresh(kitchen):
    """Once the person's KB learns that the robot carries a dish (the high-level state changed), the old
    evidence is dropped; with the same KB it would have been kept."""
    prior = observe(kitchen, None, None, BEFORE, None)
    leaning = observe(kitchen, prior, BEFORE, TOWARD_ONION, Action.WEST)
    world = initial_state(kitchen, RULES)
    robot_with_dish = initial_kb(replace(world, robot=replace(world.robot, held=DISH)))
    fresh = observe(kitchen, leaning, TOWARD_ONION, TOWARD_ONION, Action.STAY, kb=robot_with_dish)
    assert fresh.as_dict() == pytest.approx({s.value: 1 / 3 for s in FETCHING})
    kept = observe(kitchen, leaning, TOWARD_ONION, TOWARD_ONION, Action.STAY)
    assert kept.as_dict()["pickup_onion"] > 1 / 3


def test_no_feasible_subtask_is_ever_ruled_out(kitchen):
    """A subtask the robot was sure against keeps the floor (0.01 before renormalising), so a person who turns
    out to be doing it can win the belief back."""
    sure = Belief(probs=((Subtask.PICKUP_MEAT, 0.0), (Subtask.PICKUP_ONION, 1.0), (Subtask.PICKUP_PLATE, 0.0)),
                  held=None, summary=observe(kitchen, None, None, BEFORE, None).summary)
    belief = observe(kitchen, sure, BEFORE, TOWARD_ONION, Action.WEST)
    probs = belief.as_dict()
    assert probs["pickup_meat"] == pytest.approx(0.01 / 1.02) and probs["pickup_plate"] == pytest.approx(0.01 / 1.02)
    assert sum(probs.values()) == pytest.approx(1.0)


def test_the_likely_subtasks_are_those_above_the_threshold_renormalised():
    belief = Belief(probs=((Subtask.PICKUP_MEAT, 0.1), (Subtask.PICKUP_ONION, 0.8), (Subtask.PICKUP_PLATE, 0.1)))
    assert belief.likely(threshold=0.15, limit=3) == ((Subtask.PICKUP_ONION, 1.0),)
    two = belief.likely(threshold=0.05, limit=2)
    assert [s for s, _ in two] == [Subtask.PICKUP_ONION, Subtask.PICKUP_MEAT]  # ties broken by name
    assert [p for _, p in two] == pytest.approx([0.8 / 0.9, 0.1 / 0.9])
    assert belief.likely(threshold=0.9, limit=3) == ((Subtask.PICKUP_ONION, 1.0),)  # never empty
