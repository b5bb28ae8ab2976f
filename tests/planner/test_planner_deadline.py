"""A robot whose every decision comes after its deadline still answers a legal action each tick (it scores
at least one subtask and one first move, then stops): found by the server load benchmark, where a worker
busy with other trials hands a planner a request whose deadline has already passed."""

from __future__ import annotations

import time
from collections.abc import Sequence

import numpy as np
import pytest

from planner.decision import Decision
from planner.events import Event
from planner.kb import KnowledgeBase
from planner.planner_config import PlannerConfig
from planner.play import run_trial
from planner.robots import make_robot
from planner.rules import Rules
from planner.state import WorldState
from study_config import load_layout


class AlwaysLate:
    """Passes a deadline one second in the past to every decision."""

    def __init__(self, inner: object) -> None:
        self.inner = inner
        self.timed_out = 0

    def reset(self, world: WorldState, kb: KnowledgeBase | None = None) -> None:
        self.inner.reset(world, kb)  # type: ignore[attr-defined]

    def decide(self, world: WorldState, events: Sequence[Event], rng: np.random.Generator,
               deadline: float | None = None) -> Decision:
        decision: Decision = self.inner.decide(world, events, rng, time.perf_counter() - 1)  # type: ignore[attr-defined]
        self.timed_out += decision.timed_out
        return decision


@pytest.mark.parametrize("kitchen", ["none_3", "mid_2"])
def test_a_planner_always_past_its_deadline_plays_a_whole_trial(kitchen):
    layout = load_layout(kitchen)
    robot = AlwaysLate(make_robot("fov_aware", layout, Rules(), PlannerConfig()))
    result = run_trial(layout, 0, robot=robot)
    assert result.ticks > 0 and robot.timed_out > 0
