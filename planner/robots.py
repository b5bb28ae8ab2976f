"""The robot planners by name (docs/domain.md §5): ``make_robot(name, layout, rules, config)``.

``stay`` never moves (practice trials); ``fov_aware``, ``fov_aware_showing``, ``baseline`` and ``no_rollout`` are
the hierarchical QMDP planner with different models of the person and what they value (see :mod:`planner.qmdp`).
"""

from __future__ import annotations

import time
from collections.abc import Sequence

import numpy as np

from planner.decision import Decision, Robot
from planner.events import Event
from planner.geometry import Action
from planner.interning import interned
from planner.kb import KnowledgeBase
from planner.layout import Layout
from planner.planner_config import PlannerConfig
from planner.registry import PLANNER_NAMES
from planner.rules import Rules
from planner.state import WorldState


class StayRobot:
    """A robot that never moves."""

    def reset(self, world: WorldState, kb: KnowledgeBase | None = None) -> None:
        return None

    def decide(self, world: WorldState, events: Sequence[Event], rng: np.random.Generator,
               deadline: float | None = None) -> Decision:
        start = time.perf_counter()
        return Decision(Action.STAY, elapsed_ms=(time.perf_counter() - start) * 1000)


def make_robot(name: str, layout: Layout, rules: Rules, config: PlannerConfig | None = None) -> Robot:
    """A fresh robot policy (a :class:`planner.decision.RobotFactory`). ``config`` is the robot's model of the
    person (``None``: the paper's defaults). Raises ``ValueError`` naming the known planners for an unknown
    name."""
    if name not in PLANNER_NAMES:
        raise ValueError(f"unknown robot planner {name!r}; known: {', '.join(PLANNER_NAMES)}")
    if name == "stay":
        return StayRobot()
    from planner.qmdp import make_qmdp_robot
    return make_qmdp_robot(name, interned(layout), interned(rules), config)
