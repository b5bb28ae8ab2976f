"""The robot's randomness is the trial's: its rollouts draw from the generator it is handed."""

from __future__ import annotations

import numpy as np

from planner.planner_config import PlannerConfig
from planner.play import run_trial
from planner.robots import make_robot
from planner.rules import Rules
from planner.state import initial_state
from study_config import load_layout

LAYOUT = load_layout("mid_2")
RULES = Rules()


def decisions(seed: int, ticks: int = 6) -> list[dict[str, float]]:
    """The q-values of the first ``ticks`` decisions on the same worlds, with a robot stream from ``seed``."""
    robot = make_robot("fov_aware", LAYOUT, RULES, PlannerConfig())
    world = initial_state(LAYOUT, RULES)
    robot.reset(world)
    rng = np.random.default_rng(seed)
    return [robot.decide(world, (), rng).q_values for _ in range(ticks)]


def test_same_stream_same_decisions_other_stream_other_rollouts():
    assert decisions(1) == decisions(1)
    assert decisions(1) != decisions(2)


def test_a_whole_trial_depends_on_the_trial_seed_only():
    runs = [run_trial(LAYOUT, seed, robot=make_robot("fov_aware", LAYOUT, RULES), record=True).actions
            for seed in (4, 4)]
    assert runs[0] == runs[1]
