"""docs/domain.md §5 step by step (``PlannerConfig(lookahead="abstract")``, :mod:`planner.reference`)."""

from __future__ import annotations

import time
from dataclasses import replace

import numpy as np
import pytest

from planner.geometry import ACTIONS, MOTIONS, Action, Direction
from planner.kb import initial_kb
from planner.planner_config import PlannerConfig
from planner.play import run_trial
from planner.reference import ReferenceLookahead
from planner.robots import make_robot
from planner.rules import Rules
from planner.state import AgentState, initial_state
from planner.subtasks import Subtask
from study_config import load_layout

RULES = Rules()
LAYOUT = load_layout("practice")
CONFIG = PlannerConfig(lookahead="abstract")


def test_every_motion_sequence_is_explored_when_there_are_few_else_a_uniform_sample():
    few = ReferenceLookahead(LAYOUT, RULES, replace(CONFIG, exploration_depth=2, exploration_samples=25))
    assert sorted(few.sequences(np.random.default_rng(0))) == sorted(
        (a, b) for a in MOTIONS for b in MOTIONS)
    many = ReferenceLookahead(LAYOUT, RULES, replace(CONFIG, exploration_depth=3, exploration_samples=16))
    drawn = many.sequences(np.random.default_rng(0))
    assert 1 < len(drawn) <= 16 and all(len(seq) == 3 and set(seq) <= set(MOTIONS) for seq in drawn)
    assert drawn == many.sequences(np.random.default_rng(0))


def test_q_values_cover_every_action_and_prefer_delivering_a_dish_it_faces():
    world = replace(initial_state(LAYOUT, RULES), robot=AgentState((2, 3), Direction.WEST, "dish"))
    q, explored, cut = ReferenceLookahead(LAYOUT, RULES, CONFIG).q_values(
        world, initial_kb(world), ((Subtask.PICKUP_MEAT, 1.0),), seed=1)
    assert set(q) == set(ACTIONS) and explored >= 1 and not cut
    assert max(q, key=lambda a: q[a]) is Action.INTERACT


def test_the_robot_with_abstract_lookahead_decides_legally_and_reproducibly():
    decisions = []
    for _ in range(2):
        robot = make_robot("fov_aware", LAYOUT, RULES, CONFIG)
        world = initial_state(LAYOUT, RULES)
        robot.reset(world)
        decisions.append(robot.decide(world, (), np.random.default_rng(0)))
    first, second = decisions
    assert first.action in ACTIONS and first.action == second.action and first.q_values == second.q_values
    assert set(first.q_values) == {a.value for a in ACTIONS} and first.explored_kbs >= 1


def test_a_passed_deadline_still_values_one_action_and_says_so():
    robot = make_robot("baseline", LAYOUT, RULES, CONFIG)
    world = initial_state(LAYOUT, RULES)
    robot.reset(world)
    decision = robot.decide(world, (), np.random.default_rng(0), deadline=time.perf_counter() - 1.0)
    assert decision.timed_out and len(decision.q_values) == 1 and decision.action in ACTIONS


@pytest.mark.parametrize("name", ["fov_aware", "baseline"])
def test_the_abstract_lookahead_plays_the_practice_kitchen_to_the_end(name):
    robot = make_robot(name, LAYOUT, RULES, CONFIG)
    assert run_trial(LAYOUT, 0, robot=robot).finished
