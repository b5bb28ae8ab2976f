"""The one planner check every robot passes (STYLE 10): legal actions, determinism, every kitchen finished."""

from __future__ import annotations

import time

import numpy as np
import pytest

from planner.decision import Decision
from planner.geometry import ACTIONS
from planner.planner_config import PlannerConfig
from planner.play import run_trial
from planner.registry import PLANNER_NAMES
from planner.robots import make_robot
from planner.rules import Rules
from planner.state import initial_state
from study_config import layout_names, load_layout

RULES = Rules()


@pytest.mark.parametrize("name", PLANNER_NAMES)
def test_decisions_are_legal_and_carry_their_record(name):
    layout = load_layout("none_3")
    robot = make_robot(name, layout, RULES, PlannerConfig())
    world = initial_state(layout, RULES)
    robot.reset(world)
    decision = robot.decide(world, (), np.random.default_rng(0))
    assert isinstance(decision, Decision) and decision.action in ACTIONS
    assert decision.elapsed_ms >= 0
    if name != "stay":
        assert abs(sum(decision.belief.values()) - 1.0) < 1e-9 and decision.q_values


@pytest.mark.parametrize("name", PLANNER_NAMES)
def test_same_seed_same_trial(name):
    layout = load_layout("mid_2")
    runs = [run_trial(layout, 5, robot=make_robot(name, layout, RULES, PlannerConfig()), record=True)
            for _ in range(2)]
    assert runs[0].actions == runs[1].actions and all(a in ACTIONS for pair in runs[0].actions for a in pair)


@pytest.mark.slow
@pytest.mark.parametrize("name", PLANNER_NAMES)
@pytest.mark.parametrize("kitchen", layout_names())
def test_finishes_every_kitchen_with_the_simulated_human(name, kitchen):
    layout = load_layout(kitchen)
    for seed in range(2):
        robot = make_robot(name, layout, RULES, PlannerConfig())
        result = run_trial(layout, seed, robot=robot)
        assert result.finished, f"{name} on {kitchen} seed {seed}: {result.delivered} delivered"


def test_unknown_planner_is_named():
    with pytest.raises(ValueError, match="known: fov_aware"):
        make_robot("clairvoyant", load_layout("none_3"), RULES)


def test_a_passed_deadline_returns_an_action_and_says_so():
    layout = load_layout("none_3")
    robot = make_robot("fov_aware", layout, RULES)
    world = initial_state(layout, RULES)
    robot.reset(world)
    decision = robot.decide(world, (), np.random.default_rng(0), deadline=time.perf_counter() - 1)
    assert decision.action in ACTIONS and decision.timed_out
