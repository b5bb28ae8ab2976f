"""The simulated partner: the human model driving the robot's avatar, a :class:`planner.decision.Robot` like
the planners of :mod:`planner.robots`; and the protocol of what plays the human's avatar in a headless trial."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Protocol
import time

import numpy as np

from planner.decision import Decision
from planner.events import Event
from planner.geometry import Action
from planner.human import HumanMemory, HumanModel
from planner.kb import KnowledgeBase, omniscient_kb
from planner.layout import Layout
from planner.rules import Rules
from planner.state import WorldState


class HumanPolicy(Protocol):
    """What plays the human's avatar in a headless trial: :class:`planner.human.HumanModel` (the simulated
    human) or another partner model (e.g. :class:`planner.adversary.AdversarialHuman`)."""

    def act(self, world: WorldState, kb: KnowledgeBase, memory: HumanMemory,
            rng: np.random.Generator) -> tuple[Action, HumanMemory]: ...


class SimulatedPartner:
    """The simulated human's model driving the robot's avatar, seeing everything (a scripted teammate)."""

    def __init__(self, layout: Layout, rules: Rules) -> None:
        self.model = HumanModel(layout, rules, me="robot")
        self.memory = HumanMemory()

    def reset(self, world: WorldState, kb: KnowledgeBase | None = None) -> None:
        self.memory = HumanMemory()

    def act(self, world: WorldState, events: Sequence[Event], rng: np.random.Generator) -> Action:
        action, self.memory = self.model.act(world, omniscient_kb(world), self.memory, rng)
        return action

    def decide(self, world: WorldState, events: Sequence[Event], rng: np.random.Generator,
               deadline: float | None = None) -> Decision:
        start = time.perf_counter()
        action = self.act(world, events, rng)
        return Decision(action, elapsed_ms=(time.perf_counter() - start) * 1000)
