"""The abstract-state search of docs/domain.md §5 (``lookahead="abstract"``), on the practice kitchen:

    XXXXXBOWXXXXXXX      board (5,1), onion (6,1), sink (7,1)
    XX1 2   XXXXXXX
    XS      DXXXXXX      serve (1,3), (1,4); plate (8,3)
    XS      PXXXXXX      grill (8,4)
    XX      MXXXXXX      meat (8,5)
"""

from __future__ import annotations

from dataclasses import replace

import pytest

import planner.abstract as abstract
from planner.abstract import STALEMATE, AbstractSearch, AbstractState, Job
from planner.geometry import Direction
from planner.objects import CLEAN_PLATE, MEAT, STEAK_PLATE
from planner.planner_config import PlannerConfig
from planner.rules import Rules
from planner.state import AgentState, WorldState, initial_state
from planner.subtasks import Subtask
from study_config import load_layout

RULES = Rules()
LAYOUT = load_layout("practice")
FAR = AgentState((2, 3), Direction.WEST)
WAITING_HUMAN = AgentState((2, 3), Direction.WEST, STEAK_PLATE)
"""Holds a plated steak for a garnish nobody has chopped: it finishes nothing until someone chops."""


def world_with(robot: AgentState, human: AgentState = FAR, **statuses) -> WorldState:
    return replace(initial_state(LAYOUT, RULES), robot=robot, human=human, **statuses)


def search() -> AbstractSearch:
    return AbstractSearch(LAYOUT, RULES, PlannerConfig(lookahead="abstract"))


def test_the_first_agent_to_finish_makes_the_transition_and_the_grill_cooks_meanwhile():
    world = world_with(AgentState((7, 5), Direction.EAST), grills=(2,))
    state = AbstractState(world, robot=Job(Subtask.PICKUP_MEAT), human=Job(Subtask.PICKUP_ONION))
    after, cost = search().transition(state)
    assert cost == 1 and after.world.robot.held == MEAT and after.world.grills == (3,)
    assert after.robot == Job(None) and after.human == Job(Subtask.PICKUP_ONION, elapsed=1)
    assert after.world.human == FAR  # the other agent's walk is counted, not placed


def test_a_steak_is_taken_only_once_it_is_cooked():
    world = world_with(AgentState((7, 4), Direction.EAST, CLEAN_PLATE), WAITING_HUMAN, grills=(4,))
    state = AbstractState(world, robot=Job(Subtask.PICKUP_STEAK), human=Job(Subtask.PICKUP_GARNISH))
    after, cost = search().transition(state)
    assert cost == RULES.cook_time - 4 + 1
    assert after.world.robot.held == STEAK_PLATE and after.world.grills == (None,)


def test_chopping_takes_every_press_the_onion_needs():
    world = world_with(AgentState((5, 2), Direction.NORTH), WAITING_HUMAN, boards=(0,))
    state = AbstractState(world, robot=Job(Subtask.CHOP_ONION), human=Job(Subtask.PICKUP_GARNISH))
    after, cost = search().transition(state)
    assert cost == RULES.chop_time and after.world.boards == (RULES.chop_time,)


def test_a_walk_already_made_is_not_paid_twice():
    world = world_with(AgentState((2, 2), Direction.EAST))
    fresh = search().finish_time(world, "robot", Job(Subtask.PICKUP_MEAT))[0]
    assert search().finish_time(world, "robot", Job(Subtask.PICKUP_MEAT, elapsed=3))[0] == fresh - 3


def test_two_agents_waiting_on_each_other_are_a_stalemate():
    """Both hold a plated steak for an onion nobody can chop with full hands."""
    world = world_with(AgentState((5, 2), Direction.NORTH, STEAK_PLATE),
                       AgentState((4, 2), Direction.EAST, STEAK_PLATE), boards=(0,))
    state = AbstractState(world, robot=Job(Subtask.PICKUP_GARNISH), human=Job(Subtask.PICKUP_GARNISH))
    assert search().value(state) == STALEMATE
    # with a free robot the search finds the way out: put the plate down and chop
    free = AbstractState.of(replace(world, robot=AgentState((5, 2), Direction.NORTH)), None,
                            Subtask.PICKUP_GARNISH)
    assert search().value(free) > STALEMATE


def test_successors_are_computed_lazily_and_cached_within_a_bound(monkeypatch):
    s = search()
    start = initial_state(LAYOUT, RULES)
    first = s.leaf(start, None, None)
    size = len(s.cache)
    assert size > 0 and s.leaf(start, None, None) == first and len(s.cache) == size
    monkeypatch.setattr(abstract, "CACHE_LIMIT", 50)
    small = search()
    assert small.leaf(start, None, None) == pytest.approx(first) and len(small.cache) <= 50


def test_leaf_chooses_again_for_a_subtask_already_done():
    """A rollout can stop right after the human picked up its meat: its subtask is then re-chosen."""
    world = world_with(AgentState((2, 2), Direction.EAST), AgentState((7, 5), Direction.EAST, MEAT))
    s = search()
    assert s.leaf(world, None, Subtask.PICKUP_MEAT) == s.leaf(world, None, None)


def test_an_unknown_lookahead_is_named():
    with pytest.raises(ValueError, match="lookahead must be one of rollout, abstract"):
        PlannerConfig(lookahead="mcts")
